// The simulator against analytic physics: resting contact, friction on a slope, free fall,
// a friction pinch and a torque-limited finger.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rw/math/rpy.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "sim_test_scenes.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::BodyId;
using rwsim::simulator::Simulator;
using rwsim::simulator::StepStatus;
using visgrab::test::sim::kG;
using visgrab::test::sim::SceneBuilder;

constexpr double kDeg = std::numbers::pi / 180.0;

Transform3D at(double x, double y, double z) {
  return rw::math::makeTranslation(Vector3D(x, y, z));
}

// Runs until `t`, failing the test on a bad step.
void runUntil(Simulator& sim, double t) {
  while (sim.time() < t - 1e-9) {
    const StepStatus s = sim.step();
    ASSERT_EQ(s, StepStatus::kOk) << sim.failureDetail();
  }
}

// Sum of the contact forces on body `b` in the last step.
Vector3D forceOn(const Simulator& sim, BodyId b) {
  Vector3D f = Vector3D::Zero();
  for (const auto& bc : sim.contacts()) {
    for (const auto& p : bc.points) {
      if (bc.bodyB == b) f += p.force;
      if (bc.bodyA == b) f -= p.force;
    }
  }
  return f;
}

TEST(SimulatorPhysics, BoxRestsOnTable) {
  SceneBuilder scene("rest");
  scene.addTable("Table", at(0, 0, -0.05), Vector3D(1, 1, 0.1));
  scene.addBox("Box", at(0, 0, 0.05), Vector3D(0.1, 0.1, 0.1), 1.0);
  const auto dwc = scene.build();
  Simulator sim(*dwc);
  const auto box = dwc->findBody("Box");
  runUntil(sim, 1.0);
  EXPECT_NEAR(sim.bodyPose(box).translation().z(), 0.05, 1e-3);
  EXPECT_NEAR(sim.bodyPose(box).translation().x(), 0.0, 1e-3);
  EXPECT_LT(sim.bodyLinearVelocity(box).norm(), 1e-3);
  // The table pushes the box up with its weight: checks ODE's normal and feedback conventions.
  const Vector3D f = forceOn(sim, box);
  EXPECT_NEAR(f.z(), 1.0 * kG, 0.02 * kG);
  EXPECT_NEAR(f.head<2>().norm(), 0.0, 0.01);
  // The state follows the bodies.
  const auto& frame = dwc->workcell().frames().frame(dwc->body(box).frame);
  EXPECT_TRANSFORM_NEAR(frame.movableTransform(sim.state()), sim.bodyPose(box), 1e-12);
}

struct Slope {
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc;
  Transform3D X_W_slope;
};

Slope slope(double angle) {
  SceneBuilder scene("slope", 0.4);
  const Transform3D X_W_slope(Eigen::AngleAxisd(angle, Vector3D::UnitY()));
  scene.addTable("Slope", X_W_slope * at(0, 0, -0.05), Vector3D(2, 1, 0.1));
  scene.addBox("Block", X_W_slope * at(0, 0, 0.025), Vector3D(0.1, 0.1, 0.05), 0.5);
  return {scene.build(), X_W_slope};
}

// Distance slid down the slope (along the slope's -x... the downhill direction).
double slid(const Simulator& sim, const Slope& s, BodyId block) {
  const Vector3D p = s.X_W_slope.inverse() * sim.bodyPose(block).translation();
  return p.x();  // Ry(+angle) tilts +x downwards
}

// The acceleration down the slope from the distances slid at 0.2 s and 0.8 s (s = a t^2 / 2
// from rest), running `sim` to 0.8 s.
double slideAcceleration(Simulator& sim, const Slope& s, BodyId body) {
  runUntil(sim, 0.2);
  const double s1 = slid(sim, s, body);
  runUntil(sim, 0.8);
  const double s2 = slid(sim, s, body);
  return 2.0 * (s2 - s1) / (0.8 * 0.8 - 0.2 * 0.2);
}

// Expects `body` to stay put on the slope for 1 s: less than 1 mm slid, slower than 1 mm/s.
void expectStaysPut(const Slope& s, const std::string& body) {
  Simulator sim(*s.dwc);
  const auto b = s.dwc->findBody(body);
  runUntil(sim, 1.0);
  EXPECT_LT(std::abs(slid(sim, s, b)), 1e-3);
  EXPECT_LT(sim.bodyLinearVelocity(b).norm(), 1e-3);
}

