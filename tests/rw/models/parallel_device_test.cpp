// Parallel devices: a four-bar linkage written inline, checked against its closed-form
// solution, and RobWork's two Robotiq models (RW_COMPAT_DATA) against the numbers of RobWork's
// gtest/models/ParallelDeviceTest.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "rw/models/parallel_kinematics.hpp"
#include "support/test_support.hpp"

namespace {

using rw::kinematics::FrameId;
using rw::kinematics::State;
using rw::math::Q;
using rw::math::Transform3D;
using rw::models::ClosureError;
using rw::models::Device;
using rw::models::WorkCell;

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------- the four-bar linkage
//
// Ground pivots O = (0, 0) and G = (d, 0). The crank (length a, angle theta, active) turns
// about O; the coupler (length b) is pinned to the crank tip A and turns by phi relative to the
// crank; the rocker (length c, angle psi) turns about G; the pin at the coupler's far end D
// turns by rho relative to the rocker. The junction holds the coupler's end (leg "Crank") and
// the rocker's pin (leg "Rocker") together, position and orientation:
//   D = A + b (cos(theta + phi), sin(theta + phi)) = G + c (cos psi, sin psi)
//   theta + phi = psi + rho.
// a = 2, b = 2.5, c = 2, d = 3: not a Grashof linkage (s + l = 5 > p + q = 4.5), so the crank
// cannot turn all the way: the loop closes only while |A - G| <= b + c, that is
// a^2 + d^2 - 2 a d cos(theta) <= 4.5^2, cos(theta) >= -0.6042, theta <= 2.2197 rad.
constexpr double kA = 2.0;
constexpr double kB = 2.5;
constexpr double kC = 2.0;
constexpr double kD = 3.0;

const char* const kFourBar = R"(<WorkCell name="FourBar">
 <ParallelDevice name="FourBar">
  <Frame name="Base"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Frame>
  <SerialChain name="Crank">
   <Joint name="Crank" type="Revolute"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Joint>
   <Joint name="Coupler" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>2 0 0</Pos></Joint>
   <Frame name="CouplerEnd"><RPY>0 0 0</RPY><Pos>2.5 0 0</Pos></Frame>
  </SerialChain>
  <Frame name="Ground" refframe="Base"><RPY>0 0 0</RPY><Pos>3 0 0</Pos></Frame>
  <SerialChain name="Rocker">
   <Joint name="Rocker" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Joint>
   <Joint name="Pin" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>2 0 0</Pos></Joint>
  </SerialChain>
  <Junction>
   <Chains>Crank</Chains>
   <Chains>Rocker</Chains>
  </Junction>
 </ParallelDevice>
</WorkCell>
)";

// The closed form, on the branch where D lies to the left of the line from A to G:
// with v = G - A and L = |v|, the coupler's absolute angle is beta = atan2(v) + alpha with
// cos(alpha) = (b^2 + L^2 - c^2) / (2 b L) (law of cosines in the triangle A, D, G).
struct FourBarPose {
  double phi;  // coupler relative to crank
  double psi;  // rocker
  double rho;  // pin, relative to rocker
};

FourBarPose fourBarClosedForm(double theta) {
  const double ax = kA * std::cos(theta);
  const double ay = kA * std::sin(theta);
  const double vx = kD - ax;
  const double vy = -ay;
  const double L = std::hypot(vx, vy);
  const double alpha = std::acos((kB * kB + L * L - kC * kC) / (2.0 * kB * L));
  const double beta = std::atan2(vy, vx) + alpha;
  const double dx = ax + kB * std::cos(beta);
  const double dy = ay + kB * std::sin(beta);
  const double psi = std::atan2(dy, dx - kD);
  return {beta - theta, psi, beta - psi};
}

// x - y as an angle in (-pi, pi].
double angleDifference(double x, double y) { return std::remainder(x - y, 2.0 * kPi); }

std::unique_ptr<WorkCell> loadFourBar() {
  return rw::loaders::loadWorkCellFromString(kFourBar, "fourbar.wc.xml");
}

