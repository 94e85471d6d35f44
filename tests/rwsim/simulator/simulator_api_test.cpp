// Simulator behaviour other than physics accuracy: failures as statuses, ODE's handlers, reset,
// kinematic bodies, motors, engine options, determinism across threads, the outcome table.
#include <ode/ode.h>

#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <stdexcept>
#include <thread>

#include "rwsim/simulator/detail/ode_runtime.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "sim_test_scenes.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::BodyId;
using rwsim::dynamics::DeviceId;
using rwsim::simulator::Simulator;
using rwsim::simulator::SimulatorOptions;
using rwsim::simulator::StepStatus;
using rwsim::trial::GraspOutcome;
using rwsim::trial::kOutcomeTable;
using visgrab::test::sim::SceneBuilder;

Transform3D at(double x, double y, double z) {
  return rw::math::makeTranslation(Vector3D(x, y, z));
}

std::unique_ptr<rwsim::dynamics::DynamicWorkCell> tableAndBox() {
  SceneBuilder scene("api");
  scene.addTable("Table", at(0, 0, -0.05), Vector3D(1, 1, 0.1));
  scene.addBox("Box", at(0, 0, 0.3), Vector3D(0.1, 0.1, 0.1), 1.0);
  return scene.build();
}

TEST(SimulatorApi, RunawayBodyIsAStatusNotACrash) {
  const auto dwc = tableAndBox();
  SimulatorOptions options;
  options.escapeDistance = 0.05;
  Simulator sim(*dwc, options);
  StepStatus s = StepStatus::kOk;
  while (s == StepStatus::kOk && sim.time() < 1.0) s = sim.step();
  EXPECT_EQ(s, StepStatus::kRunaway);
  EXPECT_NE(sim.failureDetail().find("Box"), std::string::npos) << sim.failureDetail();
  const double t = sim.time();
  EXPECT_EQ(sim.step(), StepStatus::kRunaway);  // sticky until reset
  EXPECT_EQ(sim.time(), t);
  sim.reset(dwc->workcell().defaultState());
  EXPECT_EQ(sim.time(), 0.0);
  EXPECT_EQ(sim.step(), StepStatus::kOk);
  EXPECT_TRUE(sim.failureDetail().empty());
}

TEST(SimulatorApi, TooFastBodyIsRunaway) {
  const auto dwc = tableAndBox();
  SimulatorOptions options;
  options.maxSpeed = 1.0;  // the box reaches 1 m/s after ~0.1 s of falling
  Simulator sim(*dwc, options);
  StepStatus s = StepStatus::kOk;
  while (s == StepStatus::kOk && sim.time() < 1.0) s = sim.step();
  EXPECT_EQ(s, StepStatus::kRunaway);
  EXPECT_NEAR(sim.time(), 0.1, 0.02);
}

TEST(SimulatorApi, NonFiniteStateIsNumericalFailure) {
  SceneBuilder scene("nan");
  scene.addGripper(Transform3D::Identity(), 0.05, 10.0);
  const auto dwc = scene.build();
  Simulator sim(*dwc);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  sim.setKinematicVelocity(BodyId(0), Vector3D(nan, 0, 0), Vector3D::Zero());
  EXPECT_EQ(sim.step(), StepStatus::kNumericalFailure);
  EXPECT_NE(sim.failureDetail().find("Gripper.Base"), std::string::npos) << sim.failureDetail();
  // Caught before ODE sees it (ODE's own assertions would otherwise fire inside the step); a
  // reset world, like any other, simulates again.
  sim.reset(dwc->workcell().defaultState());
  EXPECT_EQ(sim.step(), StepStatus::kOk) << sim.failureDetail();
  Simulator other(*dwc);
  EXPECT_EQ(other.step(), StepStatus::kOk) << other.failureDetail();
}

TEST(SimulatorApi, OdeErrorHandlersThrowInsteadOfAborting) {
  rwsim::simulator::detail::prepareOdeForThisThread();
  EXPECT_THROW(dDebug(7, "internal %s", "oops"), rwsim::simulator::detail::OdeFatalError);
  EXPECT_THROW(dError(8, "error %d", 8), rwsim::simulator::detail::OdeFatalError);
  rwsim::simulator::detail::takeOdeMessages();
  dMessage(3, "LCP %s", "warning");
  const std::string m = rwsim::simulator::detail::takeOdeMessages();
  EXPECT_NE(m.find("LCP warning"), std::string::npos) << m;
  EXPECT_TRUE(rwsim::simulator::detail::takeOdeMessages().empty());
}

