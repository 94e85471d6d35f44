// Per-trial physics variations (rwsim::trial::PhysicsVariation) on the ODE engine: scaled friction
// and object masses against analytic truth and against a dwc built with the scaled values, the
// identity bit for bit as without a variation, and invalid scales rejected.
#include "rwsim/trial/physics_variation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "engine_steps.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "sim_test_scenes.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Q;
using rw::math::Vector3D;
using rwsim::dynamics::BodyId;
using rwsim::simulator::Simulator;
using rwsim::simulator::SimulatorOptions;
using rwsim::trial::PhysicsEngine;
using rwsim::trial::PhysicsVariation;
using rwsim::trial::StepStatus;
using visgrab::test::sim::kG;

constexpr double kDeg = std::numbers::pi / 180.0;

using visgrab::test::sim::forceOn;
using visgrab::test::sim::runUntil;

PhysicsVariation friction(double scale) {
  PhysicsVariation v;
  v.frictionScale = scale;
  return v;
}

PhysicsVariation mass(double scale) {
  PhysicsVariation v;
  v.objectMassScale = scale;
  return v;
}

// Expects check() to reject the variation with a message naming `field`.
void expectRejected(const PhysicsVariation& v, const std::string& field) {
  try {
    v.check();
    ADD_FAILURE() << field << " " << v.frictionScale << " / " << v.objectMassScale
                  << " was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("> 0"), std::string::npos) << e.what();
  }
}

TEST(PhysicsVariation, TheDefaultIsTheIdentityAndInvalidScalesAreRejected) {
  EXPECT_TRUE(PhysicsVariation{}.isIdentity());
  EXPECT_NO_THROW(PhysicsVariation{}.check());
  EXPECT_FALSE(friction(0.9).isIdentity());
  EXPECT_FALSE(mass(1.1).isIdentity());
  EXPECT_NO_THROW(friction(1e-3).check());
  EXPECT_NO_THROW(mass(50.0).check());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {0.0, -0.0, -1.0, nan, inf, -inf}) {
    expectRejected(friction(bad), "frictionScale");
    expectRejected(mass(bad), "objectMassScale");
  }
  try {
    friction(-2.0).check();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("-2"), std::string::npos) << e.what();
  }
}

TEST(PhysicsVariation, OnlyRigidBodiesOfNoDeviceAreVariedObjects) {
  visgrab::test::sim::SceneBuilder scene("kinds");
  scene.addTable("Table", rw::math::makeTranslation(Vector3D(0, 0, -0.05)), Vector3D(1, 1, 0.1));
  scene.addBox("Box", rw::math::makeTranslation(Vector3D(0, 0, 0.05)), Vector3D(0.1, 0.1, 0.1),
               1.0);
  scene.addGripper(rw::math::makeTranslation(Vector3D(0.5, 0, 0.5)), 0.05, 10.0);
  scene.addFinger(rw::math::makeTranslation(Vector3D(-0.5, 0, 0.5)), 0.1, 0.5);
  const auto dwc = scene.build();
  for (const auto& body : dwc->bodies()) {
    EXPECT_EQ(rwsim::trial::isVariedObject(body), body.name == "Box") << body.name;
  }
}

TEST(OdeVariation, InvalidScalesAreRejectedByTheEngineAndItsFactory) {
  const auto dwc = visgrab::test::sim::weighingScene(1.0, 10.0);
  EXPECT_THROW(Simulator(*dwc, SimulatorOptions{}, friction(0.0)), std::invalid_argument);
  EXPECT_THROW(Simulator(*dwc, SimulatorOptions{}, mass(std::nan(""))), std::invalid_argument);
  const auto factory = rwsim::simulator::odeEngineFactory(*dwc, {});
  EXPECT_THROW(factory->create(mass(-1.0)), std::invalid_argument);
  EXPECT_THROW(factory->create(friction(std::numeric_limits<double>::infinity())),
               std::invalid_argument);
  EXPECT_EQ(Simulator(*dwc, {}, friction(0.5)).variation().frictionScale, 0.5);
}

