#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/request/grasp_request.hpp"

/// Grasps on the shared test database for the shard, merge and Slurm tests.
namespace visgrab::test {

/// `perScene` SDH cylinder grasps (pre-shape SDH_CYL) from above around the first object of each
/// scene in `sceneIds` (scenes of the shared test database), method `method`, ids g0, g1, ...
std::vector<grasp::GraspRequest> cylinderGrasps(const std::vector<std::string_view>& sceneIds,
                                                int perScene, const std::string& method);

/// The SDH's grasp description in the source tree.
std::filesystem::path sdhHandFile();

}  // namespace visgrab::test