TEST(SimulatorApi, KinematicBodyFollowsItsVelocity) {
  SceneBuilder scene("kinematic");
  scene.addGripper(at(0, 0, 1), 0.05, 10.0);
  const auto dwc = scene.build();
  Simulator sim(*dwc);
  const auto base = dwc->findBody("Gripper.Base");
  sim.setKinematicVelocity(base, Vector3D(0, 0, 0.1), Vector3D(0, 0, 0.5));
  while (sim.time() < 1.0 - 1e-9) ASSERT_EQ(sim.step(), StepStatus::kOk);
  const Transform3D X = sim.bodyPose(base);
  EXPECT_NEAR(X.translation().z(), 1.1, 1e-9);
  EXPECT_NEAR(Eigen::AngleAxisd(X.linear()).angle(), 0.5, 1e-6);
  // The jaws ride along on their motors (held at q = 0 against gravity).
  const auto left = dwc->findBody("Gripper.Left");
  EXPECT_NEAR(sim.bodyPose(left).translation().z(), 1.1, 1e-3);
  EXPECT_LT(sim.jointPositions(DeviceId(0)).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_THROW(sim.setKinematicVelocity(left, Vector3D::Zero(), Vector3D::Zero()),
               std::invalid_argument);
}

TEST(SimulatorApi, MotorsTrackVelocityAndRespectLimits) {
  SceneBuilder scene("motors");
  scene.addGripper(Transform3D::Identity(), 0.05, 10.0);
  const auto dwc = scene.build(0.0);
  Simulator sim(*dwc);
  sim.setMotorVelocityTargets(DeviceId(0), Eigen::Vector2d(0.02, -0.01));
  while (sim.time() < 0.5 - 1e-9) ASSERT_EQ(sim.step(), StepStatus::kOk);
  const auto q = sim.jointPositions(DeviceId(0));
  EXPECT_NEAR(q[0], 0.01, 1e-4);
  EXPECT_NEAR(q[1], 0.0, 1e-3);  // the lower stop at 0 holds
  EXPECT_NEAR(sim.jointVelocities(DeviceId(0))[0], 0.02, 1e-4);
  const auto left = dwc->findBody("Gripper.Left");
  EXPECT_NEAR(sim.bodyPose(left).translation().y(), -0.04, 1e-4);
  // The state carries the joint values.
  const auto& device = *dwc->devices()[0].device;
  EXPECT_NEAR(device.getQ(sim.state())[0], q[0], 1e-12);
  EXPECT_THROW(sim.setMotorVelocityTargets(DeviceId(0), Eigen::VectorXd::Zero(3)),
               std::invalid_argument);
  EXPECT_THROW(sim.setMotorForceLimits(DeviceId(0), Eigen::Vector2d(1.0, -1.0)),
               std::invalid_argument);
  EXPECT_THROW(sim.jointPositions(DeviceId(5)), std::out_of_range);
  EXPECT_THROW(sim.jointPositions(DeviceId::none()), std::out_of_range);
  EXPECT_THROW(sim.bodyPose(BodyId::none()), std::out_of_range);
  try {
    sim.bodyLinearVelocity(BodyId(99));
    ADD_FAILURE() << "no exception for body 99";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "Simulator: no body 99");
  }
}

TEST(SimulatorApi, ForceLimitsBoundTheMotors) {
  SceneBuilder scene("weak");
  scene.addGripper(Transform3D::Identity(), 0.05, 10.0);
  const auto dwc = scene.build(0.0);
  Simulator sim(*dwc);
  sim.setMotorForceLimits(DeviceId(0), Eigen::Vector2d(0.01, 100.0));
  sim.setMotorVelocityTargets(DeviceId(0), Eigen::Vector2d(1.0, 1.0));
  sim.step();
  // 0.01 N on 0.1 kg for one 5 ms step: 0.0005 m/s; 100 N could give 5 m/s, so the strong jaw
  // reaches its 1 m/s target at once (both start on their lower stops).
  EXPECT_NEAR(sim.jointVelocities(DeviceId(0))[0], 0.0005, 1e-5);
  EXPECT_NEAR(sim.jointVelocities(DeviceId(0))[1], 1.0, 1e-5);
  sim.setMotorForceLimits(DeviceId(0), Eigen::Vector2d(10.0, 10.0));
  sim.setMotorVelocityTargets(DeviceId(0), Eigen::Vector2d(0.0, 0.0));
  sim.step();
  EXPECT_NEAR(sim.jointVelocities(DeviceId(0))[0], 0.0, 1e-6);
  EXPECT_NEAR(sim.jointVelocities(DeviceId(0))[1], 0.5, 1e-5);  // 10 N stop 0.5 m/s per step
}

