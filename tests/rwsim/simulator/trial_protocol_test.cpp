// Trial protocols (rwsim::trial::TrialProtocol): the XML reader on the project's files and on bad
// input (file:line:column), gravity switched off through the physics seam (ODE), and the shake
// protocol's verdicts against the friction bound of a pinch: a floating box between two jaws
// held when 2 mu F > m a_max and left behind when the friction is far below.
#include "rwsim/trial/trial_protocol.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "engine_steps.hpp"
#include "gripper_trial.hpp"
#include "rw/common/diagnostic.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "sim_test_scenes.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::simulator::GraspTrial;
using rwsim::simulator::GraspTrialResult;
using rwsim::simulator::GraspTrialSetup;
using rwsim::trial::GraspOutcome;
using rwsim::trial::PhaseKind;
using rwsim::trial::TrialProtocol;
using visgrab::test::sim::at;
using visgrab::test::sim::gripperGrasp;
using visgrab::test::sim::gripperScene;
using visgrab::test::sim::gripperSetup;
using visgrab::test::sim::kG;
using visgrab::test::sim::SceneBuilder;

std::filesystem::path protocolDir() { return visgrab::test::sourceDir() / "scenes/protocols"; }

// The one message of the LoadError that parsing `xml` as "p.xml" throws.
std::string loadError(const std::string& xml) {
  try {
    rwsim::trial::parseTrialProtocol(xml, "p.xml");
  } catch (const rw::common::LoadError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << xml;
  return {};
}

// A protocol file around `body` (the lines inside <TrialProtocol name="t">, from line 2 on).
std::string protocolXml(const std::string& body) {
  return "<TrialProtocol name=\"t\">\n" + body + "</TrialProtocol>\n";
}

TEST(TrialProtocolFile, LiftXmlIsTheDefaultProtocolInEveryField) {
  const TrialProtocol lift = rwsim::trial::loadTrialProtocol(protocolDir() / "lift.xml");
  EXPECT_EQ(lift, TrialProtocol::lift());
  EXPECT_TRUE(lift.isLift());
  EXPECT_EQ(rwsim::trial::describe(lift),
            "gravity on; close until rest; lift 0.1 m at 0.5 m/s 1 m/s^2, settle 0.2 s; held by "
            "hand contact");
  EXPECT_EQ(rwsim::trial::protocolHash(lift).size(), 16u);
}

TEST(TrialProtocolFile, ShakeXmlHasTheDocumentedValues) {
  const TrialProtocol shake = rwsim::trial::loadTrialProtocol(protocolDir() / "shake.xml");
  EXPECT_EQ(shake.name, "shake");
  EXPECT_FALSE(shake.isLift());
  EXPECT_FALSE(shake.gravity);
  EXPECT_EQ(shake.closing, rwsim::trial::ClosingRule::kForceThreshold);
  EXPECT_EQ(shake.gripForce, 20.0);
  ASSERT_EQ(shake.phases.size(), 2u);
  const auto& along = shake.phases[0];
  EXPECT_EQ(along.kind, PhaseKind::kShake);
  EXPECT_FALSE(along.rotation);
  // Along the approach and about the closing axis, whatever the TCP's axes: the jaw frame's.
  EXPECT_EQ(along.frame, rwsim::trial::AxisFrame::kJaw);
  EXPECT_TRUE(shake.usesJawFrame());
  EXPECT_FALSE(TrialProtocol::lift().usesJawFrame());
  EXPECT_EQ(along.axis, Vector3D::UnitZ());
  // Peak acceleration A (2 pi f)^2 = 0.02 (10 pi)^2 = 19.74 m/s^2, 2 g.
  EXPECT_NEAR(along.amplitude * std::pow(2 * std::numbers::pi * along.frequency, 2), 19.74, 0.01);
  const auto& about = shake.phases[1];
  EXPECT_TRUE(about.rotation);
  EXPECT_EQ(about.frame, rwsim::trial::AxisFrame::kJaw);
  EXPECT_EQ(about.axis, Vector3D::UnitX());
  EXPECT_NE(rwsim::trial::describe(shake).find("shake about 1 0 0 (jaw)"), std::string::npos)
      << rwsim::trial::describe(shake);
  EXPECT_NEAR(about.amplitude, 15 * std::numbers::pi / 180, 1e-15);
  EXPECT_EQ(shake.success, rwsim::trial::SuccessRule::kTwoFingers);
  EXPECT_NE(rwsim::trial::protocolHash(shake), rwsim::trial::protocolHash(TrialProtocol::lift()));
}

TEST(TrialProtocolFile, EachErrorNamesTheFileLineAndColumn) {
  struct Case {
    std::string xml;
    std::string expected;
  };
  const Case cases[] = {
      {"<TrialProtocol name=\"t\">\n  <Phases>\n    <Lift heigth=\"0.1\"/>\n  </Phases>\n"
       "</TrialProtocol>\n",
       "p.xml:3:5: error:"},
      {protocolXml("  <Phases>\n    <Lift height=\"abc\"/>\n  </Phases>\n"), "p.xml:3:5: error:"},
      {protocolXml("  <Phases>\n    <Lift height=\"-0.1\"/>\n  </Phases>\n"),
       "p.xml:3:5: error: <Lift>: attribute height: expected a number > 0, got -0.1"},
      {protocolXml("  <Phases>\n    <Hop height=\"0.1\"/>\n  </Phases>\n"),
       "p.xml:3:5: error: unknown element <Hop>"},
      {protocolXml("  <Closing rule=\"force\"/>\n  <Phases><Lift height=\"0.1\"/></Phases>\n"),
       "p.xml:2:3: error: <Closing>: missing required attribute \"force\""},
      {protocolXml("  <Closing rule=\"rest\" force=\"3\"/>\n  <Phases><Lift height=\"0.1\"/>"
                   "</Phases>\n"),
       "p.xml:2:3: error: <Closing>: attribute force: only rule=\"force\" takes a force"},
      {protocolXml("  <Phases>\n    <Shake motion=\"translation\" frame=\"tcp\" axis=\"0 0 0\" "
                   "amplitude=\"0.01\" frequency=\"2\" cycles=\"1\"/>\n  </Phases>\n"),
       "p.xml:3:5: error: <Shake>: attribute axis: expected a non-zero vector"},
      {protocolXml("  <Phases>\n    <Shake motion=\"translation\" frame=\"tcp\" axis=\"0 0 1\" "
                   "amplitude=\"0.01\" frequency=\"2\" cycles=\"1.3\"/>\n  </Phases>\n"),
       "p.xml:3:5: error: <Shake>: attribute cycles: expected a whole or half number"},
      {protocolXml("  <Phases>\n    <Pull frame=\"hand\" direction=\"0 0 1\" distance=\"0.1\"/>\n"
                   "  </Phases>\n"),
       "p.xml:3:5: error:"},
      {protocolXml("  <Success rule=\"three-fingers\"/>\n"), "p.xml:2:3: error:"},
      {"<TrialProtocol>\n  <Phases><Lift height=\"0.1\"/></Phases>\n</TrialProtocol>\n",
       "p.xml:1:1: error:"},
      {"", "p.xml:1:1: error: expected a <TrialProtocol> element, found none"},
      {protocolXml("  <Phases><Lift height=\"0.1\"/></Phases>\n") +
           protocolXml("  <Phases><Lift height=\"0.1\"/></Phases>\n"),
       "p.xml:4:1: error: a second <TrialProtocol> element"},
      {"<TrialProtocol name=\"t\">\n  <Phases>\n", "p.xml:"},
  };
  for (const Case& c : cases) {
    const std::string message = loadError(c.xml);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected \"" << c.expected << "\" in:\n"
        << message << "\nfor:\n"
        << c.xml;
  }
  // The misspelt attribute is named.
  EXPECT_NE(loadError(cases[0].xml).find("heigth"), std::string::npos);
}

TEST(TrialProtocolFile, AnUnreadableFileIsNamed) {
  try {
    rwsim::trial::loadTrialProtocol("/no/such/protocol.xml");
    ADD_FAILURE() << "a missing file loaded";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/protocol.xml"), std::string::npos) << e.what();
  }
}

TEST(TrialProtocolFile, CheckRejectsValuesOutOfRange) {
  TrialProtocol p;
  p.phases.front().distance = -1.0;
  EXPECT_THROW(rwsim::trial::checkProtocol(p), std::invalid_argument);
  p = TrialProtocol{};
  p.phases.clear();
  EXPECT_THROW(rwsim::trial::checkProtocol(p), std::invalid_argument);
  p = TrialProtocol{};
  p.closing = rwsim::trial::ClosingRule::kForceThreshold;
  EXPECT_THROW(rwsim::trial::checkProtocol(p), std::invalid_argument);
  p.gripForce = 5.0;
  EXPECT_NO_THROW(rwsim::trial::checkProtocol(p));
}

// --- Gravity through the seam -------------------------------------------------------------------

// A 0.1 m box floating at z = 1 with nothing else in the world.
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> floatingBox() {
  SceneBuilder scene("float");
  scene.addBox("Box", at(0, 0, 1), Vector3D(0.1, 0.1, 0.1), 0.5);
  return scene.build();
}

TEST(TrialProtocolGravity, WithoutGravityAFloatingBoxStaysPutOnOde) {
  const auto dwc = floatingBox();
  const auto box = dwc->findBody("Box");
  rwsim::trial::PhysicsVariation off;
  off.gravity = false;
  EXPECT_FALSE(off.isIdentity());
  rwsim::simulator::Simulator still(*dwc, {}, off);
  visgrab::test::sim::runUntil(still, 1.0);
  EXPECT_NEAR(still.bodyPose(box).translation().z(), 1.0, 1e-9);
  EXPECT_LT(still.bodyLinearVelocity(box).norm(), 1e-9);
  // With gravity it falls g t^2 / 2 (semi-implicit Euler: g dt^2 n (n + 1) / 2 after n steps).
  rwsim::simulator::Simulator falling(*dwc);
  visgrab::test::sim::runUntil(falling, 1.0);
  const double n = std::round(falling.time() / falling.timeStep());
  const double dt = falling.timeStep();
  EXPECT_NEAR(1.0 - falling.bodyPose(box).translation().z(), kG * dt * dt * n * (n + 1) / 2, 1e-9);
  EXPECT_NEAR(1.0 - falling.bodyPose(box).translation().z(), kG / 2, 0.03);
}

// --- The shake protocol on a floating box between two jaws -------------------------------------

// A 6 cm box of `mass` floating at the origin (no table) and the two-jaw gripper with force
// limit `jawForce` per jaw (jaw faces at |y| = 0.04 when open, plates 0.1 x 0.1).
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> floatingBoxAndGripper(double mass,
                                                                        double jawForce) {
  SceneBuilder scene("shake");
  scene.addBox("Box", at(0, 0, 0), Vector3D(0.06, 0.06, 0.06), mass);
  scene.addGripper(at(0.5, 0.5, 0.5), 0.05, jawForce);
  return scene.build();
}

// No gravity; close until 0.02 N; half a period of A (1 - cos 2 pi f t) along the approach
// (TCP z): the hand moves 2 A = 12 cm and stops, with peak acceleration A (2 pi f)^2.
TrialProtocol halfShake() {
  TrialProtocol p;
  p.name = "half-shake";
  p.gravity = false;
  p.closing = rwsim::trial::ClosingRule::kForceThreshold;
  p.gripForce = 0.02;
  rwsim::trial::ProtocolPhase shake;
  shake.kind = PhaseKind::kShake;
  shake.frame = rwsim::trial::AxisFrame::kTcp;
  shake.axis = Vector3D::UnitZ();
  shake.amplitude = 0.06;
  shake.frequency = 2.0;
  shake.cycles = 0.5;
  shake.settle = 0.1;
  p.phases = {shake};
  p.success = rwsim::trial::SuccessRule::kTwoFingers;
  return p;
}

GraspTrialResult shakeTrial(double mass, double jawForce, const Transform3D& X_W_tcp) {
  const auto dwc = floatingBoxAndGripper(mass, jawForce);
  GraspTrialSetup setup = gripperSetup();
  setup.protocol = halfShake();
  const GraspTrial trial(*dwc, setup);
  return trial.run(gripperGrasp(X_W_tcp), dwc->workcell().defaultState());
}

std::string describe(const GraspTrialResult& r) {
  return std::string(rwsim::trial::outcomeName(r.outcome)) + " (" + r.detail + ")";
}

TEST(ShakeProtocol, APinchFarAboveTheShakesInertialForceHolds) {
  // a_max = 0.06 (4 pi)^2 = 9.47 m/s^2: m a_max = 0.2 * 9.47 = 1.9 N, the pinch's friction bound
  // 2 mu F = 2 * 0.6 * 20 = 24 N, 12 times more. The box moves with the hand: 12 cm.
  const auto r = shakeTrial(0.2, 20.0, at(0, 0, 0));
  EXPECT_EQ(r.outcome, GraspOutcome::kStable) << describe(r);
  EXPECT_NEAR(r.handLift.z(), 0.12, 1e-6);
  EXPECT_NEAR(r.objectLift.z(), 0.12, 0.005);
  // Both jaws touch the box.
  std::vector<rwsim::dynamics::BodyId> jaws;
  for (const auto& c : r.contacts) {
    if (std::find(jaws.begin(), jaws.end(), c.handBody) == jaws.end()) jaws.push_back(c.handBody);
  }
  EXPECT_EQ(jaws.size(), 2u);
}

TEST(ShakeProtocol, APinchFarBelowTheShakesInertialForceLeavesTheBoxBehind) {
  // 2 mu F = 2 * 0.6 * 0.05 = 0.06 N against m a_max = 1.9 N: the friction accelerates the box
  // by at most 0.3 m/s^2, 1 cm in the 0.25 s of the motion (the jaws' first touch and the
  // settle add about as much), while the hand moves 12 cm: the box's 6 cm leave the 10 cm
  // plates and no finger touches it.
  const auto r = shakeTrial(0.2, 0.05, at(0, 0, 0));
  EXPECT_EQ(r.outcome, GraspOutcome::kDropped) << describe(r);
  EXPECT_NEAR(r.handLift.z(), 0.12, 1e-6);
  EXPECT_LT(std::abs(r.objectLift.z()), 0.04);
}

TEST(ShakeProtocol, ABoxBesideTheJawsIsMissed) {
  // The box's centre 0.2 m beside the jaws' centre along x: the plates (|x| <= 0.05) close on
  // nothing.
  const auto r = shakeTrial(0.2, 20.0, at(0.2, 0, 0));
  EXPECT_EQ(r.outcome, GraspOutcome::kMissed) << describe(r);
}

// Half a turn-shake (cycles 0.5: the hand ends turned 2 A = 0.5 rad) about `axis` in `frame`.
TrialProtocol halfTurn(rwsim::trial::AxisFrame frame, const Vector3D& axis) {
  TrialProtocol p = halfShake();
  p.name = "half-turn";
  rwsim::trial::ProtocolPhase& turn = p.phases.front();
  turn.rotation = true;
  turn.frame = frame;
  turn.axis = axis;
  turn.amplitude = 0.25;
  return p;
}

GraspTrialResult turnTrial(const TrialProtocol& protocol,
                           const std::optional<Transform3D>& X_tcp_jaw) {
  const auto dwc = floatingBoxAndGripper(0.2, 20.0);
  GraspTrialSetup setup = gripperSetup();
  setup.protocol = protocol;
  setup.X_tcp_jaw = X_tcp_jaw;
  const GraspTrial trial(*dwc, setup);
  return trial.run(gripperGrasp(at(0, 0, 0)), dwc->workcell().defaultState());
}

void expectNear(const Vector3D& a, const Vector3D& b, double tolerance) {
  EXPECT_LT((a - b).norm(), tolerance) << a.transpose() << " vs " << b.transpose();
}

TEST(ShakeProtocol, AJawFrameAxisIsTheHandsClosingAxisWhateverTheTcpsAxes) {
  // The test gripper's jaws close along its TCP's y (faces at |y| = 0.04), as the SDH's fingers
  // 2 and 3 do: its jaw frame (x the closing axis, z the approach) is the TCP turned 90 degrees
  // about z. A turn about the jaw frame's x is a turn about the TCP's y, not its x.
  const Transform3D X_tcp_jaw(
      rw::math::Rotation3D(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3D::UnitZ())));
  const auto jaw = turnTrial(halfTurn(rwsim::trial::AxisFrame::kJaw, Vector3D::UnitX()), X_tcp_jaw);
  const auto tcpY = turnTrial(halfTurn(rwsim::trial::AxisFrame::kTcp, Vector3D::UnitY()), {});
  EXPECT_EQ(jaw.outcome, GraspOutcome::kStable) << describe(jaw);
  EXPECT_EQ(jaw.outcome, tcpY.outcome);
  // The same motion (the axes differ by cos 90 degrees' rounding, 6e-17).
  expectNear(jaw.handLift, tcpY.handLift, 1e-9);
  expectNear(jaw.objectLift, tcpY.objectLift, 1e-6);
  // A turn about the jaw frame's x goes through the jaw frame's origin. The gripper's base is
  // at its TCP, so a turn through the TCP leaves it where it is; with the pads' centre c 2 cm
  // behind the TCP (c = (0, 0, -0.02)) the base at 0 ends at c + R (0 - c) = (I - R) c, R the
  // turn by theta = 0.5 rad. About the TCP's y (the closing axis), R (0, 0, z) = (z sin theta, 0,
  // z cos theta), so (I - R) c = (0.02 sin theta, 0, -0.02 (1 - cos theta)) = (0.009589, 0,
  // -0.002448); about the TCP's x, R (0, 0, z) = (0, -z sin theta, z cos theta) and the base
  // moves (0, -0.02 sin theta, -0.02 (1 - cos theta)) instead.
  expectNear(tcpY.handLift, Vector3D::Zero(), 1e-9);
  const double theta = 0.5;
  Transform3D behind = X_tcp_jaw;
  behind.translation() = Vector3D(0, 0, -0.02);
  const auto pivot = turnTrial(halfTurn(rwsim::trial::AxisFrame::kJaw, Vector3D::UnitX()), behind);
  expectNear(pivot.handLift, Vector3D(0.02 * std::sin(theta), 0, -0.02 * (1 - std::cos(theta))),
             1e-6);
  Transform3D behindTcp = Transform3D::Identity();
  behindTcp.translation() = Vector3D(0, 0, -0.02);
  const auto aboutX =
      turnTrial(halfTurn(rwsim::trial::AxisFrame::kJaw, Vector3D::UnitX()), behindTcp);
  expectNear(aboutX.handLift, Vector3D(0, -0.02 * std::sin(theta), -0.02 * (1 - std::cos(theta))),
             1e-6);

  // A hand without a jaw frame cannot run such a protocol: an error naming the protocol and the
  // hand, before any trial.
  const auto dwc = floatingBoxAndGripper(0.2, 20.0);
  GraspTrialSetup setup = gripperSetup();
  setup.protocol = halfTurn(rwsim::trial::AxisFrame::kJaw, Vector3D::UnitX());
  try {
    const GraspTrial trial(*dwc, setup);
    ADD_FAILURE() << "a jaw-frame protocol ran on a hand without a jaw frame";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the protocol \"half-turn\" gives an axis in the jaw "
                                         "frame, but hand 'Gripper' declares no jaw frame"),
              std::string::npos)
        << e.what();
  }
}

TEST(ShakeProtocol, TheLiftProtocolFromItsFileGivesTheDefaultTrialBitForBit) {
  const auto dwc = gripperScene();
  GraspTrialSetup setup = gripperSetup();
  const GraspTrial plain(*dwc, setup);
  setup.protocol = rwsim::trial::loadTrialProtocol(protocolDir() / "lift.xml");
  const GraspTrial fromFile(*dwc, setup);
  const auto g = gripperGrasp(at(0, 0, 0.06));
  const auto a = plain.run(g, dwc->workcell().defaultState());
  const auto b = fromFile.run(g, dwc->workcell().defaultState());
  EXPECT_EQ(a.outcome, GraspOutcome::kStable) << describe(a);
  EXPECT_EQ(a.outcome, b.outcome);
  EXPECT_EQ(a.detail, b.detail);
  EXPECT_EQ(a.qLift, b.qLift);
  EXPECT_EQ(a.qGws, b.qGws);
  EXPECT_EQ(a.simulatedTime, b.simulatedTime);
  EXPECT_EQ(a.objectLift, b.objectLift);
  EXPECT_NE(a.detail.find("during a lift of"), std::string::npos) << a.detail;
}

}  // namespace
