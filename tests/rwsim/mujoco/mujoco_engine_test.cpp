// The MuJoCo engine against analytic physics and the physics seam's contract (free fall, a box at
// rest, reset, a torque-limited velocity servo, a kinematic base at any pose, scaled friction and
// object masses), and the SDH box trial through the one protocol, GraspTrial, on both engines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/mujoco/mujoco_engine.hpp"
#include "rwsim/simulator/engine_steps.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/simulator/sim_test_scenes.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::BodyId;
using rwsim::trial::PhysicsEngine;
using rwsim::trial::StepStatus;
using visgrab::test::sim::kG;
using visgrab::test::sim::SceneBuilder;

Transform3D at(double x, double y, double z) {
  return rw::math::makeTranslation(Vector3D(x, y, z));
}

using visgrab::test::sim::forceOn;
using visgrab::test::sim::runUntil;

TEST(MujocoEngine, FactoryNamesItselfAndItsSettings) {
  SceneBuilder scene("names");
  scene.addBox("Box", at(0, 0, 1), Vector3D(0.1, 0.1, 0.1), 1.0);
  const auto dwc = scene.build();
  const auto factory = rwsim::mujoco::mujocoEngineFactory(*dwc);
  EXPECT_EQ(factory->name(), "mujoco");
  const std::string settings = factory->settings();
  for (const char* part :
       {"MuJoCo 2.2.2", "step 0.002 s", "Newton", "implicit", "elliptic cone impratio 10",
        "solref 0.004 1", "motor kv 2", "prismatic motor kv 1000 armature 2"}) {
    EXPECT_NE(settings.find(part), std::string::npos) << part << " in " << settings;
  }
}

TEST(MujocoEngine, FreeFallFollowsGravity) {
  SceneBuilder scene("fall");
  scene.addBox("Box", at(0.1, 0.2, 1.0), Vector3D(0.1, 0.1, 0.1), 1.0);
  const auto dwc = scene.build();
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*dwc)->create();
  const BodyId box = dwc->findBody("Box");
  const double dt = engine->timeStep();
  EXPECT_DOUBLE_EQ(dt, 0.002);
  runUntil(*engine, 0.5);
  const double t = engine->time();
  const auto n = static_cast<double>(std::lround(t / dt));
  const double z = engine->bodyPose(box).translation().z();
  // Semi-implicit Euler: v_n = -g n dt, z_n = z0 - g dt^2 n (n + 1) / 2 exactly ...
  EXPECT_NEAR(z, 1.0 - kG * dt * dt * n * (n + 1) / 2, 1e-9);
  // ... which is z0 - g t^2 / 2 up to g dt t / 2.
  EXPECT_NEAR(z, 1.0 - kG * t * t / 2, kG * dt * t / 2 + 1e-9);
  EXPECT_NEAR(engine->bodyLinearVelocity(box).z(), -kG * t, 1e-9);
  EXPECT_NEAR(engine->bodyPose(box).translation().x(), 0.1, 1e-12);
  EXPECT_TRUE(engine->contacts().empty());
}

TEST(MujocoEngine, BoxRestsOnTableWithItsWeightAsContactForce) {
  SceneBuilder scene("rest");
  scene.addTable("Table", at(0, 0, -0.05), Vector3D(1, 1, 0.1));
  scene.addBox("Box", at(0, 0, 0.05), Vector3D(0.1, 0.1, 0.1), 1.0);
  const auto dwc = scene.build();
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*dwc)->create();
  const BodyId box = dwc->findBody("Box");
  runUntil(*engine, 1.0);
  EXPECT_NEAR(engine->bodyPose(box).translation().z(), 0.05, 1e-3);  // soft contact: sub-mm
  EXPECT_NEAR(engine->bodyPose(box).translation().head<2>().norm(), 0.0, 1e-6);
  EXPECT_LT(engine->bodyLinearVelocity(box).norm(), 1e-3);
  // The table pushes the box up with its weight; each point's normal points from A to B.
  const Vector3D f = forceOn(*engine, box);
  EXPECT_NEAR(f.z(), 1.0 * kG, 0.01 * kG);
  EXPECT_NEAR(f.head<2>().norm(), 0.0, 1e-3);
  ASSERT_EQ(engine->contacts().size(), 1u);
  const auto& pair = engine->contacts().front();
  const double up = pair.bodyB == box ? 1.0 : -1.0;
  for (const auto& p : pair.points) {
    EXPECT_NEAR(p.point.normal.z(), up, 1e-9);
    EXPECT_GT(up * p.force.z(), 0.0);
    EXPECT_NEAR(p.point.position.z(), 0.0, 1e-3);
  }
  // The state follows the bodies.
  const auto& frame = dwc->workcell().frames().frame(dwc->body(box).frame);
  EXPECT_TRANSFORM_NEAR(frame.movableTransform(engine->state()), engine->bodyPose(box), 1e-12);
}

