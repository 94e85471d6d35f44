// The project's Robotiq-2F-85-like gripper (scenes/hands/robotiq2f85/robotiq2f85.wc.xml): a
// parallel device with one active joint and a closed parallel four-bar linkage per finger. Pad
// positions against the linkage worked out by hand (the file's header), now through the closure
// solver: the opening is 85 mm at q = 0, 50 mm at q = 0.3594, 0.55 mm at q = 0.8; the pads stay
// parallel; each linkage stays closed.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene_test_helpers.hpp"

namespace {

using rw::math::Q;
using rw::math::Vector3D;
using visgrab::test::scenes::deviceOf;
using visgrab::test::scenes::worldPose;

class Robotiq2F85 : public ::testing::Test {
 protected:
  void SetUp() override {
    wc_ = rw::loaders::loadWorkCell(
        visgrab::test::sourceDir() / "scenes/hands/robotiq2f85/robotiq2f85.wc.xml", &warnings_);
  }
  rw::kinematics::State stateAt(double q) const {
    rw::kinematics::State state = wc_->defaultState();
    deviceOf(*wc_, "Robotiq2F85").setQ(Q::Constant(1, q), state);
    return state;
  }
  Vector3D at(const rw::kinematics::State& s, const char* frame) const {
    return worldPose(*wc_, s, std::string("Robotiq2F85.") + frame).translation();
  }

  std::unique_ptr<rw::models::WorkCell> wc_;
  std::vector<rw::common::Diagnostic> warnings_;
};

// One DOF (the right outer knuckle), the left outer knuckle dependent on it (one motor for both
// sides), and each finger's inner finger, inner knuckle and pin passive, closed by that finger's
// junction: the linkage, not dependent joints, keeps the pads parallel.
TEST_F(Robotiq2F85, OneDofTwoClosedLinkages) {
  for (const auto& w : warnings_) ADD_FAILURE() << w.format();
  const auto& device = deviceOf(*wc_, "Robotiq2F85");
  EXPECT_EQ(device.dof(), 1);
  ASSERT_NE(device.parallel(), nullptr);
  const auto name = [&](rw::kinematics::FrameId f) { return wc_->frames().frame(f).name(); };
  ASSERT_EQ(device.activeJoints().size(), 1u);
  EXPECT_EQ(name(device.activeJoints()[0]), "Robotiq2F85.RightOuterKnuckle");
  std::vector<std::string> dependent;
  std::vector<std::string> passive;
  for (const auto j : device.joints()) {
    if (wc_->frames().frame(j).isDependent()) dependent.push_back(name(j));
    if (wc_->frames().frame(j).isPassive()) passive.push_back(name(j));
  }
  EXPECT_EQ(dependent, std::vector<std::string>{"Robotiq2F85.LeftOuterKnuckle"});
  EXPECT_EQ(passive, (std::vector<std::string>{
                         "Robotiq2F85.RightInnerFinger", "Robotiq2F85.RightInnerKnuckle",
                         "Robotiq2F85.RightInnerLeg.Pin", "Robotiq2F85.LeftInnerFinger",
                         "Robotiq2F85.LeftInnerKnuckle", "Robotiq2F85.LeftInnerLeg.Pin"}));
  const auto& junctions = device.parallel()->junctions();
  ASSERT_EQ(junctions.size(), 2u);
  for (const auto& [junction, side] : {std::pair{0, "Right"}, std::pair{1, "Left"}}) {
    const auto& legs = junctions[static_cast<std::size_t>(junction)].legs;
    ASSERT_EQ(legs.size(), 2u);
    EXPECT_EQ(name(legs[0].end), std::string("Robotiq2F85.") + side + "OuterLeg.End");
    EXPECT_EQ(name(legs[1].end), std::string("Robotiq2F85.") + side + "InnerKnuckleTip");
  }
}

// By hand (header of the file): with the knuckle turned by q about -x, the inner finger's pivot
// B = A + (-0.0376 cos q + 0.0430 sin q, 0.0376 sin q + 0.0430 cos q) in Base (y, z), A = (-0.0306,
// 0.0549); the pad's grip face centre = B + (0.0225 + 0.003175, 0.03242). The left pad mirrors
// it (y -> -y).
TEST_F(Robotiq2F85, PadsWhereTheLinkageWorkedByHandPutsThem) {
  for (const double q : {0.0, 0.3594, 0.8}) {
    SCOPED_TRACE("q = " + std::to_string(q));
    const double by = -0.0306 - 0.0376 * std::cos(q) + 0.0430 * std::sin(q);
    const double bz = 0.0549 + 0.0376 * std::sin(q) + 0.0430 * std::cos(q);
    const Vector3D right(0.0, by + 0.025675, bz + 0.03242);
    const auto s = stateAt(q);
    EXPECT_LT((at(s, "RightPad") - right).norm(), 1e-9);
    EXPECT_LT((at(s, "LeftPad") - Vector3D(0.0, -right.y(), right.z())).norm(), 1e-9);
  }
  // The three openings written out.
  EXPECT_NEAR(2 * -at(stateAt(0.0), "RightPad").y(), 0.08505, 1e-6);
  EXPECT_NEAR(2 * -at(stateAt(0.3594), "RightPad").y(), 0.0500, 1e-5);
  EXPECT_NEAR(2 * -at(stateAt(0.8), "RightPad").y(), 0.00055, 1e-6);
}

TEST_F(Robotiq2F85, PadsStayParallelAndTheLinkageClosed) {
  const auto R0 = worldPose(*wc_, stateAt(0.0), "Robotiq2F85.RightPad").linear();
  const auto L0 = worldPose(*wc_, stateAt(0.0), "Robotiq2F85.LeftPad").linear();
  // The pads push towards each other along Base y.
  EXPECT_LT((R0.col(2) - Vector3D::UnitY()).norm(), 1e-9);
  EXPECT_LT((L0.col(2) + Vector3D::UnitY()).norm(), 1e-9);
  for (int i = 1; i <= 8; ++i) {
    const double q = 0.1 * i;
    SCOPED_TRACE("q = " + std::to_string(q));
    const auto s = stateAt(q);
    EXPECT_LT((worldPose(*wc_, s, "Robotiq2F85.RightPad").linear() - R0).norm(), 1e-8);
    EXPECT_LT((worldPose(*wc_, s, "Robotiq2F85.LeftPad").linear() - L0).norm(), 1e-8);
    EXPECT_LT((at(s, "RightInnerKnuckleTip") - at(s, "RightInnerFingerPin")).norm(), 1e-8);
    EXPECT_LT((at(s, "LeftInnerKnuckleTip") - at(s, "LeftInnerFingerPin")).norm(), 1e-8);
  }
}

TEST_F(Robotiq2F85, TcpBetweenThePadsClosingAlongX) {
  const auto tcp = worldPose(*wc_, stateAt(0.3594), "Robotiq2F85.TCP");
  EXPECT_LT((tcp.translation() - Vector3D(0, 0, 0.1408)).norm(), 1e-9);
  EXPECT_LT((tcp.linear().col(2) - Vector3D::UnitZ()).norm(), 1e-9);  // approach
  EXPECT_LT((tcp.linear().col(0) - Vector3D::UnitY()).norm(), 1e-9);  // closing
  // At the 50 mm opening the pads' centres are level with the TCP.
  EXPECT_NEAR(at(stateAt(0.3594), "RightPad").z(), 0.1408, 1e-5);
}

}  // namespace
