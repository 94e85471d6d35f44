#pragma once

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/detail/wc_description.hpp"
#include "rw/models/setups.hpp"
#include "rw/models/workcell.hpp"

namespace rw::loaders::detail {

/// Reads the CollisionSetup (old format, reference §1.7) and ProximitySetup (§1.8) files named
/// in the description and stores the merged setups in `wc` exactly as RobWork's loader does
/// (§1.5 steps 6-7): collision setups merged with their scope prefix; RobWork's default exclude
/// list when the workcell names no setup file at all; the proximity setup starts from the
/// collision setup's pairs as Exclude rules (useIncludeAll true, useExcludeStaticPairs from
/// <ExcludeStaticPairs/>) and appends every ProximitySetup file's rules, patterns prefixed with
/// the scope. The files' own UseIncludeAll/UseExcludeStaticPairs are not merged (as in RobWork).
void buildSetups(rw::models::WorkCell& wc, const WorkCellDesc& desc, common::XmlReader& reader,
                 common::DiagnosticSink& sink);

/// RobWork's default collision setup (reference §1.5.6): every pair (B, A) where B's parent P
/// is not WORLD and A is a child of P's parent (so A = P, or a sibling of P). Frames that are
/// dynamically attachable are left out with their subtrees, as RobWork only walks static
/// children. Names are full frame names; the pair is (B, A).
rw::models::CollisionSetup defaultCollisionSetup(const rw::kinematics::FrameTree& frames);

}  // namespace rw::loaders::detail