TEST(SimulatorPhysics, BlockStaysOnA20DegreeSlope) { expectStaysPut(slope(20 * kDeg), "Block"); }

TEST(SimulatorPhysics, BlockSlidesOnA25DegreeSlope) {
  const double angle = 25 * kDeg;
  const Slope s = slope(angle);
  Simulator sim(*s.dwc);
  const auto block = s.dwc->findBody("Block");
  const double expected = kG * (std::sin(angle) - 0.4 * std::cos(angle));
  const double a = slideAcceleration(sim, s, block);
  EXPECT_NEAR(a, expected, 0.1 * expected);
}

// Round bodies on a 2 m slope (mu 0.6, enough for rolling without slip): a body whose inertia
// about its rolling axis is k m r^2 rolls down with a = g sin(angle) / (1 + k).
struct Roller {
  std::shared_ptr<const rw::geometry::Geometry> geometry;
  Transform3D X_slope_body;  // start pose on the slope
  double mass = 1.0;
  Eigen::Matrix3d inertia;
  Vector3D cog = Vector3D::Zero();  // in the body frame
};

Slope rollerOnSlope(double angle, const Roller& roller, double mu = 0.6) {
  SceneBuilder scene("roll", mu);
  const Transform3D X_W_slope(Eigen::AngleAxisd(angle, Vector3D::UnitY()));
  scene.addTable("Slope", X_W_slope * at(0, 0, -0.05), Vector3D(2, 1, 0.1));
  scene.addBody("Roller", X_W_slope * roller.X_slope_body, roller.geometry, roller.mass,
                roller.inertia, roller.cog);
  return {scene.build(), X_W_slope};
}

/// A cylinder (radius r, height h) lying across the slope (axis along the slope's y), its
/// centre `x` along the slope; inertia diag(perp, perp, axial) in its frame (axis z).
Roller lyingCylinder(double r, double h, double x, double axial, double perp) {
  return {rw::geometry::Geometry::cylinder(r, h),
          at(x, 0, r) * Transform3D(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3D::UnitX())),
          1.0, Vector3D(perp, perp, axial).asDiagonal()};
}

/// Acceleration down the slope from the distances at 0.2 s and 1 s (s = a t^2 / 2 from rest).
double rollingAcceleration(const Slope& s, double* drift = nullptr) {
  Simulator sim(*s.dwc);
  const auto body = s.dwc->findBody("Roller");
  const Vector3D start = s.X_W_slope.inverse() * sim.bodyPose(body).translation();
  runUntil(sim, 0.2);
  const double s1 = slid(sim, s, body) - start.x();
  runUntil(sim, 1.0);
  const Vector3D end = s.X_W_slope.inverse() * sim.bodyPose(body).translation();
  const double s2 = end.x() - start.x();
  if (drift != nullptr) *drift = std::abs(end.y() - start.y()) / s2;
  const double a = 2.0 * (s2 - s1) / (1.0 - 0.2 * 0.2);
  ::testing::Test::RecordProperty("acceleration", std::to_string(a));
  return a;
}

TEST(SimulatorPhysics, SolidCylinderRollsWithTwoThirdsGSin) {
  const double angle = 20 * kDeg;
  const double r = 0.05;
  const double h = 0.1;
  const Roller roller = lyingCylinder(r, h, -0.8, r * r / 2, (3 * r * r + h * h) / 12);
  const double a = rollingAcceleration(rollerOnSlope(angle, roller));
  const double expected = 2.0 / 3.0 * kG * std::sin(angle);
  EXPECT_NEAR(a, expected, 0.03 * expected);
}

TEST(SimulatorPhysics, ThinWalledCylinderRollsWithHalfGSin) {
  // A thin-walled tube's inertia (m r^2 about the axis) on the cylinder's geometry.
  const double angle = 20 * kDeg;
  const double r = 0.05;
  const double h = 0.1;
  const Roller roller = lyingCylinder(r, h, -0.8, r * r, r * r / 2 + h * h / 12);
  const double a = rollingAcceleration(rollerOnSlope(angle, roller));
  const double expected = 0.5 * kG * std::sin(angle);
  EXPECT_NEAR(a, expected, 0.03 * expected);
}