// A one-joint finger (hinge about world +y, positive q turns the tip down; 0.1 kg link of length
// `lever` with its COG at lever / 2) above nothing.
struct FingerScene {
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc;
  rwsim::dynamics::DeviceId finger;
};

FingerScene fingerScene(double lever, double torque) {
  SceneBuilder scene("finger");
  scene.addFinger(at(0, 0, 0.5), lever, torque);
  FingerScene out;
  out.dwc = scene.build();
  out.finger = out.dwc->findDevice("Finger");
  return out;
}

TEST(MujocoEngine, ServoHoldsItsTargetVelocityUpToTheLoadOverItsGain) {
  const double lever = 0.1;
  const FingerScene s = fingerScene(lever, 1.0);  // generous limit: gravity needs 0.049 N m
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*s.dwc)->create();
  engine->setMotorVelocityTargets(s.finger, Q::Constant(1, -0.5));  // lift the tip
  runUntil(*engine, 0.3);
  // Steady state of torque = kv (target - v) against gravity's m g (l / 2) cos q.
  const double q = engine->jointPositions(s.finger)[0];
  const double gravity = 0.1 * kG * lever / 2 * std::cos(q);
  EXPECT_NEAR(engine->jointVelocities(s.finger)[0], -0.5 + gravity / 2.0, 1e-3);
  EXPECT_LT(q, -0.1);
}

TEST(MujocoEngine, ASmallForceLimitStallsTheServoAgainstGravity) {
  const double lever = 0.1;
  const double limit = 0.02;  // below gravity's 0.1 kg * g * 0.05 m = 0.049 N m
  const FingerScene s = fingerScene(lever, limit);
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*s.dwc)->create();
  engine->setMotorVelocityTargets(s.finger, Q::Constant(1, -1.0));
  runUntil(*engine, 0.02);
  // The servo pushes up with its limit but the tip falls: q'' = (m g l / 2 - limit) / I', I of a
  // 0.1 x 0.01 x 0.01 box about its end, plus the joint's armature. The implicit integrator keeps
  // the servo's velocity feedback (-kv) in the step even while the force is clipped, so the joint
  // responds as if its inertia were I + armature + kv dt (MujocoEngine's documented model
  // difference).
  const rwsim::mujoco::MujocoOptions options;
  const double dt = engine->timeStep();
  const double inertia = 0.1 * (lever * lever + 0.01 * 0.01) / 12 +
                         0.1 * (lever / 2) * (lever / 2) + options.motorArmature;
  const double accel = (0.1 * kG * lever / 2 - limit) / (inertia + options.motorGain * dt);
  const auto n = static_cast<double>(std::lround(engine->time() / dt));
  const double expected = accel * dt * dt * n * (n + 1) / 2;  // semi-implicit Euler
  EXPECT_NEAR(engine->jointPositions(s.finger)[0], expected, 0.02 * expected);
  EXPECT_GT(engine->jointVelocities(s.finger)[0], 0.0);
  // Raising the limit per engine lifts it.
  engine->setMotorForceLimits(s.finger, Q::Constant(1, 1.0));
  runUntil(*engine, 0.5);
  EXPECT_LT(engine->jointVelocities(s.finger)[0], -0.9);
}