TEST(SimulatorApi, LastStepRowsCountJointsMotorsAndContacts) {
  // Two prismatic jaws, each 5 rows of a slider and 1 of its motor; nothing touches.
  SceneBuilder gripper("rows");
  gripper.addGripper(at(0, 0, 1), 0.05, 10.0);
  const auto gripperCell = gripper.build();
  Simulator jaws(*gripperCell);
  EXPECT_EQ(jaws.lastStepRows(), 0U);
  ASSERT_EQ(jaws.step(), StepStatus::kOk);
  EXPECT_EQ(jaws.lastStepRows(), 12U);
  // Without force limits the jaws still sit on their lower stops (q = 0): a stop row each.
  jaws.setMotorForceLimits(DeviceId(0), Eigen::Vector2d(0.0, 0.0));
  ASSERT_EQ(jaws.step(), StepStatus::kOk);
  EXPECT_EQ(jaws.lastStepRows(), 12U);
  // A hinge without stops: 5 rows, and 1 for its motor while it has a force limit.
  SceneBuilder finger("hinge");
  finger.addFinger(Transform3D::Identity(), 0.1, 10.0, false);
  const auto fingerCell = finger.build(0.0);
  Simulator hinge(*fingerCell);
  ASSERT_EQ(hinge.step(), StepStatus::kOk);
  EXPECT_EQ(hinge.lastStepRows(), 6U);
  hinge.setMotorForceLimits(DeviceId(0), Eigen::VectorXd::Zero(1));
  ASSERT_EQ(hinge.step(), StepStatus::kOk);
  EXPECT_EQ(hinge.lastStepRows(), 5U);
  hinge.reset(fingerCell->workcell().defaultState());
  EXPECT_EQ(hinge.lastStepRows(), 0U);

  // A box resting on a table: one face-on-face manifold of 4 points, 3 rows each (a normal and
  // two friction directions).
  SceneBuilder resting("resting");
  resting.addTable("Table", at(0, 0, -0.05), Vector3D(1, 1, 0.1));
  resting.addBox("Box", at(0, 0, 0.05), Vector3D(0.1, 0.1, 0.1), 1.0);
  const auto restingCell = resting.build();
  Simulator box(*restingCell);
  ASSERT_EQ(box.step(), StepStatus::kOk);
  ASSERT_EQ(box.contacts().size(), 1U);
  EXPECT_EQ(box.contacts()[0].points.size(), 4U);
  EXPECT_EQ(box.lastStepRows(), 12U);
}

TEST(SimulatorApi, RevoluteJointValuesDoNotWrapAtPi) {
  SceneBuilder scene("spin");
  scene.addFinger(Transform3D::Identity(), 0.1, 10.0, false);
  const auto dwc = scene.build(0.0);
  Simulator sim(*dwc);
  sim.setMotorVelocityTargets(DeviceId(0), Eigen::VectorXd::Constant(1, 2.0));
  while (sim.time() < 3.0 - 1e-9) ASSERT_EQ(sim.step(), StepStatus::kOk);
  EXPECT_NEAR(sim.jointPositions(DeviceId(0))[0], 6.0, 1e-3);  // past pi and 2 pi
  EXPECT_NEAR(dwc->devices()[0].device->getQ(sim.state())[0], 6.0, 1e-3);
}

std::vector<double> runSlide() {
  SceneBuilder scene("determinism", 0.3);
  const Transform3D X(Eigen::AngleAxisd(0.35, Vector3D(1, 2, 0).normalized()));
  scene.addTable("Slope", X * at(0, 0, -0.05), Vector3D(2, 2, 0.1));
  scene.addBox("A", X * at(0, 0, 0.03), Vector3D(0.1, 0.06, 0.05), 0.5);
  scene.addBox("B", X * at(0.2, 0.05, 0.3), Vector3D(0.05, 0.05, 0.05), 0.2);
  const auto dwc = scene.build();
  Simulator sim(*dwc);
  std::vector<double> out;
  while (sim.time() < 1.0 - 1e-9) {
    if (sim.step() != StepStatus::kOk) break;
  }
  for (std::size_t b = 0; b < 3; ++b) {
    const Transform3D p = sim.bodyPose(BodyId(b));
    out.insert(out.end(), p.data(), p.data() + 16);
  }
  return out;
}