TEST(ParallelDevice, FourBarStructure) {
  const auto wc = loadFourBar();
  const Device* device = wc->findDevice("FourBar");
  ASSERT_NE(device, nullptr);
  ASSERT_EQ(device->kind(), Device::Kind::kParallel);
  const auto* parallel = device->parallel();
  ASSERT_NE(parallel, nullptr);
  EXPECT_EQ(device->dof(), 1);
  EXPECT_EQ(parallel->fullDof(), 4);
  EXPECT_EQ(parallel->allJoints().size(), 4u);
  EXPECT_EQ(parallel->passiveJoints().size(), 3u);
  ASSERT_EQ(parallel->junctions().size(), 1u);
  const auto& legs = parallel->junctions()[0].legs;
  ASSERT_EQ(legs.size(), 2u);
  EXPECT_EQ(wc->frames().frame(legs[0].start).name(), "FourBar.Base");
  EXPECT_EQ(wc->frames().frame(legs[0].end).name(), "FourBar.Crank.CouplerEnd");
  EXPECT_EQ(wc->frames().frame(legs[1].start).name(), "FourBar.Base");
  EXPECT_EQ(wc->frames().frame(legs[1].end).name(), "FourBar.Rocker.Pin");
  EXPECT_EQ(legs[1].chains, std::vector<std::string>{"Rocker"});
  EXPECT_EQ(wc->frames().frame(device->base()).name(), "FourBar.Base");
  EXPECT_EQ(wc->frames().frame(device->ends().front()).name(), "FourBar.Crank.CouplerEnd");
}

// RobWork's older form: without <Junction>, all serial chains are the legs of one junction.
TEST(ParallelDevice, WithoutJunctionsAllChainsAreTheLegsOfOneJunction) {
  std::string xml = kFourBar;
  const auto from = xml.find("  <Junction>");
  const auto to = xml.find("</Junction>\n") + std::string("</Junction>\n").size();
  xml.erase(from, to - from);
  const auto wc = rw::loaders::loadWorkCellFromString(xml, "fourbar.wc.xml");
  const auto* parallel = wc->findDevice("FourBar")->parallel();
  ASSERT_NE(parallel, nullptr);
  ASSERT_EQ(parallel->junctions().size(), 1u);
  const auto& legs = parallel->junctions()[0].legs;
  ASSERT_EQ(legs.size(), 2u);
  EXPECT_EQ(legs[0].chains, std::vector<std::string>{"Crank"});
  EXPECT_EQ(wc->frames().frame(legs[0].end).name(), "FourBar.Crank.CouplerEnd");
  EXPECT_EQ(legs[1].chains, std::vector<std::string>{"Rocker"});
  EXPECT_EQ(wc->frames().frame(legs[1].end).name(), "FourBar.Rocker.Pin");
}

TEST(ParallelDevice, FourBarFollowsTheClosedFormWithin1e9Rad) {
  const auto wc = loadFourBar();
  const Device& device = *wc->findDevice("FourBar");
  State state = wc->defaultState();
  // Start on the branch of the closed form; every later solve starts from the previous pose.
  const FourBarPose start = fourBarClosedForm(0.3);
  device.parallel()->setFullQ(Q{{0.3, start.phi, start.psi, start.rho}}, state);
  // Up to 2.1 rad and back in steps. (Near the limit 2.2197 the two assembly modes meet, and
  // a solve started there may land on either: the solver finds a closure near its start, not
  // a chosen branch.)
  for (const double theta :
       {0.3, 0.5, 0.8, 1.2, 1.6, 1.9, 2.1, 1.9, 1.6, 1.2, 0.8, 0.4, 0.0, -0.4, -0.8}) {
    SCOPED_TRACE("theta = " + std::to_string(theta));
    device.setQ(Q{{theta}}, state);
    const FourBarPose truth = fourBarClosedForm(theta);
    const Q full = device.parallel()->getFullQ(state);
    EXPECT_EQ(full[0], theta);
    EXPECT_NEAR(angleDifference(full[1], truth.phi), 0.0, 1e-9);
    EXPECT_NEAR(angleDifference(full[2], truth.psi), 0.0, 1e-9);
    EXPECT_NEAR(angleDifference(full[3], truth.rho), 0.0, 1e-9);
    const auto residual = device.parallel()->residual(0, state);
    EXPECT_LE(residual.position, 1e-12);
    EXPECT_LE(residual.angle, 1e-12);
  }
}

