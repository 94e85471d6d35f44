#pragma once

// The SDH box trial shared by the simulator benchmark, the MuJoCo comparison and its test: the
// simulator tests' scene (tests/rwsim/simulator/data/sdh_box.dwc.xml: the project's SDH over a
// 6 x 6 x 10 cm box on a table) and VisGraB's SDH_CYL pre-shape with the hand pointing down at
// the box centre.

#include <memory>
#include <numbers>
#include <string>

#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"

namespace visgrab::bench {

/// The scene, loaded once.
inline const rwsim::dynamics::DynamicWorkCell& sdhBoxScene() {
  static const auto dwc = rwsim::loaders::loadDynamicWorkCell(
      std::string(VISGRAB_SOURCE_DIR) + "/tests/rwsim/simulator/data/sdh_box.dwc.xml");
  return *dwc;
}

/// SDH_CYL over the box centre shifted by `x` (m) along the world x axis, the SDH's torque limits.
inline rwsim::simulator::GraspParameters sdhCylinderGrasp(double x) {
  using rw::math::Q;
  rwsim::simulator::GraspParameters g;
  g.X_W_tcp = rw::math::rpyTransform(rw::math::Vector3D(0, std::numbers::pi, 0),
                                     rw::math::Vector3D(x, 0, 0.05));
  g.qOpen = Q(7);
  g.qOpen << -1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174;
  g.qClosed = Q(7);
  g.qClosed << 0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349;
  g.tauMax = Q(7);
  g.tauMax << 2.1, 1.4, 2.1, 1.05, 0.7, 1.05, 0.7;
  return g;
}

}  // namespace visgrab::bench
