#pragma once

#include <optional>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/detail/wc_description.hpp"
#include "rw/models/parallel_kinematics.hpp"

namespace rw::loaders::detail {

/// The legs and junctions of a ParallelDevice, as RobWork's loader makes them: the device's
/// frames, in document order, are split into serial chains where a frame does not hang on the
/// previous one, where a later frame also hangs on the previous one, or where the SerialChain
/// scope changes; each chain is named after its last SerialChain. Each `<Junction>` joins the
/// named chains of every `<Chains>` into one leg (no Junction: one junction of all chains).
/// `ids` maps WorkCellDesc::frames to the frames already created in `tree`. Problems are
/// reported at their elements; returns nullopt after an error.
std::optional<rw::models::ParallelStructure> buildParallelStructure(
    const WorkCellDesc& desc, const DeviceDesc& device,
    const std::vector<rw::kinematics::FrameId>& ids, const rw::kinematics::FrameTree& tree,
    common::DiagnosticSink& sink);

}  // namespace rw::loaders::detail