TEST(ParallelDevice, FourBarCrankAngleThatCannotCloseIsAnErrorNamingTheJunction) {
  const auto wc = loadFourBar();
  const Device& device = *wc->findDevice("FourBar");
  State state = wc->defaultState();
  device.setQ(Q{{1.0}}, state);
  const State before = state;
  // theta = 2.6: |A - G| = sqrt(13 - 12 cos 2.6) = 4.825 > b + c = 4.5, so the coupler and the
  // rocker, stretched out, still miss each other by 0.325.
  try {
    device.setQ(Q{{2.6}}, state);
    FAIL() << "closed an impossible loop";
  } catch (const ClosureError& e) {
    EXPECT_EQ(e.junction(), 0u);
    // The solver minimises position and orientation error together, so the gap it stops at
    // is the geometric one, 0.3252, or a little more.
    const double gap = std::sqrt(13.0 - 12.0 * std::cos(2.6)) - 4.5;
    EXPECT_GE(e.residual().position, gap - 1e-12);
    EXPECT_LE(e.residual().position, gap + 1e-3);
    EXPECT_NE(std::string(e.what()).find("device \"FourBar\": junction 1 (leg \"Crank\", leg "
                                         "\"Rocker\") cannot be closed: residual 0.325 m"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(state.values(), before.values());
}

TEST(ParallelDevice, FullQRoundTripsAndSetsNoActiveJointItDoesNotName) {
  const auto wc = loadFourBar();
  const Device& device = *wc->findDevice("FourBar");
  State state = wc->defaultState();
  const Q q{{0.1, 0.2, 0.3, 0.4}};
  device.parallel()->setFullQ(q, state);
  EXPECT_EQ(device.parallel()->getFullQ(state), q);
  EXPECT_EQ(device.getQ(state), Q{{0.1}});
  EXPECT_THROW(device.parallel()->setFullQ(Q{{0.1}}, state), std::invalid_argument);
  EXPECT_THROW(device.setQ(Q{{0.1, 0.2}}, state), std::invalid_argument);
}

// A passive joint coupled to another passive joint with gain -2 on a leg. Leg "Slide": a
// prismatic joint J along x, so its end is at (J, 0) with the base's orientation. Leg "Arm": a
// passive revolute K at the base, a link of 1, the dependent joint M = -2 K, a link of 1, a
// passive revolute N; its end is at (cos K + cos(K - 2K), sin K + sin(-K)) = (2 cos K, 0) with
// orientation K - 2K + N. Closed: K = acos(J / 2), N = K, M = -2 K.
const char* const kCoupled = R"(<WorkCell name="Coupled">
 <ParallelDevice name="C">
  <Frame name="Base"/>
  <SerialChain name="Slide">
   <Joint name="J" type="Prismatic"><RPY>0 90 0</RPY><Pos>0 0 0</Pos></Joint>
   <Frame name="End"><RPY>0 -90 0</RPY><Pos>0 0 0</Pos></Frame>
  </SerialChain>
  <Frame name="ArmBase" refframe="Base"/>
  <SerialChain name="Arm">
   <Joint name="K" type="Revolute" state="Passive"/>
   <Joint name="M" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>1 0 0</Pos>
    <Depend on="K" gain="-2" offset="0"/></Joint>
   <Joint name="N" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>1 0 0</Pos></Joint>
  </SerialChain>
  <Junction><Chains>Slide</Chains><Chains>Arm</Chains></Junction>
 </ParallelDevice>
</WorkCell>
)";

TEST(ParallelDevice, DependentJointOnALegMovesWithItsOwnerTimesItsGain) {
  const auto wc = rw::loaders::loadWorkCellFromString(kCoupled, "coupled.wc.xml");
  const Device& device = *wc->findDevice("C");
  const auto& p = *device.parallel();
  ASSERT_EQ(p.passiveJoints().size(), 2u);  // K and N; M follows K
  ASSERT_EQ(p.dependentJoints().size(), 1u);
  State state = wc->defaultState();
  p.setFullQ(Q{{1.0, kPi / 3, kPi / 3}}, state);
  const auto& M = wc->frames().frame(p.dependentJoints().front());
  for (const double j : {1.2, 1.5, 1.9, 0.8, 0.3}) {
    SCOPED_TRACE("J = " + std::to_string(j));
    device.setQ(Q{{j}}, state);
    const double k = std::acos(j / 2.0);
    const Q full = p.getFullQ(state);
    EXPECT_NEAR(full[1], k, 1e-9);
    EXPECT_NEAR(full[2], k, 1e-9);
    EXPECT_NEAR(M.jointValue(state), -2.0 * k, 1e-9);
  }
}

// ---------------------------------------------------------------------- RobWork's Robotiq

class Robotiq : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto data = visgrab::test::compatDataDir();
    if (!data) {
      GTEST_SKIP() << "RW_COMPAT_DATA is not set: RobWork's files are needed for this "
                      "compatibility test";
    }
    wc_ = rw::loaders::loadWorkCell(*data / "devices/Robotiq-2-finger-85/robotiq.wc.xml");
    distance_ = wc_->findDevice("RobotiqDistanceControl");
    finger_ = wc_->findDevice("RobotiqFingerControl");
    ASSERT_NE(distance_, nullptr);
    ASSERT_NE(finger_, nullptr);
    ASSERT_NE(distance_->parallel(), nullptr);
    ASSERT_NE(finger_->parallel(), nullptr);
  }

  std::string name(FrameId id) const { return wc_->frames().frame(id).name(); }
  Transform3D baseTend(const Device& d, const State& state) const {
    return rw::kinematics::relativeTransform(wc_->frames(), state, d.base(), d.ends().front());
  }
  // Every leg of every junction reaches the same pose from the junction's start (RobWork's
  // getJunctions()[j][i]->baseTend(state) compared with equal(..., 1e-6)).
  void expectClosed(const Device& d, const State& state) const {
    for (const auto& junction : d.parallel()->junctions()) {
      const auto& first = junction.legs.front();
      const Transform3D X0 =
          rw::kinematics::relativeTransform(wc_->frames(), state, first.start, first.end);
      for (const auto& leg : junction.legs) {
        EXPECT_TRANSFORM_NEAR(
            rw::kinematics::relativeTransform(wc_->frames(), state, leg.start, leg.end), X0, 1e-6);
      }
    }
  }

  std::unique_ptr<WorkCell> wc_;
  const Device* distance_ = nullptr;
  const Device* finger_ = nullptr;
};