// A servo that pushes a finger into a fixed block with its full force comes to rest, as the
// project's velocity motor does: the trial's closing ends on that rest (0.01 rad/s for 0.1 s).
// Without the joint's armature (MujocoOptions::motorArmature) the contact forces were computed
// for the bare link while the implicit step moved it as a heavier one, and the tip kept bouncing.
TEST(MujocoEngine, AFingerPressedOnABlockComesToRest) {
  SceneBuilder scene("press");
  const double lever = 0.1;
  scene.addFinger(at(0, 0, 0.5), lever, 2.1);
  // A fixed block whose top the tip meets at q of about 0.58 rad. (The exporter gives a fixed box
  // with a face straight up that face's plane, unbounded, for its pairs with boxes: it must lie
  // below the rod, which hangs 5 mm below the tip's lowest point at q = 0.)
  scene.addTable("Block", at(0.085, 0, 0.445 - 0.01), Vector3D(0.03, 0.04, 0.02));
  const auto dwc = scene.build();
  const auto finger = dwc->findDevice("Finger");
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*dwc)->create();
  engine->setMotorVelocityTargets(finger, Q::Constant(1, 1.0));  // down, saturating at 2.1 N m
  runUntil(*engine, 1.0);
  double fastest = 0.0;
  while (engine->time() < 1.1) {
    runUntil(*engine, engine->time() + engine->timeStep());
    fastest = std::max(fastest, std::abs(engine->jointVelocities(finger)[0]));
  }
  EXPECT_LT(fastest, 0.01);
  // Resting on the block, pressing on it.
  const double q = engine->jointPositions(finger)[0];
  EXPECT_GT(q, 0.5);
  EXPECT_LT(q, 0.7);
  EXPECT_LT(forceOn(*engine, dwc->findBody("Block")).z(), -10.0);
}

// A prismatic two-jaw gripper (SceneBuilder::addGripper: kinematic base, jaws 0.1 kg, faces at
// |y| = 0.04 - q) closes on a 0.5 kg box 0.04 m wide standing on the table and lifts it. Each jaw
// is commanded 0.2 m/s, what the trial's PD (P 10/s) commands a jaw stopped 0.02 m short of its
// closing target, with a force limit of 20 N. The project's velocity constraint pushes with its
// limit for any speed error, and so must the servo: at rest the table-free box is squeezed by
// 20 N from each side and carried by friction, mu 0.6 (Finger-Object): it needs 2 mu N >= m g,
// N >= 4.1 N. With the revolute gain (2) in N s/m a stopped jaw pushed with 2 * 0.2 = 0.4 N and
// the box stayed on the table (every Franka and PG70 grasp was dropped).
TEST(MujocoEngine, APrismaticGripperSqueezesWithItsForceLimitAndLiftsTheBox) {
  SceneBuilder scene("jaws");
  scene.addTable("Table", at(0, 0, -0.05), Vector3D(1, 1, 0.1));
  const double mass = 0.5;
  scene.addBox("Box", at(0, 0, 0.1), Vector3D(0.04, 0.04, 0.2), mass);
  // Jaw plates span z 0.10..0.20 (clear of the table), the housing z 0.24..0.26 (above the box).
  scene.addGripper(at(0, 0, 0.15), 0.05, 20.0);
  const auto dwc = scene.build();
  const auto gripper = dwc->findDevice("Gripper");
  const BodyId box = dwc->findBody("Box");
  const BodyId base = dwc->findBody("Gripper.Base");
  const BodyId left = dwc->findBody("Gripper.Left");
  const BodyId right = dwc->findBody("Gripper.Right");
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*dwc)->create();
  engine->setMotorVelocityTargets(gripper, Q::Constant(2, 0.2));
  runUntil(*engine, 0.5);
  // The jaws rest on the box's faces (q = 0.02, less the soft contacts' sub-mm overlap).
  const Q q = engine->jointPositions(gripper);
  for (Eigen::Index i = 0; i < 2; ++i) {
    EXPECT_NEAR(q[i], 0.02, 1e-3);
    EXPECT_LT(std::abs(engine->jointVelocities(gripper)[i]), 0.001);  // the trial's rest speed
  }
  // Each jaw's push on the box along the closing axis is its force limit.
  const auto pushOf = [&](BodyId jaw) {
    Vector3D f = Vector3D::Zero();
    for (const auto& bc : engine->contacts()) {
      if (bc.bodyA != jaw && bc.bodyB != jaw) continue;
      if (bc.bodyA != box && bc.bodyB != box) continue;
      for (const auto& p : bc.points) f += bc.bodyB == box ? p.force : Vector3D(-p.force);
    }
    return f;
  };
  // The squeeze (the mean of the two pushes along the closing axis; the left jaw pushes towards
  // +y) is the force limit. The table's friction takes up a difference of about 1.6 N while the
  // box creeps sideways (below 0.1 mm/s).
  EXPECT_NEAR((pushOf(left).y() - pushOf(right).y()) / 2, 20.0, 0.2);
  // Lift by 0.1 m at 0.1 m/s, then hold still: the box goes up with the hand.
  engine->setKinematicVelocity(base, Vector3D(0, 0, 0.1), Vector3D::Zero());
  runUntil(*engine, 1.5);
  engine->setKinematicVelocity(base, Vector3D::Zero(), Vector3D::Zero());
  runUntil(*engine, 2.0);
  const double lifted = engine->bodyPose(base).translation().z() - 0.15;
  EXPECT_NEAR(lifted, 0.1, 1e-3);
  EXPECT_NEAR(engine->bodyPose(box).translation().z(), 0.1 + lifted, 2e-3);
  // Held by the jaws alone: their friction carries the weight, each pushes with its limit.
  EXPECT_NEAR(forceOn(*engine, box).z(), mass * kG, 0.02 * mass * kG);
  EXPECT_NEAR(pushOf(left).y(), 20.0, 0.2);
  EXPECT_NEAR(pushOf(right).y(), -20.0, 0.2);
  EXPECT_NEAR(pushOf(left).z() + pushOf(right).z(), mass * kG, 0.02 * mass * kG);
}

