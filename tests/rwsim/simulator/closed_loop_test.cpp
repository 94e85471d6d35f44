// Parallel devices in the simulator: every link an ODE body, every joint an ODE hinge, and each
// junction closed by an ODE joint where its legs meet (rwsim::dynamics::loopClosures). A
// hand-worked four-bar driven by its crank against gravity, and RobWork's Robotiq finger-control
// model closing (RW_COMPAT_DATA).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "rwsim/dynamics/loop_closure.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::simulator::Simulator;
using rwsim::simulator::StepStatus;

// The four-bar, in the plane z = 0 (every hinge axis along world z): ground pivots O = (0, 0)
// and G = (d, 0); the crank (length a, angle theta, active) about O; the coupler (length b)
// pinned at the crank tip A; the rocker (length c, angle psi, passive) about G; the pin at the
// rocker tip (passive, no link body of its own) where the coupler's far end D meets it.
// a + b = 0.08 <= c + d = 0.09 (Grashof, a the shortest): a crank-rocker, the crank turns
// freely. Gravity along -y loads the heavy coupler and rocker.
constexpr double kA = 0.02;
constexpr double kB = 0.06;
constexpr double kC = 0.04;
constexpr double kD = 0.05;

constexpr const char* kFourBar = R"(<WorkCell name="FourBar">
 <ParallelDevice name="FourBar">
  <Frame name="Base"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Frame>
  <SerialChain name="Crank">
   <Joint name="Crank" type="Revolute"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Joint>
   <Joint name="Coupler" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>0.02 0 0</Pos></Joint>
   <Frame name="CouplerEnd"><RPY>0 0 0</RPY><Pos>0.06 0 0</Pos></Frame>
  </SerialChain>
  <Frame name="Ground" refframe="Base"><RPY>0 0 0</RPY><Pos>0.05 0 0</Pos></Frame>
  <SerialChain name="Rocker">
   <Joint name="Rocker" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Joint>
   <Joint name="Pin" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>0.04 0 0</Pos></Joint>
  </SerialChain>
  <Junction><Chains>Crank</Chains><Chains>Rocker</Chains></Junction>
 </ParallelDevice>
</WorkCell>
)";

// Masses and inertias of slender rods (m L^2 / 12 about the centre). `pin` is inserted before
// </RigidDevice> (a Link for the pin: the junction is then welded).
std::string fourBarDynamics(const std::string& materials, const std::string& pin) {
  return R"(<DynamicWorkcell workcell="fourbar.wc.xml">
  <Gravity>0 -9.81 0</Gravity>
  <Include file=")" +
         materials + R"("/>
  <RigidDevice device="FourBar">
    <ForceLimit joint="Crank.Crank">5</ForceLimit>
    <FixedBase frame="Base"/>
    <RigidJoint joint="Crank.Crank"><Mass>0.05</Mass><COG>0.01 0 0</COG><Inertia>1e-6 2e-6 2e-6</Inertia></RigidJoint>
    <RigidJoint joint="Crank.Coupler"><Mass>0.5</Mass><COG>0.03 0 0</COG><Inertia>2e-5 1.5e-4 1.5e-4</Inertia></RigidJoint>
    <RigidJoint joint="Rocker.Rocker"><Mass>1.0</Mass><COG>0.02 0 0</COG><Inertia>2e-5 1.4e-4 1.4e-4</Inertia></RigidJoint>
)" + pin +
         R"(  </RigidDevice>
</DynamicWorkcell>
)";
}

// The closed form on the branch where D lies left of the line from A to G: with v = G - A and
// L = |v|, the coupler's absolute angle is beta = atan2(v) + alpha, cos(alpha) = (b^2 + L^2 -
// c^2) / (2 b L) (law of cosines in the triangle A, D, G); psi is the angle of D - G.
struct FourBarPose {
  double beta;  // coupler's absolute angle (theta + phi)
  double psi;   // rocker angle
};

FourBarPose closedForm(double theta) {
  const double ax = kA * std::cos(theta);
  const double ay = kA * std::sin(theta);
  const double vx = kD - ax;
  const double vy = -ay;
  const double l = std::hypot(vx, vy);
  const double alpha = std::acos((kB * kB + l * l - kC * kC) / (2.0 * kB * l));
  const double beta = std::atan2(vy, vx) + alpha;
  const double dx = ax + kB * std::cos(beta);
  const double dy = ay + kB * std::sin(beta);
  return {beta, std::atan2(dy, dx - kD)};
}

