// The protocol's closing speed (<Closing speed=... angularSpeed=...>, docs/protocols.md): read,
// described and checked; in a trial the jaws close no faster than the cap, so they reach a
// floating box after (gap / speed) s, as kinematics says; with clampToVelocityLimits the
// smaller of the device's velocity limit and the cap sets that speed; and a protocol whose phases
// outlast the trial's 10 s time limit gets the time it needs (phasesDuration, worked by hand).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gripper_trial.hpp"
#include "rw/common/diagnostic.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/trial/trial_protocol.hpp"
#include "sim_test_scenes.hpp"

namespace {

using rw::math::Vector3D;
using rwsim::simulator::GraspTrial;
using rwsim::simulator::GraspTrialResult;
using rwsim::simulator::GraspTrialSetup;
using rwsim::trial::GraspOutcome;
using rwsim::trial::TrialProtocol;
using visgrab::test::sim::at;

constexpr const char* kCapped = R"(<TrialProtocol name="slow">
  <Gravity enabled="false"/>
  <Closing rule="force" force="20" speed="0.02" angularSpeed="0.5"/>
  <Phases><Lift height="0.1"/></Phases>
</TrialProtocol>
)";

TEST(ClosingSpeed, IsReadDescribedAndHashed) {
  const TrialProtocol p = rwsim::trial::parseTrialProtocol(kCapped, "slow.xml");
  EXPECT_EQ(p.closingSpeed, 0.02);
  EXPECT_EQ(p.closingAngularSpeed, 0.5);
  const std::string text = rwsim::trial::describe(p);
  EXPECT_NE(text.find("close until rest or 20 N at most 0.02 m/s at most 0.5 rad/s"),
            std::string::npos)
      << text;
  // Without a cap the description (and so the hash run.csv records) is what it was before
  // closing speeds existed.
  TrialProtocol uncapped = p;
  uncapped.closingSpeed = 0.0;
  uncapped.closingAngularSpeed = 0.0;
  EXPECT_EQ(rwsim::trial::describe(uncapped).find("at most"), std::string::npos);
  EXPECT_NE(rwsim::trial::protocolHash(p), rwsim::trial::protocolHash(uncapped));
  EXPECT_TRUE(TrialProtocol::lift().closingSpeed == 0.0 && TrialProtocol::lift().isLift());
}

TEST(ClosingSpeed, BadValuesAreErrorsAtTheirLine) {
  const std::string xml =
      "<TrialProtocol name=\"t\">\n  <Closing rule=\"rest\" speed=\"-0.1\"/>\n"
      "  <Phases><Lift height=\"0.1\"/></Phases>\n</TrialProtocol>\n";
  try {
    rwsim::trial::parseTrialProtocol(xml, "p.xml");
    ADD_FAILURE() << "a negative closing speed was read";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "p.xml:2:3: error: <Closing>: attribute speed: expected a number > 0, got -0.1"),
              std::string::npos)
        << e.what();
  }
  TrialProtocol p;
  p.closingSpeed = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(rwsim::trial::checkProtocol(p), std::invalid_argument);
  p.closingSpeed = 0.0;
  p.closingAngularSpeed = -1.0;
  EXPECT_THROW(rwsim::trial::checkProtocol(p), std::invalid_argument);
}

TEST(ClosingSpeed, PhasesDurationIsEachPhasesMotionAndSettle) {
  // The lift's ramp, 0.1 m at 0.5 m/s and 1 m/s^2, never reaches 0.5 m/s (that takes 0.125 m of
  // the 0.05 m before braking): a triangle of 2 sqrt(d / a) = 2 sqrt(0.1) s, then 0.2 s still.
  EXPECT_NEAR(rwsim::trial::phasesDuration(TrialProtocol::lift()), 2 * std::sqrt(0.1) + 0.2, 1e-12);
  TrialProtocol p;
  rwsim::trial::ProtocolPhase shake;
  shake.kind = rwsim::trial::PhaseKind::kShake;
  shake.amplitude = 0.01;
  shake.frequency = 0.5;
  shake.cycles = 3;
  shake.settle = 5;
  p.phases = {shake, shake};
  EXPECT_NEAR(rwsim::trial::phasesDuration(p), 2 * (3 / 0.5 + 5), 1e-12);
}

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// A 6 cm box of 0.2 kg floating at the origin and the two-jaw gripper around it (jaw faces
// 1 cm from the box on each side when open, 20 N per jaw, `jawLimit` m/s per jaw as the
// device's velocity limit; sim_test_scenes.hpp).
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> boxBetweenJaws(double jawLimit) {
  visgrab::test::sim::SceneBuilder scene("closing");
  scene.addBox("Box", at(0, 0, 0), Vector3D(0.06, 0.06, 0.06), 0.2);
  scene.addGripper(at(0.5, 0.5, 0.5), 0.05, 20.0, jawLimit);
  return scene.build();
}