// The acceleration down the slope of boxUnderTiltedGravity from the distance slid between 0.2 s
// and 0.8 s. From rest, semi-implicit Euler moves a body at constant acceleration a by
// a dt^2 n (n + 1) / 2 in n steps (a t^2 / 2 plus a dt t / 2: 0.5 % here at ODE's 5 ms).
double slideAcceleration(PhysicsEngine& engine, BodyId block) {
  const double dt = engine.timeStep();
  const auto steps = [&] { return static_cast<double>(std::lround(engine.time() / dt)); };
  runUntil(engine, 0.2);
  const double n1 = steps();
  const double x1 = engine.bodyPose(block).translation().x();
  runUntil(engine, 0.8);
  const double n2 = steps();
  const double x2 = engine.bodyPose(block).translation().x();
  return 2.0 * (x2 - x1) / (dt * dt * (n2 * (n2 + 1) - n1 * (n1 + 1)));
}

TEST(OdeVariation, FrictionScaleMakesABoxThatSticksOnTheSlopeSlide) {
  // tan(20 deg) = 0.364: mu 0.4 holds the box, 0.5 * 0.4 = 0.2 does not.
  const double angle = 20 * kDeg;
  const double mu = 0.4;
  const double scale = 0.5;
  const auto dwc = visgrab::test::sim::boxUnderTiltedGravity(angle, mu);
  const BodyId block = dwc->findBody("Block");
  Simulator held(*dwc);
  const double x0 = held.bodyPose(block).translation().x();
  runUntil(held, 0.5);
  EXPECT_LT(std::abs(held.bodyPose(block).translation().x() - x0), 1e-4);
  EXPECT_LT(held.bodyLinearVelocity(block).norm(), 1e-3);

  Simulator sliding(*dwc, {}, friction(scale));
  const double expected = kG * (std::sin(angle) - scale * mu * std::cos(angle));
  const double a = slideAcceleration(sliding, block);
  // The engine turns each contact's friction pyramid so that its first axis is the slip: the
  // Coulomb force along the slide is exact, and the box slides from the first step (measured:
  // within 1e-5 of the analytic value). 0.5 % is room for the soft contact's settling by
  // micrometres and none for a wrong mu: 0.01 more or less of it moves a by 6 %.
  EXPECT_NEAR(a, expected, 0.005 * expected);
  RecordProperty("acceleration", std::to_string(a));
  EXPECT_NEAR(sliding.bodyLinearVelocity(block).y(), 0.0, 1e-6);  // straight down the slope
}

TEST(OdeVariation, AScaledFrictionIsTheFrictionOfTheScaledMaterialTable) {
  // 0.4 * 0.5 is 0.2 exactly: the varied engine must step as one on a dwc whose table says 0.2.
  const double angle = 20 * kDeg;
  const auto dwc = visgrab::test::sim::boxUnderTiltedGravity(angle, 0.4);
  const auto scaled = visgrab::test::sim::boxUnderTiltedGravity(angle, 0.2);
  const BodyId block = dwc->findBody("Block");
  Simulator varied(*dwc, {}, friction(0.5));
  Simulator reference(*scaled);
  runUntil(varied, 0.5);
  runUntil(reference, 0.5);
  EXPECT_EQ(varied.bodyPose(block).matrix(), reference.bodyPose(block).matrix());
  EXPECT_EQ(varied.bodyLinearVelocity(block), reference.bodyLinearVelocity(block));
}