TEST(MujocoEngine, ResetClearsVelocitiesTargetsLimitsAndKinematicCommands) {
  SceneBuilder scene("reset");
  scene.addTable("Table", at(0, 0, -0.05), Vector3D(1, 1, 0.1));
  scene.addBox("Box", at(0, 0, 0.2), Vector3D(0.1, 0.1, 0.1), 1.0);
  scene.addFinger(at(0.5, 0, 0.5), 0.1, 0.5);
  scene.addGripper(at(-0.5, 0, 0.3), 0.05, 10.0);
  const auto dwc = scene.build();
  const auto factory = rwsim::mujoco::mujocoEngineFactory(*dwc);
  const auto fresh = factory->create();
  const auto used = factory->create();
  const auto finger = dwc->findDevice("Finger");
  const auto gripper = dwc->findBody("Gripper.Base");
  used->setMotorVelocityTargets(finger, Q::Constant(1, 2.0));
  used->setMotorForceLimits(finger, Q::Constant(1, 0.01));
  used->setKinematicVelocity(gripper, Vector3D(0, 0, 1), Vector3D(0, 0, 1));
  runUntil(*used, 0.3);
  const auto initial = dwc->workcell().defaultState();
  used->reset(initial);
  fresh->reset(initial);
  EXPECT_EQ(used->time(), 0.0);
  for (std::size_t b = 0; b < dwc->bodies().size(); ++b) {
    EXPECT_EQ(used->bodyLinearVelocity(BodyId(b)).norm(), 0.0);
    EXPECT_EQ(used->bodyAngularVelocity(BodyId(b)).norm(), 0.0);
  }
  runUntil(*used, 0.2);
  runUntil(*fresh, 0.2);
  for (std::size_t b = 0; b < dwc->bodies().size(); ++b) {
    EXPECT_TRANSFORM_NEAR(used->bodyPose(BodyId(b)), fresh->bodyPose(BodyId(b)), 1e-12)
        << dwc->bodies()[b].name;
  }
  EXPECT_EQ(used->jointVelocities(finger)[0], fresh->jointVelocities(finger)[0]);
}