TEST(SimulatorPhysics, SphereRollsWithFiveSeventhsGSin) {
  const double angle = 20 * kDeg;
  const double r = 0.05;
  const Roller roller{rw::geometry::Geometry::sphere(r), at(-0.9, 0, r), 1.0,
                      Eigen::Matrix3d::Identity() * (0.4 * r * r)};
  const double a = rollingAcceleration(rollerOnSlope(angle, roller));
  const double expected = 5.0 / 7.0 * kG * std::sin(angle);
  EXPECT_NEAR(a, expected, 0.03 * expected);
}

TEST(SimulatorPhysics, CanRollsStraightDownTheSlope) {
  // A can's size (r 3.3 cm, 12 cm tall): sideways drift under 1 % of the distance rolled. The
  // can starts turned 7.3 degrees about its own axis and with its centre of mass 1 cm off the
  // middle of its length (a full can's liquid, a necked top): a true cylinder has no preferred
  // turn, and an axial offset of the mass must not steer it.
  const double r = 0.033;
  const double h = 0.12;
  Roller can = lyingCylinder(r, h, -0.8, r * r / 2, (3 * r * r + h * h) / 12);
  can.X_slope_body =
      can.X_slope_body * Transform3D(Eigen::AngleAxisd(7.3 * kDeg, Vector3D::UnitZ()));
  can.cog = Vector3D(0, 0, 0.01);
  double drift = 1.0;
  const double a = rollingAcceleration(rollerOnSlope(20 * kDeg, can), &drift);
  EXPECT_GT(a, 0.0);
  EXPECT_LT(drift, 0.01);
  RecordProperty("drift", std::to_string(drift));
}

/// A squat cylinder (r 5 cm, 5 cm tall, tips only beyond 63 degrees) standing on the slope.
Slope standingCylinder(double angle) {
  const double r = 0.05;
  const double h = 0.05;
  const Roller standing{
      rw::geometry::Geometry::cylinder(r, h), at(0, 0, h / 2), 0.5,
      Vector3D(0.5 * (3 * r * r + h * h) / 12, 0.5 * (3 * r * r + h * h) / 12, 0.5 * r * r / 2)
          .asDiagonal()};
  return rollerOnSlope(angle, standing, 0.4);
}

TEST(SimulatorPhysics, StandingCylinderHoldsBelowTheFrictionAngle) {
  // mu 0.4: the friction angle is atan(0.4) = 21.8 degrees.
  expectStaysPut(standingCylinder(18 * kDeg), "Roller");
}

TEST(SimulatorPhysics, StandingCylinderSlidesAboveTheFrictionAngle) {
  const double angle = 25 * kDeg;
  const Slope s = standingCylinder(angle);
  Simulator sim(*s.dwc);
  const auto body = s.dwc->findBody("Roller");
  const double expected = kG * (std::sin(angle) - 0.4 * std::cos(angle));
  const double a = slideAcceleration(sim, s, body);
  EXPECT_NEAR(a, expected, 0.1 * expected);
  RecordProperty("acceleration", std::to_string(a));
  // It slides upright: no tumbling.
  EXPECT_NEAR((s.X_W_slope.linear().transpose() * sim.bodyPose(body).linear()).col(2).z(), 1.0,
              1e-3);
}

TEST(SimulatorPhysics, FreeFallFollowsGravity) {
  SceneBuilder scene("fall");
  scene.addBox("Box", at(0, 0, 2.0), Vector3D(0.1, 0.1, 0.1), 1.0);
  const auto dwc = scene.build();
  Simulator sim(*dwc);
  const auto box = dwc->findBody("Box");
  // Semi-implicit Euler falls (1 + dt/t) times too far: within 1% from t = 100 dt on.
  for (const double t : {0.55, 0.6, 0.8}) {
    runUntil(sim, t);
    const double fallen = 2.0 - sim.bodyPose(box).translation().z();
    EXPECT_NEAR(fallen, 0.5 * kG * t * t, 0.01 * 0.5 * kG * t * t) << "t = " << t;
    EXPECT_NEAR(sim.bodyLinearVelocity(box).z(), -kG * t, 0.01 * kG * t);
  }
}

