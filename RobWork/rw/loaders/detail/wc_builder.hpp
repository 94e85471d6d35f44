#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/loaders/detail/wc_description.hpp"
#include "rw/models/workcell.hpp"

namespace rw::loaders::detail {

/// Second pass: builds the WorkCell from a description. Resolves every name (refframes, Depend
/// owners, refjoints, model frames) with a close-name hint on failure, orders the frames
/// parent-first (reporting cycles), creates frames, devices, the default state, geometry and
/// the setups. `setupReader` parses the CollisionSetup/ProximitySetup files; `fileName` is the
/// absolute name stored in the workcell. Returns nullptr if the model could not be made; errors
/// after that point (meshes, setup files) are in `sink` with a workcell returned.
std::unique_ptr<rw::models::WorkCell> buildWorkCell(const WorkCellDesc& desc,
                                                    common::XmlReader& setupReader,
                                                    const std::string& fileName,
                                                    common::DiagnosticSink& sink);

/// "; did you mean \"X\"?" for the candidate closest to `wanted`, or an empty string if none is
/// close (edit distance, with a bonus for the same last name component).
std::string suggestName(std::string_view wanted, const std::vector<std::string>& candidates);

}  // namespace rw::loaders::detail