TEST(MujocoEngine, AKinematicBaseIsPlacedAtAnyPoseAndMovesAsCommanded) {
  SceneBuilder scene("base");
  scene.addGripper(Transform3D::Identity(), 0.05, 10.0);
  const auto dwc = scene.build();
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*dwc)->create();
  const auto base = dwc->findBody("Gripper.Base");
  const Transform3D X0 =
      rw::math::rpyTransform(Vector3D(0.7, std::numbers::pi * 0.9, -0.4), Vector3D(0.2, -0.1, 0.4));
  auto state = dwc->workcell().defaultState();
  dwc->workcell().frames().frame(dwc->body(base).frame).setMovableTransform(state, X0);
  engine->reset(state);
  EXPECT_TRANSFORM_NEAR(engine->bodyPose(base), X0, 1e-12);
  const Vector3D v(0.1, -0.05, 0.2);
  engine->setKinematicVelocity(base, v, Vector3D::Zero());
  runUntil(*engine, 0.5);
  const double t = engine->time();
  EXPECT_LT((engine->bodyPose(base).translation() - (X0.translation() + v * t)).norm(), 1e-5);
  EXPECT_LT((engine->bodyPose(base).linear() - X0.linear()).norm(), 1e-5);
  EXPECT_LT((engine->bodyLinearVelocity(base) - v).norm(), 1e-4);
  // Turning about the world z axis through the frame origin.
  const Transform3D X1 = engine->bodyPose(base);
  const Vector3D w(0, 0, 0.8);
  engine->setKinematicVelocity(base, Vector3D::Zero(), w);
  runUntil(*engine, t + 0.5);
  const Eigen::Matrix3d turned =
      Eigen::AngleAxisd(0.8 * (engine->time() - t), Vector3D::UnitZ()).toRotationMatrix() *
      X1.linear();
  // The hinges' speeds are solved from their axes at the start of each step: exact to first
  // order in the step, the turn's axis then wanders by about |w| dt per step.
  EXPECT_LT((engine->bodyPose(base).translation() - X1.translation()).norm(), 1e-5);
  EXPECT_LT((engine->bodyPose(base).linear() - turned).norm(), 1e-3);
  EXPECT_LT((engine->bodyAngularVelocity(base) - w).norm(), w.norm() * w.norm() * 0.002);
  // The state carries the base's pose.
  const auto& frame = dwc->workcell().frames().frame(dwc->body(base).frame);
  EXPECT_TRANSFORM_NEAR(frame.movableTransform(engine->state()), engine->bodyPose(base), 1e-12);
  EXPECT_THROW(engine->setKinematicVelocity(dwc->findBody("Gripper.Left"), v, w),
               std::invalid_argument);
}

TEST(MujocoEngine, ANonFiniteCommandIsANumericalFailureUntilReset) {
  const FingerScene s = fingerScene(0.1, 1.0);
  const auto engine = rwsim::mujoco::mujocoEngineFactory(*s.dwc)->create();
  engine->setMotorVelocityTargets(s.finger, Q::Constant(1, std::nan("")));
  EXPECT_EQ(engine->step(), StepStatus::kNumericalFailure);
  EXPECT_NE(engine->failureDetail().find("Finger.Joint"), std::string::npos)
      << engine->failureDetail();
  EXPECT_EQ(engine->step(), StepStatus::kNumericalFailure);
  engine->reset(s.dwc->workcell().defaultState());
  EXPECT_EQ(engine->step(), StepStatus::kOk);
  EXPECT_TRUE(engine->failureDetail().empty());
}

// The comparison benchmark's scene and grasp (benchmarks/sdh_box_trial.hpp).
const rwsim::dynamics::DynamicWorkCell& sdhBox() {
  static const auto dwc = rwsim::loaders::loadDynamicWorkCell(
      visgrab::test::sourceDir() / "tests/rwsim/simulator/data/sdh_box.dwc.xml");
  return *dwc;
}

rwsim::simulator::GraspParameters sdhCylinderGrasp() {
  rwsim::simulator::GraspParameters g;
  g.X_W_tcp = rw::math::rpyTransform(Vector3D(0, std::numbers::pi, 0), Vector3D(0, 0, 0.05));
  g.qOpen = Q(7);
  g.qOpen << -1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174;
  g.qClosed = Q(7);
  g.qClosed << 0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349;
  g.tauMax = Q(7);
  g.tauMax << 2.1, 1.4, 2.1, 1.05, 0.7, 1.05, 0.7;
  return g;
}

void expectHeld(const std::shared_ptr<const rwsim::trial::EngineFactory>& engine,
                const std::string& expectedName) {
  const auto& dwc = sdhBox();
  rwsim::simulator::GraspTrialSetup setup;
  setup.hand = "SchunkHand";
  setup.tcpFrame = "SchunkHand.SDHTCP";
  setup.simulator = rwsim::simulator::optionsFromEngineProperties(dwc);
  const rwsim::simulator::GraspTrial trial(dwc, setup, engine);
  EXPECT_EQ(trial.engine().name(), expectedName);
  const auto result = trial.run(sdhCylinderGrasp(), dwc.workcell().defaultState());
  EXPECT_TRUE(result.outcome == rwsim::simulator::GraspOutcome::kStable ||
              result.outcome == rwsim::simulator::GraspOutcome::kSlipped)
      << expectedName << ": " << rwsim::simulator::outcomeName(result.outcome) << ", "
      << result.detail;
  EXPECT_EQ(result.object, dwc.findBody("Box"));
  // Lifted 10 cm with the hand: the object rose with it.
  EXPECT_NEAR(result.handLift.z(), 0.10, 0.005) << expectedName;
  EXPECT_GT(result.objectLift.z(), 0.08) << expectedName;
  EXPECT_GT(result.qLift, 0.8) << expectedName;
  EXPECT_FALSE(result.contacts.empty()) << expectedName;
  EXPECT_FALSE(result.closingCapped) << expectedName << ": " << result.detail;
  // Closing takes at least minCloseTime, the lift 0.1 m at 0.5 m/s and 1 m/s^2 0.45 s, then
  // 0.2 s of settling.
  EXPECT_GT(result.simulatedTime, 0.2 + 0.45 + 0.2 - 1e-6) << expectedName;
}