// Transmission angle at D (between coupler and rocker) for crank angle theta.
double transmissionAngle(double theta) {
  const double l2 = kA * kA + kD * kD - 2.0 * kA * kD * std::cos(theta);
  return std::acos((kB * kB + kC * kC - l2) / (2.0 * kB * kC));
}

double planarAngle(const Transform3D& X) { return std::atan2(X.linear()(1, 0), X.linear()(0, 0)); }

// The test's limits: the loop-closure error at every step, and the rocker angle's tolerance
// that follows from it. A closure error e at D moves the rocker tip by about e / sin(mu) across
// the rocker (mu the transmission angle), so the rocker angle by e / (c sin(mu)); mu stays
// above its value at the start (0.3 rad: 28.7 deg) over the motion (0.3 -> 1.8 rad).
constexpr double kClosureTolerance = 1e-4;
constexpr double kTheta0 = 0.3;
constexpr double kTheta1 = 1.8;
constexpr double kDriveTime = 2.0;

struct RunStats {
  double maxClosure = 0.0;
  double maxRockerError = 0.0;
  double maxStateResidual = 0.0;
  double finalTheta = 0.0;
  StepStatus status = StepStatus::kOk;
};

class FourBar : public ::testing::Test {
 protected:
  void load(const std::string& pin) {
    visgrab::test::writeFile(tmp_.path() / "fourbar.wc.xml", kFourBar);
    visgrab::test::writeFile(
        tmp_.path() / "fourbar.dwc.xml",
        fourBarDynamics((visgrab::test::sourceDir() / "scenes/materials.xml").generic_string(),
                        pin));
    dwc_ = rwsim::loaders::loadDynamicWorkCell(tmp_.path() / "fourbar.dwc.xml");
  }

  // The closed configuration at kTheta0 on the closed form's branch.
  rw::kinematics::State startState() const {
    const auto& device = *dwc_->workcell().findDevice("FourBar");
    rw::kinematics::State state = dwc_->workcell().defaultState();
    const FourBarPose p = closedForm(kTheta0);
    Q full(4);  // Crank, Coupler, Rocker, Pin
    full << kTheta0, p.beta - kTheta0, p.psi, p.beta - p.psi;
    device.parallel()->setFullQ(full, state);
    device.setQ(Q::Constant(1, kTheta0), state);
    return state;
  }

  Transform3D bodyPose(Simulator& sim, const std::string& joint) const {
    return sim.bodyPose(dwc_->findBody("FourBar." + joint));
  }

  // The crank follows a ramp from kTheta0 to kTheta1 over kDriveTime under the velocity-output
  // P law (P = 10 1/s, RobWork's gain), then holds.
  RunStats run() {
    Simulator sim(*dwc_);
    sim.reset(startState());
    const auto dev = dwc_->findDevice("FourBar");
    const auto* parallel = dwc_->workcell().findDevice("FourBar")->parallel();
    const double rate = (kTheta1 - kTheta0) / kDriveTime;
    RunStats s;
    while (sim.time() < kDriveTime + 0.25 && s.status == StepStatus::kOk) {
      const double t = sim.time();
      const double target = kTheta0 + rate * std::min(t, kDriveTime);
      const double theta = sim.jointPositions(dev)[0];
      const double v = (t < kDriveTime ? rate : 0.0) + 10.0 * (target - theta);
      sim.setMotorVelocityTargets(dev, Q::Constant(1, v));
      s.status = sim.step();
      const Vector3D d0 = bodyPose(sim, "Crank.Coupler") * Vector3D(kB, 0, 0);
      const Vector3D d1 = bodyPose(sim, "Rocker.Rocker") * Vector3D(kC, 0, 0);
      s.maxClosure = std::max(s.maxClosure, (d0 - d1).norm());
      const double crank = planarAngle(bodyPose(sim, "Crank.Crank"));
      const double rocker = planarAngle(bodyPose(sim, "Rocker.Rocker"));
      s.maxRockerError = std::max(
          s.maxRockerError,
          std::abs(std::remainder(rocker - closedForm(crank).psi, 2.0 * std::numbers::pi)));
      s.maxStateResidual =
          std::max(s.maxStateResidual, parallel->residual(0, sim.state()).position);
      s.finalTheta = sim.jointPositions(dev)[0];
    }
    return s;
  }