// No gravity; close until 1 N at most `speed` m/s (0: no cap); then `phase`.
TrialProtocol slowClosing(double speed, const rwsim::trial::ProtocolPhase& phase) {
  TrialProtocol p;
  p.name = "slow";
  p.gravity = false;
  p.closing = rwsim::trial::ClosingRule::kForceThreshold;
  p.gripForce = 1.0;
  p.closingSpeed = speed;
  p.phases = {phase};
  p.success = rwsim::trial::SuccessRule::kTwoFingers;
  return p;
}

rwsim::trial::ProtocolPhase pull() {
  rwsim::trial::ProtocolPhase phase;
  phase.kind = rwsim::trial::PhaseKind::kPull;
  phase.axis = Vector3D::UnitX();
  phase.distance = 0.02;
  phase.settle = 0.05;
  return phase;
}

struct Closing {
  GraspTrialResult result;
  double firstTouch = -1.0;  // first step with a jaw-box contact, s
  double qTouch = 0.0;       // the first jaw's position then, m
  double fastestJaw = 0.0;   // largest |joint speed| of a jaw over the trial, m/s
};

// A trial closing at most `speed` m/s (the protocol's cap; 0: none) on jaws whose device limit
// is `jawLimit` m/s, which the trial's PD obeys when `clamp` (clampToVelocityLimits).
Closing close(double speed, const rwsim::trial::ProtocolPhase& phase, double jawLimit = kNoLimit,
              bool clamp = false) {
  const auto dwc = boxBetweenJaws(jawLimit);
  GraspTrialSetup setup = visgrab::test::sim::gripperSetup();
  setup.protocol = slowClosing(speed, phase);
  setup.clampToVelocityLimits = clamp;
  const GraspTrial trial(*dwc, setup);
  const auto g = visgrab::test::sim::gripperGrasp(at(0, 0, 0));
  Closing out;
  const auto device = dwc->findDevice("Gripper");
  const auto box = dwc->findBody("Box");
  const rwsim::simulator::Observer observer = [&](const rwsim::trial::PhysicsEngine& sim,
                                                  std::string_view) {
    out.fastestJaw = std::max(out.fastestJaw, sim.jointVelocities(device).cwiseAbs().maxCoeff());
    if (out.firstTouch >= 0.0) return;
    for (const auto& pair : sim.contacts()) {
      if (pair.bodyA == box || pair.bodyB == box) {
        out.firstTouch = sim.time();
        out.qTouch = sim.jointPositions(device)[0];
      }
    }
  };
  out.result = trial.run(g, dwc->workcell().defaultState(), observer);
  return out;
}

// `c` held the box, its jaws closed at `speed` m/s and no faster, and touched the box after the
// 1 cm gap: contacts are reported from the contact margin on (0.5 mm apart), so the first one
// comes when the jaw is between 9.5 and 10 mm along, at q / speed s (within a 5 ms step), later
// than `after` s.
void expectTouchedAtSpeed(const Closing& c, double speed, double after) {
  EXPECT_EQ(c.result.outcome, GraspOutcome::kStable) << c.result.detail;
  EXPECT_GE(c.qTouch, 0.01 - 0.0005 - 1e-9);
  EXPECT_LE(c.qTouch, 0.01 + 1e-4);
  EXPECT_NEAR(c.firstTouch, c.qTouch / speed, 0.0051);
  EXPECT_GT(c.firstTouch, after);
  EXPECT_LE(c.fastestJaw, speed * (1 + 1e-6));
}