TEST(SimulatorApi, DeterministicAcrossRunsAndThreads) {
  const std::vector<double> reference = runSlide();
  EXPECT_EQ(runSlide(), reference);
  // Parallel worlds once shared ODE's global threading object and mixed their islands up now
  // and then: repeat the concurrent runs.
  for (int round = 0; round < 10; ++round) {
    std::vector<double> a;
    std::vector<double> b;
    std::thread ta([&] { a = runSlide(); });
    std::thread tb([&] { b = runSlide(); });
    ta.join();
    tb.join();
    EXPECT_EQ(a, reference) << "round " << round;
    EXPECT_EQ(b, reference) << "round " << round;
  }
}

TEST(EngineOptions, RobWorkKeysAreMapped) {
  auto dwc = tableAndBox();
  dwc->setEngineProperty("StepMethod", "WorldQuickStep");
  dwc->setEngineProperty("WorldCFM", "1e-4");
  dwc->setEngineProperty("WorldERP", " 0.3 ");
  dwc->setEngineProperty("ContactSurfaceLayer", "0.0004");
  dwc->setEngineProperty("MaxSepDistance", "0.001");
  dwc->setEngineProperty("MaxCorrectingVelocity", "0.2");
  dwc->setEngineProperty("SpaceType", "Simple");
  const SimulatorOptions o = rwsim::simulator::optionsFromEngineProperties(*dwc);
  EXPECT_EQ(o.stepMethod, "WorldQuickStep");
  EXPECT_DOUBLE_EQ(o.worldCfm, 1e-4);
  EXPECT_DOUBLE_EQ(o.worldErp, 0.3);
  EXPECT_DOUBLE_EQ(o.contactSurfaceLayer, 0.0004);
  EXPECT_DOUBLE_EQ(o.contacts.margin, 0.001);
  EXPECT_DOUBLE_EQ(o.maxCorrectingVelocity, 0.2);
  dwc->setEngineProperty("StepMethod", "WorldFast1");
  EXPECT_EQ(rwsim::simulator::optionsFromEngineProperties(*dwc).stepMethod, "WorldStep");
  // QuickStep runs too.
  Simulator sim(*dwc, rwsim::simulator::optionsFromEngineProperties(*dwc));
  EXPECT_EQ(sim.step(), StepStatus::kOk);
}

TEST(EngineOptions, BadValuesAreRejected) {
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"StepMethod", "Euler"},
                                                        {"WorldCFM", "abc"},
                                                        {"WorldERP", "1.5"},
                                                        {"ContactSurfaceLayer", "-1"},
                                                        {"MaxCorrectingVelocity", "0"},
                                                        {"MaxSepDistance", "1e-3x"}}) {
    auto dwc = tableAndBox();
    dwc->setEngineProperty(key, value);
    try {
      rwsim::simulator::optionsFromEngineProperties(*dwc);
      ADD_FAILURE() << key << " = " << value << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

TEST(GraspOutcomeTable, NamesAndRobWorkCodes) {
  const std::vector<std::tuple<GraspOutcome, std::string, int>> expected = {
      {GraspOutcome::kStable, "stable", 1},
      {GraspOutcome::kSlipped, "slipped", 5},
      {GraspOutcome::kDropped, "dropped", 4},
      {GraspOutcome::kMissed, "missed", 3},
      {GraspOutcome::kInCollision, "in_collision", 2},
      {GraspOutcome::kInvalidContacts, "invalid_contacts", 8},
      {GraspOutcome::kSimulationFailure, "simulation_failure", 7},
      {GraspOutcome::kTimeout, "timeout", 6}};
  ASSERT_EQ(expected.size(), kOutcomeTable.size());
  std::set<std::string_view> names;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const auto& [outcome, name, code] = expected[i];
    EXPECT_EQ(kOutcomeTable[i].outcome, outcome);
    EXPECT_EQ(rwsim::trial::outcomeName(outcome), name);
    EXPECT_EQ(rwsim::trial::robworkCode(outcome), code);
    EXPECT_EQ(rwsim::trial::outcomeFromName(name), outcome);
    names.insert(kOutcomeTable[i].name);
  }
  EXPECT_EQ(names.size(), kOutcomeTable.size());
  EXPECT_FALSE(rwsim::trial::outcomeFromName("success").has_value());
}

}  // namespace