  visgrab::test::TempDir tmp_;
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc_;
};

TEST_F(FourBar, TheClosedFormIsClosed) {
  for (double theta = kTheta0; theta <= kTheta1; theta += 0.1) {
    const FourBarPose p = closedForm(theta);
    const double dx = kA * std::cos(theta) + kB * std::cos(p.beta);
    const double dy = kA * std::sin(theta) + kB * std::sin(p.beta);
    EXPECT_NEAR(std::hypot(dx - kD, dy), kC, 1e-12);
    EXPECT_GE(transmissionAngle(theta), transmissionAngle(kTheta0) - 1e-12);
  }
}

TEST_F(FourBar, ThePinWithoutALinkClosesTheLoopAsAHinge) {
  load("");
  const auto closures =
      rwsim::dynamics::loopClosures(*dwc_, dwc_->device(dwc_->findDevice("FourBar")));
  ASSERT_EQ(closures.size(), 1u);
  EXPECT_EQ(dwc_->workcell().frames().frame(closures[0].joint).name(), "FourBar.Rocker.Pin");
  EXPECT_EQ(dwc_->body(closures[0].parent).name, "FourBar.Rocker.Rocker");
  EXPECT_EQ(dwc_->body(closures[0].child).name, "FourBar.Crank.Coupler");
}

TEST_F(FourBar, CrankDrivenAgainstGravityKeepsTheLoopClosedAndTheRockerOnTheClosedForm) {
  load("");
  const RunStats s = run();
  ASSERT_EQ(s.status, StepStatus::kOk);
  EXPECT_NEAR(s.finalTheta, kTheta1, 0.01);
  EXPECT_LT(s.maxClosure, kClosureTolerance);
  EXPECT_LT(s.maxRockerError, kClosureTolerance / (kC * std::sin(transmissionAngle(kTheta0))));
  // The State read back carries the passive joints: its FK closes the junction too.
  EXPECT_LT(s.maxStateResidual, kClosureTolerance);
  std::printf("[ measured ] hinge closure: max gap %.3g m, max rocker error %.3g rad\n",
              s.maxClosure, s.maxRockerError);
}

// The same loop with the pin given a link body of its own: the junction is then a weld between
// the coupler and the pin (6 rows, 3 of them redundant in a planar loop).
TEST_F(FourBar, WithAPinLinkTheJunctionIsWeldedAndStaysClosed) {
  load(
      "    <RigidJoint joint=\"Rocker.Pin\"><Mass>0.01</Mass><COG>0 0 0</COG>"
      "<Inertia>1e-7 1e-7 1e-7</Inertia></RigidJoint>\n");
  const auto closures =
      rwsim::dynamics::loopClosures(*dwc_, dwc_->device(dwc_->findDevice("FourBar")));
  ASSERT_EQ(closures.size(), 1u);
  EXPECT_FALSE(closures[0].joint.valid());
  const RunStats s = run();
  ASSERT_EQ(s.status, StepStatus::kOk);
  EXPECT_NEAR(s.finalTheta, kTheta1, 0.01);
  EXPECT_LT(s.maxClosure, kClosureTolerance);
  EXPECT_LT(s.maxRockerError, kClosureTolerance / (kC * std::sin(transmissionAngle(kTheta0))));
  std::printf("[ measured ] weld closure: max gap %.3g m, max rocker error %.3g rad\n",
              s.maxClosure, s.maxRockerError);
}

// ------------------------------------------------------------- RobWork's Robotiq 2F-85 model
//
// RobWork's finger-control model (robotiq.wc.xml, by absolute path), with a dwc written here:
// the motor arms, outer links, fingers and inner links as bodies, LinkConnection (the joint
// where each loop meets, without geometry in RobWork's file) left without a link, so each
// junction closes with a hinge there. All three DOF close from Home over 1 s.
std::string robotiqDynamics(const std::string& workcell, const std::string& materials) {
  std::string links;
  for (const char* side : {"Left", "Right"}) {
    const std::string s = side;
    for (const std::string& joint : {s + "Motor.MotorJoint", s + "Motor.OuterLink",
                                     s + "Motor.Finger", s + "Passive.PassiveJoint"}) {
      links += "    <Link object=\"" + joint +
               "\"><Mass>0.02</Mass><EstimateInertia/><MaterialID>Finger</MaterialID></Link>\n";
    }
  }
  return "<DynamicWorkcell workcell=\"" + workcell + R"(">
  <Gravity>0 0 -9.81</Gravity>
  <Include file=")" +
         materials +
         R"("/>
  <RigidDevice device="RobotiqFingerControl">
    <ForceLimit joint="LeftMotor.MotorJoint">2</ForceLimit>
    <ForceLimit joint="RightMotor.MotorJoint">2</ForceLimit>
    <ForceLimit joint="LeftPassive.PassiveJoint">2</ForceLimit>
    <ForceLimit joint="RightPassive.PassiveJoint">2</ForceLimit>
    <FixedBase frame="Base"><MaterialID>Finger</MaterialID></FixedBase>
)" + links +
         R"(  </RigidDevice>