TEST(ClosingSpeed, JawsReachTheBoxAfterTheGapOverTheCap) {
  // Each jaw has 1 cm to go: at 0.02 m/s it touches after 0.5 s (the velocity motor reaches the
  // capped speed in the first step: 20 N on 0.1 kg is 200 m/s^2, 0.1 ms to 0.02 m/s), at
  // q / 0.02 s with q between 9.5 and 10 mm.
  expectTouchedAtSpeed(close(0.02, pull()), 0.02, 0.47);
  // Without the cap the PD (P 10/s on a 4 cm error, 0.4 m/s) gets there ten times sooner.
  const Closing free = close(0.0, pull());
  EXPECT_EQ(free.result.outcome, GraspOutcome::kStable) << free.result.detail;
  EXPECT_LT(free.firstTouch, 0.05);
  EXPECT_GT(free.fastestJaw, 0.2);
}

TEST(ClosingSpeed, TheDevicesLimitWinsWhenItIsBelowTheCap) {
  // Jaws limited to 0.01 m/s by the device, the protocol's cap 0.02 m/s: clamped, the PD
  // commands min(0.02, 0.01) = 0.01 m/s, so the 1 cm gap takes 1 s, and the first contact comes
  // with the jaw between 9.5 and 10 mm along (contact margin 0.5 mm, as above), at q / 0.01 s:
  // between 0.95 and 1 s, twice the 0.5 s the cap alone gives.
  const Closing limited = close(0.02, pull(), 0.01, true);
  expectTouchedAtSpeed(limited, 0.01, 0.94);
  // It closes at the limit, not below it (the motor reaches 0.01 m/s in 0.05 ms, as above).
  EXPECT_GT(limited.fastestJaw, 0.01 * (1 - 1e-3));
  // The same jaws unclamped (RobWork's default) ignore the device's limit: the cap's 0.5 s.
  const Closing unclamped = close(0.02, pull(), 0.01, false);
  EXPECT_EQ(unclamped.result.outcome, GraspOutcome::kStable) << unclamped.result.detail;
  EXPECT_NEAR(unclamped.firstTouch, unclamped.qTouch / 0.02, 0.0051);
  EXPECT_LT(unclamped.firstTouch, 0.51);
  EXPECT_GT(unclamped.fastestJaw, 0.02 * (1 - 1e-3));
}

TEST(ClosingSpeed, TheCapWinsWhenItIsBelowTheDevicesLimit) {
  // Jaws limited to 0.04 m/s by the device, the protocol's cap 0.02 m/s: clamped, the PD
  // commands min(0.02, 0.04) = 0.02 m/s (the PD alone would ask 10/s * 4 cm = 0.4 m/s), so the
  // first contact comes at q / 0.02 s, between 0.475 and 0.5 s, and no jaw passes 0.02 m/s.
  const Closing capped = close(0.02, pull(), 0.04, true);
  expectTouchedAtSpeed(capped, 0.02, 0.47);
  EXPECT_GT(capped.fastestJaw, 0.02 * (1 - 1e-3));
}

TEST(ClosingSpeed, ALongProtocolGetsTheTimeItNeeds) {
  // A 12 s shake of 1 mm: the default limit is 10 s of simulated time, which the closing
  // (0.5 s) and the shake would pass; the trial's limit grows to the protocol's length.
  rwsim::trial::ProtocolPhase shake;
  shake.kind = rwsim::trial::PhaseKind::kShake;
  shake.frame = rwsim::trial::AxisFrame::kTcp;
  shake.axis = Vector3D::UnitZ();
  shake.amplitude = 0.001;
  shake.frequency = 1.0;
  shake.cycles = 12;
  shake.settle = 0.1;
  const Closing c = close(0.02, shake);
  EXPECT_EQ(c.result.outcome, GraspOutcome::kStable) << c.result.detail;
  EXPECT_GT(c.result.simulatedTime, 12.5);
}

}  // namespace