TEST(MujocoEngine, AModelMujocoCannotCompileIsReportedWithTheDwcAndMujocosMessage) {
  rwsim::mujoco::MujocoOptions options;
  options.solver = "Bogus";
  try {
    rwsim::mujoco::mujocoEngineFactory(sdhBox(), options);
    FAIL() << "a bad solver compiled";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sdh_box.dwc.xml"), std::string::npos) << what;
    EXPECT_NE(what.find("Bogus"), std::string::npos) << what;
  }
}

TEST(MujocoEngine, TheSdhHoldsTheBoxThroughGraspTrialOnBothEngines) {
  expectHeld(nullptr, "ode");
  expectHeld(rwsim::mujoco::mujocoEngineFactory(sdhBox()), "mujoco");
}

// --- Per-trial physics variations (rwsim::trial::PhysicsVariation) ----------------------------

rwsim::trial::PhysicsVariation variation(double frictionScale, double objectMassScale) {
  rwsim::trial::PhysicsVariation v;
  v.frictionScale = frictionScale;
  v.objectMassScale = objectMassScale;
  return v;
}

TEST(MujocoEngine, FrictionScaleMakesABoxThatSticksOnTheSlopeSlide) {
  // tan(20 deg) = 0.364: mu 0.4 holds the box, 0.5 * 0.4 = 0.2 does not. (Tilted gravity on a
  // level table: the export meets the box with the table's top plane, exact for box-plane.)
  const double angle = 20 * std::numbers::pi / 180;
  const double mu = 0.4;
  const double scale = 0.5;
  const auto dwc = visgrab::test::sim::boxUnderTiltedGravity(angle, mu);
  const BodyId block = dwc->findBody("Block");
  const auto factory = rwsim::mujoco::mujocoEngineFactory(*dwc);
  const auto held = factory->create();
  const double x0 = held->bodyPose(block).translation().x();
  runUntil(*held, 0.5);
  // MuJoCo's friction is a soft constraint: a sticking contact creeps (impratio 10 keeps it to
  // micrometres).
  EXPECT_LT(std::abs(held->bodyPose(block).translation().x() - x0), 1e-4);
  EXPECT_LT(held->bodyLinearVelocity(block).norm(), 1e-3);

  const auto sliding = factory->create(variation(scale, 1.0));
  const double expected = kG * (std::sin(angle) - scale * mu * std::cos(angle));
  // From rest, semi-implicit Euler moves the box by a dt^2 n (n + 1) / 2 in n steps.
  const double dt = sliding->timeStep();
  runUntil(*sliding, 0.2);
  const double n1 = std::round(sliding->time() / dt);
  const double x1 = sliding->bodyPose(block).translation().x();
  runUntil(*sliding, 0.8);
  const double n2 = std::round(sliding->time() / dt);
  const double x2 = sliding->bodyPose(block).translation().x();
  const double a = 2.0 * (x2 - x1) / (dt * dt * (n2 * (n2 + 1) - n1 * (n1 + 1)));
  // The elliptic cone has no preferred direction; MuJoCo's friction is a soft (regularised)
  // constraint, which costs the slide 0.1 % (measured). 0.5 % leaves nothing for a wrong mu:
  // 0.01 more or less of it moves a by 6 %.
  EXPECT_NEAR(a, expected, 0.005 * expected);
  RecordProperty("acceleration", std::to_string(a));
}