TEST_F(Robotiq, NamesFramesAndSizesAreRobWorks) {
  EXPECT_EQ(distance_->name(), "RobotiqDistanceControl");
  EXPECT_EQ(finger_->name(), "RobotiqFingerControl");
  const State state = wc_->defaultState();
  const Transform3D expected = rw::math::makeTransform(
      Eigen::AngleAxisd(kPi / 2, rw::math::Vector3D::UnitY()).toRotationMatrix(),
      rw::math::Vector3D(-0.0425, 0.119008, 0));
  EXPECT_TRANSFORM_NEAR(baseTend(*distance_, state), expected, 1e-6);
  EXPECT_TRANSFORM_NEAR(baseTend(*finger_, state), expected, 1e-4);
  EXPECT_EQ(name(distance_->base()), "RobotiqDistanceControl.Base");
  EXPECT_EQ(name(distance_->ends().front()), "RobotiqDistanceControl.LeftMotorEnd");
  EXPECT_EQ(name(finger_->base()), "RobotiqFingerControl.Base");
  EXPECT_EQ(name(finger_->ends().front()), "RobotiqFingerControl.LeftMotorEnd");

  // RobWork's getJoints() is our actuatedJoints(); its getDOF() and bounds our dof() and limits.
  const auto* dist = distance_->parallel();
  const auto* fing = finger_->parallel();
  EXPECT_EQ(dist->actuatedJoints().size(), 3u);
  EXPECT_EQ(distance_->dof(), 3);
  EXPECT_EQ(distance_->lowerLimits().size(), 3);
  EXPECT_EQ(distance_->upperLimits().size(), 3);
  EXPECT_EQ(distance_->velocityLimits().size(), 3);
  EXPECT_EQ(distance_->accelerationLimits().size(), 3);
  EXPECT_EQ(fing->actuatedJoints().size(), 4u);  // two coupled motor joints, one DOF
  EXPECT_EQ(finger_->dof(), 3);
  EXPECT_EQ(finger_->lowerLimits().size(), 3);
  EXPECT_EQ(finger_->velocityLimits().size(), 3);
  EXPECT_EQ(finger_->accelerationLimits().size(), 3);

  ASSERT_EQ(dist->junctions().size(), 3u);
  for (const auto& j : dist->junctions()) EXPECT_EQ(j.legs.size(), 2u);
  ASSERT_EQ(fing->junctions().size(), 2u);
  for (const auto& j : fing->junctions()) EXPECT_EQ(j.legs.size(), 2u);
  EXPECT_EQ(dist->allJoints().size(), 13u);
  EXPECT_EQ(dist->fullDof(), 12);
  EXPECT_EQ(dist->fullLowerLimits().size(), 12);
  EXPECT_EQ(dist->fullUpperLimits().size(), 12);
  // Limits per joint in full-configuration order: MotorJoint [-10, 100] deg first,
  // FingerDistance [0, 0.085] m eleventh.
  EXPECT_NEAR(dist->fullLowerLimits()[0], -10.0 * kPi / 180.0, 1e-15);
  EXPECT_NEAR(dist->fullUpperLimits()[0], 100.0 * kPi / 180.0, 1e-15);
  EXPECT_EQ(dist->fullLowerLimits()[10], 0.0);
  EXPECT_EQ(dist->fullUpperLimits()[10], 0.085);
  EXPECT_EQ(fing->allJoints().size(), 10u);
  EXPECT_EQ(fing->fullDof(), 9);
  EXPECT_EQ(fing->fullLowerLimits().size(), 9);
  EXPECT_EQ(distance_->getQ(state).size(), 3);
  EXPECT_EQ(dist->getFullQ(state).size(), 12);
  EXPECT_EQ(finger_->getQ(state).size(), 3);
  EXPECT_EQ(fing->getFullQ(state).size(), 9);
  // The third junction: leg "LeftPassive Distance" against leg "RightPassive".
  const auto& third = dist->junctions()[2].legs;
  EXPECT_EQ(third[0].chains, (std::vector<std::string>{"LeftPassive", "Distance"}));
  EXPECT_EQ(name(third[0].end), "RobotiqDistanceControl.DistanceEnd");
  EXPECT_EQ(name(third[1].end), "RobotiqDistanceControl.RightPassiveEnd");
}

