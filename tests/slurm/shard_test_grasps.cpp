#include "shard_test_grasps.hpp"

#include <cmath>
#include <numbers>

#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"

namespace visgrab::test {

std::vector<grasp::GraspRequest> cylinderGrasps(const std::vector<std::string_view>& sceneIds,
                                                int perScene, const std::string& method) {
  using rw::math::Vector3D;
  std::vector<grasp::GraspRequest> out;
  for (const std::string_view id : sceneIds) {
    const auto& poses = testDatabase().groundTruth(id);
    Vector3D base = Vector3D::Zero();
    if (!poses.empty()) base = poses.front().X_WO.translation();
    for (int k = 0; k < perScene; ++k) {
      const double a = k * 2.0 * std::numbers::pi / perScene;
      grasp::GraspRequest r;
      r.sceneId = std::string(id);
      r.id = "g" + std::to_string(k);
      r.method = method;
      r.kind = grasp::GraspKind::kPreshape;
      r.preshape = "SDH_CYL";
      r.X_W_tcp =
          rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0),
                                 base + Vector3D(0.02 * std::cos(a), 0.02 * std::sin(a), 0.06));
      out.push_back(r);
    }
  }
  return out;
}

std::filesystem::path sdhHandFile() { return sourceDir() / "scenes/hands/sdh/sdh.grasp.xml"; }

}  // namespace visgrab::test