TEST(MujocoEngine, ObjectMassScaleScalesTheObjectsWeightButNotTheHandsLinks) {
  // The box's weight on the table: its contact force. The gripper's jaws (a device's bodies)
  // driven at their force limit accelerate at a rate set by their mass, which the variation must
  // leave alone.
  const double boxMass = 1.0;
  const auto dwc = visgrab::test::sim::weighingScene(boxMass, 0.05);
  const BodyId box = dwc->findBody("Box");
  const auto gripper = dwc->findDevice("Gripper");
  const auto factory = rwsim::mujoco::mujocoEngineFactory(*dwc);
  const auto closeJaws = [&](PhysicsEngine& engine) {
    engine.setMotorVelocityTargets(gripper, Q::Constant(2, 1.0));
    runUntil(engine, 0.1);
    return engine.jointPositions(gripper);
  };
  const auto identity = factory->create();
  const Q jaws = closeJaws(*identity);
  // Driven at the 0.05 N limit: q'' = limit / (0.1 kg + armature + kv dt) (the implicit step's
  // clipped servo, see ASmallForceLimitStallsTheServoAgainstGravity), semi-implicit Euler.
  const rwsim::mujoco::MujocoOptions options;
  const double dt = identity->timeStep();
  const double accel =
      0.05 / (0.1 + options.prismaticMotorArmature + options.prismaticMotorGain * dt);
  const double n = std::round(0.1 / dt);
  EXPECT_NEAR(jaws[0], accel * dt * dt * n * (n + 1) / 2, 0.02 * accel * dt * dt * n * (n + 1) / 2);
  runUntil(*identity, 1.0);
  EXPECT_NEAR(forceOn(*identity, box).z(), boxMass * kG, 1e-3 * boxMass * kG);
  // At rest the table carries the weight to rounding (measured); 0.1 % is far from any other
  // scale.
  for (const double scale : {0.4, 2.5}) {
    const auto varied = factory->create(variation(1.0, scale));
    // One solver for the whole model: the box's other mass may move the jaws' result by the
    // solver's tolerance, no more (scaled jaws would move 0.4 or 2.5 times as far).
    EXPECT_LT((closeJaws(*varied) - jaws).cwiseAbs().maxCoeff(), 1e-9 * jaws[0])
        << "scale " << scale;
    runUntil(*varied, 1.0);
    const Vector3D f = forceOn(*varied, box);
    EXPECT_NEAR(f.z(), scale * boxMass * kG, 1e-3 * scale * boxMass * kG) << "scale " << scale;
    EXPECT_NEAR(f.head<2>().norm(), 0.0, 1e-6) << "scale " << scale;
  }
}

TEST(MujocoEngine, AVariedEngineStepsAsTheEngineOfTheScaledDwc) {
  // Scaling by 2 (mass) and 0.5 (friction, 0.4 -> 0.2) is exact in floating point: the varied
  // model copy, its derived constants recomputed, must be the model compiled from a dwc that has
  // those values, step for step.
  const double angle = 25 * std::numbers::pi / 180;
  const auto dwc = visgrab::test::sim::boxUnderTiltedGravity(angle, 0.4);
  const auto slippery = visgrab::test::sim::boxUnderTiltedGravity(angle, 0.2);
  const BodyId block = dwc->findBody("Block");
  const auto varied = rwsim::mujoco::mujocoEngineFactory(*dwc)->create(variation(0.5, 1.0));
  const auto reference = rwsim::mujoco::mujocoEngineFactory(*slippery)->create();
  runUntil(*varied, 0.3);
  runUntil(*reference, 0.3);
  EXPECT_EQ(varied->bodyPose(block).matrix(), reference->bodyPose(block).matrix());
  EXPECT_EQ(forceOn(*varied, block), forceOn(*reference, block));

  const auto light = visgrab::test::sim::weighingScene(1.0, 10.0);
  const auto heavy = visgrab::test::sim::weighingScene(2.0, 10.0);
  const BodyId box = light->findBody("Box");
  auto state = light->workcell().defaultState();
  light->workcell()
      .frames()
      .frame(light->body(box).frame)
      .setMovableTransform(state, at(0, 0, 0.2));
  const auto heavier = rwsim::mujoco::mujocoEngineFactory(*light)->create(variation(1.0, 2.0));
  const auto twoKilos = rwsim::mujoco::mujocoEngineFactory(*heavy)->create();
  for (PhysicsEngine* engine : {heavier.get(), twoKilos.get()}) {
    engine->reset(state);
    runUntil(*engine, 0.5);
  }
  EXPECT_EQ(heavier->bodyPose(box).matrix(), twoKilos->bodyPose(box).matrix());
  EXPECT_EQ(forceOn(*heavier, box), forceOn(*twoKilos, box));
  EXPECT_NEAR(forceOn(*heavier, box).z(), 2.0 * kG, 0.01 * 2.0 * kG);
}