TEST_F(Robotiq, DistanceControlSetQGivesRobWorksFullQ) {
  State state = wc_->defaultState();
  expectClosed(*distance_, state);
  distance_->setQ(Q{{0.0, 0.04, 0.0}}, state);
  const Q full = distance_->parallel()->getFullQ(state);
  ASSERT_EQ(full.size(), 12);
  const Q robwork{{0.4506, 0.0008, -0.4514, 0.4511, -0.4511, 0.0008, -0.4514, 0.4511, -0.4511}};
  EXPECT_VECTOR_NEAR(Q(full.head(9)), robwork, 1e-4);
  EXPECT_EQ(full[9], 0.0);
  EXPECT_EQ(full[10], 0.04);
  EXPECT_EQ(full[11], 0.0);
  expectClosed(*distance_, state);

  distance_->setQ(Q{{-0.35, 0.04, 0.35}}, state);
  const Q second = distance_->parallel()->getFullQ(state);
  const Q robworkSecond{{0.4858, -0.2596, 0.1237, 0.2841, 0.0659, -0.2596, 0.1237, 0.2841, 0.0658}};
  EXPECT_VECTOR_NEAR(Q(second.head(9)), robworkSecond, 1e-4);
  EXPECT_EQ(second[9], -0.35);
  EXPECT_EQ(second[10], 0.04);
  EXPECT_EQ(second[11], 0.35);
  expectClosed(*distance_, state);
}

TEST_F(Robotiq, FingerControlSetQGivesRobWorksFullQ) {
  State state = wc_->defaultState();
  finger_->setQ(Q{{0.35, 0.25, 0.25}}, state);
  const Q robwork{{0.35, -0.1294, -0.0422, 0.25, -0.0716, -0.1294, -0.0422, 0.25, -0.0716}};
  EXPECT_VECTOR_NEAR(finger_->parallel()->getFullQ(state), robwork, 1e-4);
  expectClosed(*finger_, state);
  finger_->setQ(Q{{0.5, 0.52, 0.2}}, state);
  const Q robworkSecond{{0.5, 0.0327, -0.5776, 0.52, -0.5650, -0.3623, 0.3618, 0.2, 0.2995}};
  EXPECT_VECTOR_NEAR(finger_->parallel()->getFullQ(state), robworkSecond, 1e-4);
  expectClosed(*finger_, state);
}

TEST_F(Robotiq, Ac3dMeshesAreFoundWhereTheStlIsAbsent) {
  // geometry/finger has only finger.ac; RobWork's lookup falls back to it for both uses.
  const FrameId finger = wc_->findFrame("RobotiqDistanceControl.LeftMotor.Finger");
  ASSERT_TRUE(finger.valid());
  const auto* object = wc_->findObject(finger);
  ASSERT_NE(object, nullptr);
  ASSERT_FALSE(object->visual.empty());
  ASSERT_FALSE(object->collision.empty());
  EXPECT_NE(object->visual.front().geometry, nullptr);
}

}  // namespace
