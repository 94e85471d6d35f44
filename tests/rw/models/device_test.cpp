#include <gtest/gtest.h>

#include <cmath>

#include "rw/models/workcell.hpp"
#include "support/test_support.hpp"

namespace {

using rw::kinematics::FrameId;
using rw::kinematics::FrameSpec;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::kinematics::JointDependency;
using rw::math::Q;
using rw::models::Device;
using rw::models::WorkCell;

FrameId add(WorkCell& wc, std::string name, FrameId parent, FrameType type, double lower = -1,
            double upper = 1, bool ee = false) {
  FrameSpec s;
  s.name = std::move(name);
  s.parent = parent;
  s.type = type;
  s.limits.lower = lower;
  s.limits.upper = upper;
  s.endEffector = ee;
  return wc.frames().add(s);
}

// A two-finger tree device "G": base, a palm joint, and two fingers of two joints each; the
// second finger's first joint depends on the first finger's first joint.
struct Gripper {
  WorkCell wc{"test"};
  FrameId base, palm, a1, a2, aEnd, b1, b2, bEnd, outside;
  Gripper() {
    base = add(wc, "G.Base", FrameTree::kWorld, FrameType::kMovable);
    palm = add(wc, "G.Palm", base, FrameType::kRevolute, -0.5, 0.5);
    a1 = add(wc, "G.a.J1", palm, FrameType::kRevolute, -1, 1);
    a2 = add(wc, "G.a.J2", a1, FrameType::kPrismatic, 0, 0.1);
    aEnd = add(wc, "G.a.TCP", a2, FrameType::kFixed, 0, 0, true);
    FrameSpec dep;
    dep.name = "G.b.J1";
    dep.parent = palm;
    dep.type = FrameType::kRevolute;
    dep.dependency = JointDependency{a1, -1, 0};
    b1 = wc.frames().add(dep);
    b2 = add(wc, "G.b.J2", b1, FrameType::kRevolute, -2, 2);
    bEnd = add(wc, "G.b.TCP", b2, FrameType::kFixed, 0, 0, true);
    outside = add(wc, "Cup", aEnd, FrameType::kFixed);
    wc.addDevice(Device::Spec{"G", Device::Kind::kTree, base, {aEnd, bEnd}, {}, {}});
  }
};

TEST(Device, TreeJointOrderFollowsTheEndsInOrder) {
  Gripper g;
  const Device& d = *g.wc.findDevice("G");
  // RobWork: for each end, the joints on the path base -> end not yet listed.
  EXPECT_EQ(d.joints(), (std::vector<FrameId>{g.palm, g.a1, g.a2, g.b1, g.b2}));
  EXPECT_EQ(d.activeJoints(), (std::vector<FrameId>{g.palm, g.a1, g.a2, g.b2}));
  EXPECT_EQ(d.dof(), 4);
}

TEST(Device, SetQThenGetQRoundTripsAndDrivesTheDependentJoint) {
  Gripper g;
  const Device& d = *g.wc.findDevice("G");
  auto state = g.wc.defaultState();
  const Q q = (Q(4) << 0.1, 0.4, 0.05, -1.5).finished();
  d.setQ(q, state);
  EXPECT_VECTOR_NEAR(d.getQ(state), q, 0.0);
  EXPECT_DOUBLE_EQ(g.wc.frames().frame(g.b1).jointValue(state), -0.4);
  EXPECT_THROW(d.setQ(Q::Zero(3), state), std::invalid_argument);
}

TEST(Device, LimitsComeFromTheActiveJoints) {
  Gripper g;
  const Device& d = *g.wc.findDevice("G");
  EXPECT_VECTOR_NEAR(d.lowerLimits(), (Q(4) << -0.5, -1, 0, -2).finished(), 0.0);
  EXPECT_VECTOR_NEAR(d.upperLimits(), (Q(4) << 0.5, 1, 0.1, 2).finished(), 0.0);
  EXPECT_TRUE(std::isinf(d.velocityLimits()[0]));
}

TEST(Device, ContainsItsScopedFramesOnly) {
  Gripper g;
  const Device& d = *g.wc.findDevice("G");
  EXPECT_TRUE(d.contains(g.base));
  EXPECT_TRUE(d.contains(g.bEnd));
  EXPECT_FALSE(d.contains(g.outside));
  EXPECT_FALSE(d.contains(FrameTree::kWorld));
  EXPECT_EQ(d.frames().size(), 8u);
}

TEST(Device, RejectsAnEndNotBelowTheBaseAndDuplicateNames) {
  Gripper g;
  EXPECT_THROW(g.wc.addDevice(Device::Spec{"H", Device::Kind::kSerial, g.a1, {g.bEnd}, {}, {}}),
               std::invalid_argument);
  EXPECT_THROW(g.wc.addDevice(Device::Spec{"G", Device::Kind::kSerial, g.a1, {g.aEnd}, {}, {}}),
               std::invalid_argument);
}

TEST(WorkCell, ObjectsAreCreatedOncePerFrame) {
  Gripper g;
  g.wc.objectOf(g.a2).collision.push_back({"box", {}, rw::geometry::Geometry::box(1, 1, 1), {}});
  g.wc.objectOf(g.a2).visual.push_back({"box", {}, rw::geometry::Geometry::box(1, 1, 1), {}});
  EXPECT_EQ(g.wc.objects().size(), 1u);
  ASSERT_NE(g.wc.findObject(g.a2), nullptr);
  EXPECT_EQ(g.wc.findObject(g.a2)->collision.size(), 1u);
  EXPECT_EQ(g.wc.findObject(g.a1), nullptr);
}

TEST(WorkCell, DefaultStateFitsFramesAddedLater) {
  WorkCell wc("w");
  add(wc, "j", FrameTree::kWorld, FrameType::kRevolute);
  EXPECT_EQ(wc.defaultState().values().size(), 1u);
  EXPECT_THROW(wc.setDefaultState(rw::kinematics::State{}), std::invalid_argument);
}

}  // namespace