TEST(MujocoEngine, TheIdentityVariationChangesNoBitAndInvalidScalesAreRejected) {
  const auto& dwc = sdhBox();
  rwsim::simulator::GraspTrialSetup setup;
  setup.hand = "SchunkHand";
  setup.tcpFrame = "SchunkHand.SDHTCP";
  const auto factory = rwsim::mujoco::mujocoEngineFactory(dwc);
  const rwsim::simulator::GraspTrial trial(dwc, setup, factory);
  const auto plain = trial.run(sdhCylinderGrasp(), dwc.workcell().defaultState());
  const auto identity = trial.run(sdhCylinderGrasp(), dwc.workcell().defaultState(),
                                  rwsim::trial::PhysicsVariation{});
  EXPECT_EQ(identity.outcome, plain.outcome);
  EXPECT_EQ(identity.qLift, plain.qLift);
  EXPECT_EQ(identity.qGws, plain.qGws);
  EXPECT_EQ(identity.qGwsUnit, plain.qGwsUnit);
  EXPECT_EQ(identity.qGrasp, plain.qGrasp);
  EXPECT_EQ(identity.simulatedTime, plain.simulatedTime);
  EXPECT_EQ(identity.objectLift, plain.objectLift);
  EXPECT_EQ(identity.detail, plain.detail);
  for (const auto& bad : {variation(0.0, 1.0), variation(1.0, -1.0), variation(std::nan(""), 1.0),
                          variation(1.0, HUGE_VAL)}) {
    EXPECT_THROW(factory->create(bad), std::invalid_argument);
    EXPECT_THROW(trial.run(sdhCylinderGrasp(), dwc.workcell().defaultState(), bad),
                 std::invalid_argument);
  }
}

TEST(MujocoEngine, TheSdhTrialHoldsTheBoxWithTheHandTurned) {
  // The old comparison's slides could not turn the base; the engine's hinges can.
  const auto& dwc = sdhBox();
  rwsim::simulator::GraspTrialSetup setup;
  setup.hand = "SchunkHand";
  setup.tcpFrame = "SchunkHand.SDHTCP";
  const rwsim::simulator::GraspTrial trial(dwc, setup, rwsim::mujoco::mujocoEngineFactory(dwc));
  auto g = sdhCylinderGrasp();
  g.X_W_tcp = rw::math::rpyTransform(Vector3D(0.3, std::numbers::pi, 0), Vector3D(0, 0, 0.05));
  const auto result = trial.run(g, dwc.workcell().defaultState());
  EXPECT_TRUE(result.outcome == rwsim::simulator::GraspOutcome::kStable ||
              result.outcome == rwsim::simulator::GraspOutcome::kSlipped)
      << rwsim::simulator::outcomeName(result.outcome) << ", " << result.detail;
}

TEST(MujocoEngine, WithoutGravityAFloatingBoxStaysPutAndWithItFalls) {
  // A 0.1 m box floating at z = 1, nothing else: without gravity (a trial protocol's choice,
  // PhysicsVariation::gravity) it stays where it is; with it, it falls g t^2 / 2 in 1 s.
  SceneBuilder scene("float");
  scene.addBox("Box", rw::math::makeTranslation(Vector3D(0, 0, 1)), Vector3D(0.1, 0.1, 0.1), 0.5);
  const auto dwc = scene.build();
  const BodyId box = dwc->findBody("Box");
  const auto factory = rwsim::mujoco::mujocoEngineFactory(*dwc);
  rwsim::trial::PhysicsVariation off;
  off.gravity = false;
  const auto still = factory->create(off);
  runUntil(*still, 1.0);
  EXPECT_NEAR(still->bodyPose(box).translation().z(), 1.0, 1e-9);
  const auto falling = factory->create();
  runUntil(*falling, 1.0);
  // Semi-implicit Euler: g dt^2 n (n + 1) / 2 after n steps, within 1 % of g / 2 at dt 5 ms.
  EXPECT_NEAR(1.0 - falling->bodyPose(box).translation().z(), kG / 2, 0.03);
}

}  // namespace
