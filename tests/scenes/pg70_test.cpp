// The project's PG70 (scenes/hands/pg70/pg70.wc.xml): jaw and grasp frames against positions
// worked out by hand from the model's numbers, and the device interface.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "scene_test_helpers.hpp"

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rw::models::Device;
using rw::models::WorkCell;
using visgrab::test::scenes::deviceOf;
using visgrab::test::scenes::frameOf;
using visgrab::test::scenes::projectPg70File;
using visgrab::test::scenes::worldPose;

class Pg70 : public ::testing::Test {
 protected:
  void SetUp() override { wc_ = rw::loaders::loadWorkCell(projectPg70File(), &warnings_); }

  rw::kinematics::State stateAt(double q) const {
    rw::kinematics::State state = wc_->defaultState();
    deviceOf(*wc_, "PG70").setQ(Q::Constant(1, q), state);
    return state;
  }

  std::unique_ptr<WorkCell> wc_;
  std::vector<rw::common::Diagnostic> warnings_;
};

TEST_F(Pg70, LoadsWithoutWarnings) {
  for (const auto& w : warnings_) ADD_FAILURE() << w.format();
}

// By hand: Base is Movable at the identity on WORLD (a bare device file).
// RightFinger: <RPY>0 0 90</RPY><Pos>0 -0.017 0.093</Pos>, prismatic: X = T(0,-0.017,0.093)
// Rx(90 deg) Tz(q). Rx(90 deg) turns the joint's z axis (0,0,1) into (0, -sin 90, cos 90) =
// (0,-1,0), so the origin is at (0, -0.017 - q, 0.093). TCPRight has no offset.
// LeftFinger: <Pos>0 0.017 0.093</Pos>, same rotation, q_left = -1 * q (Depend gain -1), so its
// origin is at (0, 0.017 + q, 0.093).
TEST_F(Pg70, JawTcpsAtClosedAndFullyOpen) {
  for (const double q : {0.0, 0.035}) {
    SCOPED_TRACE("q = " + std::to_string(q));
    const auto state = stateAt(q);
    EXPECT_VECTOR_NEAR(worldPose(*wc_, state, "PG70.TCPRight").translation(),
                       Vector3D(0, -0.017 - q, 0.093), 1e-12);
    EXPECT_VECTOR_NEAR(worldPose(*wc_, state, "PG70.TCPLeft").translation(),
                       Vector3D(0, 0.017 + q, 0.093), 1e-12);
  }
  // The two numbers written out: closed and fully open.
  EXPECT_VECTOR_NEAR(worldPose(*wc_, stateAt(0.035), "PG70.TCPRight").translation(),
                     Vector3D(0, -0.052, 0.093), 1e-12);
  EXPECT_VECTOR_NEAR(worldPose(*wc_, stateAt(0.035), "PG70.TCPLeft").translation(),
                     Vector3D(0, 0.052, 0.093), 1e-12);
}

// By hand: TCPPG70 <RPY>90 0 0</RPY><Pos>0 0 0.14</Pos> on Base: Rz(90 deg) =
// [0 -1 0; 1 0 0; 0 0 1] at (0, 0, 0.14), whatever q is.
TEST_F(Pg70, GraspTcpIsFourteenCentimetresAboveTheBase) {
  Transform3D expected = Transform3D::Identity();
  expected.linear() << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  expected.translation() = Vector3D(0, 0, 0.14);
  for (const double q : {0.0, 0.035}) {
    EXPECT_TRANSFORM_NEAR(worldPose(*wc_, stateAt(q), "PG70.TCPPG70"), expected, 1e-12);
  }
  const auto& properties = wc_->frames().frame(frameOf(*wc_, "PG70.TCPPG70")).properties();
  ASSERT_TRUE(properties.contains("minJawWidth"));
  ASSERT_TRUE(properties.contains("maxJawWidth"));
  EXPECT_EQ(std::get<double>(properties.at("minJawWidth").value), 0.01);
  EXPECT_EQ(std::get<double>(properties.at("maxJawWidth").value), 0.09);
}

TEST_F(Pg70, OneDofWithADependentLeftFinger) {
  const Device& pg70 = deviceOf(*wc_, "PG70");
  EXPECT_EQ(pg70.kind(), Device::Kind::kTree);
  EXPECT_EQ(pg70.dof(), 1);
  ASSERT_EQ(pg70.activeJoints().size(), 1u);
  EXPECT_EQ(pg70.activeJoints()[0], frameOf(*wc_, "PG70.RightFinger"));
  EXPECT_VECTOR_NEAR(pg70.lowerLimits(), Q::Constant(1, 0.0), 0.0);
  EXPECT_VECTOR_NEAR(pg70.upperLimits(), Q::Constant(1, 0.035), 0.0);
  EXPECT_VECTOR_NEAR(pg70.velocityLimits(), Q::Constant(1, 0.06), 0.0);
  const auto& left = wc_->frames().frame(frameOf(*wc_, "PG70.LeftFinger"));
  EXPECT_EQ(left.type(), rw::kinematics::FrameType::kPrismatic);
  ASSERT_TRUE(left.isDependent());
  EXPECT_EQ(left.dependency()->owner, frameOf(*wc_, "PG70.RightFinger"));
  EXPECT_EQ(left.dependency()->gain, -1.0);
  EXPECT_EQ(wc_->frames().frame(pg70.base()).type(), rw::kinematics::FrameType::kMovable);
}

// The world y extent of a jaw's collision box.
std::pair<double, double> jawSpanY(const WorkCell& wc, const rw::kinematics::State& state,
                                   const char* frame) {
  const auto* object = wc.findObject(frameOf(wc, frame));
  EXPECT_NE(object, nullptr);
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  if (object == nullptr) return {lo, hi};
  const Transform3D X_WF = worldPose(wc, state, frame);
  for (const auto& instance : object->collision) {
    for (const Vector3D& v : instance.geometry->triangles().vertices) {
      const double y = (X_WF * instance.X_frame_geometry * v).y();
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
  }
  return {lo, hi};
}

// The README's claim: the grip faces are 0.015 + 2 q apart, symmetric about the centre plane.
TEST_F(Pg70, GripFacesAreFifteenMillimetresPlusTwiceQApart) {
  for (const double q : {0.0, 0.01, 0.035}) {
    SCOPED_TRACE("q = " + std::to_string(q));
    const auto state = stateAt(q);
    const auto right = jawSpanY(*wc_, state, "PG70.RightFinger");
    const auto left = jawSpanY(*wc_, state, "PG70.LeftFinger");
    EXPECT_NEAR(right.second, -(0.0075 + q), 1e-12);
    EXPECT_NEAR(left.first, 0.0075 + q, 1e-12);
    EXPECT_NEAR(right.second - right.first, 0.015, 1e-12);
    EXPECT_NEAR(left.second - left.first, 0.015, 1e-12);
  }
}

}  // namespace