TEST(OdeVariation, ObjectMassScaleScalesTheObjectsWeightButNotTheHandsLinks) {
  // The box's weight m g on the table: its contact force. The gripper's jaws (a device's bodies)
  // driven at their force limit F accelerate at F / m_jaw, which the variation must leave alone.
  const double boxMass = 1.0;
  const double jawForce = 0.05;
  const auto dwc = visgrab::test::sim::weighingScene(boxMass, jawForce);
  const BodyId box = dwc->findBody("Box");
  const auto gripper = dwc->findDevice("Gripper");
  const auto closeJaws = [&](Simulator& sim) {
    sim.setMotorVelocityTargets(gripper, Q::Constant(2, 1.0));
    runUntil(sim, 0.1);
    return sim.jointPositions(gripper);
  };
  Simulator identity(*dwc);
  const Q jaws = closeJaws(identity);
  // s = F t^2 / (2 m), semi-implicit Euler's n (n + 1) / 2 steps.
  const double dt = identity.timeStep();
  const auto n = static_cast<double>(std::lround(identity.time() / dt));
  EXPECT_NEAR(jaws[0], jawForce / 0.1 * dt * dt * n * (n + 1) / 2, 1e-9);
  runUntil(identity, 1.0);
  EXPECT_NEAR(forceOn(identity, box).z(), boxMass * kG, 1e-3 * boxMass * kG);
  // At rest the table carries the weight to rounding (measured); 0.1 % is far from any other
  // scale.
  for (const double scale : {0.4, 2.5}) {
    Simulator varied(*dwc, {}, mass(scale));
    // ODE steps separate islands on their own: the jaws move as in the identity, bit for bit.
    EXPECT_EQ(closeJaws(varied), jaws) << "scale " << scale;
    runUntil(varied, 1.0);
    const Vector3D f = forceOn(varied, box);
    EXPECT_NEAR(f.z(), scale * boxMass * kG, 1e-3 * scale * boxMass * kG) << "scale " << scale;
    EXPECT_NEAR(f.head<2>().norm(), 0.0, 1e-6) << "scale " << scale;
    EXPECT_NEAR(varied.bodyPose(box).translation().z(), 0.05, 1e-3) << "scale " << scale;
  }
}

TEST(OdeVariation, AScaledMassIsTheMassOfTheScaledBody) {
  // Scaling by 2 is exact in floating point, so the varied engine must step as one on a dwc
  // whose box weighs 2 kg (boxInertia(2, s) = 2 boxInertia(1, s) bit for bit); a dropped box
  // then hits the table with the same 2 kg impulses.
  const auto light = visgrab::test::sim::weighingScene(1.0, 10.0);
  const auto heavy = visgrab::test::sim::weighingScene(2.0, 10.0);
  auto state = light->workcell().defaultState();
  const BodyId box = light->findBody("Box");
  const auto& frame = light->workcell().frames().frame(light->body(box).frame);
  frame.setMovableTransform(state, rw::math::makeTranslation(Vector3D(0, 0, 0.2)));
  Simulator varied(*light, {}, mass(2.0));
  Simulator reference(*heavy);
  Simulator unvaried(*light);
  for (Simulator* sim : {&varied, &reference, &unvaried}) {
    sim->reset(state);
    runUntil(*sim, 0.6);
  }
  EXPECT_EQ(varied.bodyPose(box).matrix(), reference.bodyPose(box).matrix());
  EXPECT_EQ(forceOn(varied, box), forceOn(reference, box));
  EXPECT_NEAR(forceOn(varied, box).z(), 2.0 * forceOn(unvaried, box).z(), 0.01 * 2.0 * kG);
}

TEST(OdeVariation, TheIdentityVariationChangesNoBit) {
  // The friction table and masses built for the identity are the dwc's own: a sliding box steps
  // exactly as on an engine made without a variation.
  const auto dwc = visgrab::test::sim::boxUnderTiltedGravity(25 * kDeg, 0.4);
  const BodyId block = dwc->findBody("Block");
  const auto factory = rwsim::simulator::odeEngineFactory(*dwc, {});
  const auto plain = factory->create();
  const auto identity = factory->create(PhysicsVariation{});
  Simulator direct(*dwc);
  for (PhysicsEngine* engine :
       {plain.get(), identity.get(), static_cast<PhysicsEngine*>(&direct)}) {
    runUntil(*engine, 0.5);
  }
  EXPECT_GT(plain->bodyPose(block).translation().x(), -0.45);  // it slid
  EXPECT_EQ(identity->bodyPose(block).matrix(), plain->bodyPose(block).matrix());
  EXPECT_EQ(direct.bodyPose(block).matrix(), plain->bodyPose(block).matrix());
  EXPECT_EQ(forceOn(*identity, block), forceOn(*plain, block));
}

}  // namespace