TEST(SimulatorPhysics, DroppedBoxDoesNotRebound) {
  SceneBuilder scene("drop");
  scene.addTable("Table", at(0, 0, -0.05), Vector3D(1, 1, 0.1));
  const double z0 = 0.35;
  scene.addBox("Box", at(0, 0, z0), Vector3D(0.1, 0.1, 0.1), 1.0);
  const auto dwc = scene.build();
  Simulator sim(*dwc);
  const auto box = dwc->findBody("Box");
  double highestAfterImpact = 0.0;
  bool impacted = false;
  while (sim.time() < 1.5) {
    ASSERT_EQ(sim.step(), StepStatus::kOk) << sim.failureDetail();
    const double z = sim.bodyPose(box).translation().z();
    EXPECT_LE(z, z0 + 1e-9);
    if (!sim.contacts().empty()) impacted = true;
    if (impacted) highestAfterImpact = std::max(highestAfterImpact, z);
  }
  EXPECT_TRUE(impacted);
  EXPECT_LT(highestAfterImpact, 0.05 + 0.005);  // no bounce with restitution 0
  EXPECT_NEAR(sim.bodyPose(box).translation().z(), 0.05, 1e-3);
  EXPECT_LT(sim.bodyLinearVelocity(box).norm(), 1e-3);
}

// Drop of the box between two jaws pressing with `force` each, at the given times.
std::vector<double> pinchDrops(double force, const std::vector<double>& times) {
  SceneBuilder scene("pinch");
  const double mass = 0.5;
  scene.addBox("Box", at(0, 0, 0), Vector3D(0.06, 0.06, 0.06), mass);
  scene.addGripper(at(0, 0, 0), 0.04, force);  // jaw faces touch the box
  const auto dwc = scene.build();
  Simulator sim(*dwc);
  const auto box = dwc->findBody("Box");
  sim.setMotorVelocityTargets(rwsim::dynamics::DeviceId(0), Eigen::Vector2d(0.05, 0.05));
  std::vector<double> drops;
  for (const double t : times) {
    runUntil(sim, t);
    drops.push_back(-sim.bodyPose(box).translation().z());
  }
  return drops;
}

constexpr double kPinchMass = 0.5;
constexpr double kPinchMu = 0.6;  // Finger-Object

TEST(SimulatorPhysics, PinchHoldsWithEnoughFriction) {
  const double force = 1.25 * kPinchMass * kG / (2.0 * kPinchMu);  // 2 mu F = 1.25 m g
  const auto drops = pinchDrops(force, {0.1, 1.1});
  EXPECT_LT(std::abs(drops[1] - drops[0]), 1e-3);  // held for a second
  EXPECT_LT(std::abs(drops[1]), 1e-3);
}

TEST(SimulatorPhysics, PinchSlipsWithTooLittleFriction) {
  const double force = 0.8 * kPinchMass * kG / (2.0 * kPinchMu);  // 2 mu F = 0.8 m g
  // While the box is between the jaws it slides down with a = g - 2 mu F / m = 0.2 g.
  const auto drops = pinchDrops(force, {0.05, 0.15});
  const double a = 2.0 * (drops[1] - drops[0]) / (0.15 * 0.15 - 0.05 * 0.05);
  EXPECT_NEAR(a, 0.2 * kG, 0.1 * 0.2 * kG) << "drops " << drops[0] << ", " << drops[1];
}

TEST(SimulatorPhysics, FingerAtItsTorqueLimitPressesWithTauOverLever) {
  SceneBuilder scene("finger");
  const double lever = 0.1;
  const double torque = 0.5;
  scene.addFinger(Transform3D::Identity(), lever, torque);
  // The tip's lowest point is at (lever, 0, 0); the plate's top 2 mm below it, clear of the rod.
  scene.addTable("Plate", at(lever + 0.01, 0, -0.002 - 0.01), Vector3D(0.03, 0.05, 0.02));
  const auto dwc = scene.build(0.0);  // no gravity: only the motor loads the plate
  Simulator sim(*dwc);
  sim.setMotorVelocityTargets(rwsim::dynamics::DeviceId(0), Eigen::VectorXd::Constant(1, 1.0));
  runUntil(sim, 0.5);
  const auto plate = dwc->findBody("Plate");
  const Vector3D f = forceOn(sim, plate);
  double arm = 0.0;
  for (const auto& bc : sim.contacts()) {
    for (const auto& p : bc.points) arm = p.point.position.x();
  }
  EXPECT_NEAR(arm, lever, 0.005);
  EXPECT_NEAR(-f.z(), torque / lever, 0.1 * torque / lever);
  EXPECT_LT(std::abs(sim.jointVelocities(rwsim::dynamics::DeviceId(0))[0]), 1e-3);
}

}  // namespace
