#pragma once

#include <memory>

#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "sim_test_scenes.hpp"

/// The two-jaw gripper's grasp trial on a box standing on a table, built in code: the scene, the
/// trial's set-up and the grasp, shared by the grasp-trial and trial-protocol tests.
namespace visgrab::test::sim {

/// The translation to (x, y, z).
inline rw::math::Transform3D at(double x, double y, double z) {
  return rw::math::makeTranslation(rw::math::Vector3D(x, y, z));
}

/// A box "Box" (0.06 x 0.06 x 0.1 m, 0.2 kg) standing at the origin on a table "Table" (1 x 1 m,
/// top at z = 0) and the two-jaw gripper (SceneBuilder::addGripper: gap 0.05, force limit 20 N)
/// parked at (0.5, 0.5, 0.5), away from both; the trial places it.
inline std::unique_ptr<rwsim::dynamics::DynamicWorkCell> gripperScene() {
  SceneBuilder scene("gripper");
  scene.addTable("Table", at(0, 0, -0.05), rw::math::Vector3D(1, 1, 0.1));
  scene.addBox("Box", at(0, 0, 0.05), rw::math::Vector3D(0.06, 0.06, 0.1), 0.2);
  // Jaw faces at |y| = 0.04 when open; the gripper is parked away and placed by the trial.
  scene.addGripper(at(0.5, 0.5, 0.5), 0.05, 20.0);
  return scene.build();
}

/// The trial set-up of gripperScene()'s hand "Gripper"; the rest default (the lift protocol).
inline rwsim::simulator::GraspTrialSetup gripperSetup() {
  rwsim::simulator::GraspTrialSetup setup;
  setup.hand = "Gripper";
  return setup;
}

/// The gripper's grasp with its TCP at `X_W_tcp`: open at q = (0, 0), closing towards
/// (0.04, 0.04), where the jaws' faces meet.
inline rwsim::simulator::GraspParameters gripperGrasp(const rw::math::Transform3D& X_W_tcp) {
  rwsim::simulator::GraspParameters g;
  g.X_W_tcp = X_W_tcp;  // TCP = the base frame: the jaws' centre
  g.qOpen = rw::math::Q::Zero(2);
  g.qClosed = rw::math::Q::Constant(2, 0.04);
  return g;
}

}  // namespace visgrab::test::sim