</DynamicWorkcell>
)";
}

// World pose of a frame from the simulated pose of the body that carries it.
Transform3D framePose(const rwsim::dynamics::DynamicWorkCell& dwc, const Simulator& sim,
                      rw::kinematics::FrameId frame) {
  auto body = dwc.bodyOfFrame(frame);
  if (!body.valid()) body = dwc.bodyAbove(frame);
  return sim.bodyPose(body) * rw::kinematics::relativeTransform(dwc.workcell().frames(),
                                                                sim.state(), dwc.body(body).frame,
                                                                frame);
}

TEST(RobotiqFingerControl, ClosingForOneSecondKeepsBothJunctionsClosed) {
  REQUIRE_COMPAT_DATA(data);
  visgrab::test::TempDir tmp;
  const auto workcell = data / "devices/Robotiq-2-finger-85/robotiq.wc.xml";
  visgrab::test::writeFile(
      tmp.path() / "robotiq.dwc.xml",
      robotiqDynamics(workcell.generic_string(),
                      (visgrab::test::sourceDir() / "scenes/materials.xml").generic_string()));
  const auto dwc = rwsim::loaders::loadDynamicWorkCell(tmp.path() / "robotiq.dwc.xml");
  const auto& device = *dwc->workcell().findDevice("RobotiqFingerControl");
  const auto* parallel = device.parallel();
  ASSERT_NE(parallel, nullptr);
  const auto dev = dwc->findDevice("RobotiqFingerControl");
  ASSERT_EQ(rwsim::dynamics::loopClosures(*dwc, dwc->device(dev)).size(), 2u);

  // The target must be a closed configuration (setQ throws otherwise).
  const Q q1 = Q::Constant(3, 0.5);
  rw::kinematics::State target = dwc->workcell().defaultState();
  ASSERT_NO_THROW(device.setQ(q1, target));

  Simulator sim(*dwc);
  sim.reset(dwc->workcell().defaultState());
  const Q q0 = sim.jointPositions(dev);
  double maxBodyGap = 0.0;
  std::vector<double> stateGap(parallel->junctions().size(), 0.0);
  StepStatus status = StepStatus::kOk;
  while (sim.time() < 1.0 && status == StepStatus::kOk) {
    const double f = std::min(sim.time() / 0.8, 1.0);
    const Q goal = q0 + f * (q1 - q0);
    const Q v = (sim.time() < 0.8 ? Q((q1 - q0) / 0.8) : Q(Q::Zero(3))) +
                10.0 * (goal - sim.jointPositions(dev));
    sim.setMotorVelocityTargets(dev, v);
    status = sim.step();
    for (std::size_t j = 0; j < parallel->junctions().size(); ++j) {
      const auto& legs = parallel->junctions()[j].legs;
      const Vector3D gap = framePose(*dwc, sim, legs[0].end).translation() -
                           framePose(*dwc, sim, legs[1].end).translation();
      maxBodyGap = std::max(maxBodyGap, gap.norm());
      stateGap[j] = std::max(stateGap[j], parallel->residual(j, sim.state()).position);
    }
  }
  ASSERT_EQ(status, StepStatus::kOk) << sim.failureDetail();
  EXPECT_LT(maxBodyGap, kClosureTolerance);
  EXPECT_LT(stateGap[0], kClosureTolerance);
  EXPECT_LT((sim.jointPositions(dev) - q1).cwiseAbs().maxCoeff(), 0.02);
  std::printf("[ measured ] Robotiq closure: max gap %.3g m (bodies), %.3g / %.3g m (state FK)\n",
              maxBodyGap, stateGap[0], stateGap[1]);
}

}  // namespace
