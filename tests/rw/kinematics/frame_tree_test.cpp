#include <gtest/gtest.h>

#include <cmath>

#include "rw/kinematics/frame_tree.hpp"
#include "support/test_support.hpp"

namespace {

using rw::kinematics::FKTable;
using rw::kinematics::FrameId;
using rw::kinematics::FrameSpec;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::kinematics::JointDependency;
using rw::kinematics::State;
using rw::math::Transform3D;
using rw::math::Vector3D;

Transform3D translation(double x, double y, double z) {
  return Transform3D(Eigen::Translation3d(x, y, z));
}

FrameSpec spec(std::string name, FrameId parent, FrameType type, Transform3D X) {
  FrameSpec s;
  s.name = std::move(name);
  s.parent = parent;
  s.type = type;
  s.transform = X;
  return s;
}

// A planar two-link arm in the xy plane: joint 1 at the origin, link 1 of 0.5 m along x, joint 2,
// link 2 of 0.3 m along x to the tool. Both joints turn about z.
struct TwoLinkArm {
  FrameTree tree;
  FrameId j1, j2, tool;
  TwoLinkArm() {
    j1 = tree.add(spec("j1", FrameTree::kWorld, FrameType::kRevolute, Transform3D::Identity()));
    j2 = tree.add(spec("j2", j1, FrameType::kRevolute, translation(0.5, 0, 0)));
    tool = tree.add(spec("tool", j2, FrameType::kFixed, translation(0.3, 0, 0)));
  }
};

TEST(FrameTree, WorldIsFrameZero) {
  FrameTree tree;
  EXPECT_EQ(tree.size(), 1u);
  EXPECT_EQ(tree.find("WORLD"), FrameTree::kWorld);
  EXPECT_FALSE(tree.find("nothing").valid());
}

TEST(FrameTree, TwoLinkArmMatchesPlanarKinematics) {
  TwoLinkArm arm;
  State state = arm.tree.makeState();
  ASSERT_EQ(arm.tree.stateSize(), 2);
  const double q1 = 0.7, q2 = -1.9;
  arm.tree.frame(arm.j1).setJointValue(state, q1);
  arm.tree.frame(arm.j2).setJointValue(state, q2);
  // Worked by hand: p = (l1 cos q1 + l2 cos(q1+q2), l1 sin q1 + l2 sin(q1+q2), 0).
  const Vector3D expected(0.5 * std::cos(q1) + 0.3 * std::cos(q1 + q2),
                          0.5 * std::sin(q1) + 0.3 * std::sin(q1 + q2), 0);
  const Transform3D X = rw::kinematics::worldTransform(arm.tree, state, arm.tool);
  EXPECT_NEAR((X.translation() - expected).norm(), 0.0, 1e-15);
  EXPECT_NEAR(std::atan2(X.linear()(1, 0), X.linear()(0, 0)), q1 + q2, 1e-14);
  const FKTable fk(arm.tree, state);
  EXPECT_TRANSFORM_NEAR(fk.worldTransform(arm.tool), X, 1e-15);
}

TEST(FrameTree, PrismaticJointTranslatesAlongItsZ) {
  FrameTree tree;
  // Joint placed 1 m up, turned so that its z axis points along world x.
  Transform3D placement = translation(0, 0, 1);
  placement.rotate(Eigen::AngleAxisd(M_PI / 2, Vector3D::UnitY()));
  const FrameId slider =
      tree.add(spec("slider", FrameTree::kWorld, FrameType::kPrismatic, placement));
  State state = tree.makeState();
  tree.frame(slider).setJointValue(state, 0.25);
  const Vector3D p = rw::kinematics::worldTransform(tree, state, slider).translation();
  EXPECT_NEAR((p - Vector3D(0.25, 0, 1)).norm(), 0.0, 1e-15);
}

TEST(FrameTree, DependentJointFollowsItsOwner) {
  FrameTree tree;
  const FrameId owner = tree.add(spec("owner", FrameTree::kWorld, FrameType::kRevolute, {}));
  FrameSpec dep = spec("dep", FrameTree::kWorld, FrameType::kRevolute, translation(1, 0, 0));
  dep.dependency = JointDependency{owner, -2.0, 0.1};
  const FrameId d = tree.add(dep);
  EXPECT_EQ(tree.stateSize(), 1);  // the dependent joint has no value of its own
  State state = tree.makeState();
  tree.frame(owner).setJointValue(state, 0.3);
  EXPECT_DOUBLE_EQ(tree.frame(d).jointValue(state), -2.0 * 0.3 + 0.1);
  const Transform3D X = rw::kinematics::worldTransform(tree, state, d);
  EXPECT_NEAR(std::atan2(X.linear()(1, 0), X.linear()(0, 0)), -0.5, 1e-15);
}

TEST(FrameTree, MovableFrameStoresItsTransformInTheState) {
  FrameTree tree;
  Transform3D initial = translation(0.1, 0.2, 0.3);
  initial.rotate(Eigen::AngleAxisd(0.8, Vector3D(1, 2, 3).normalized()));
  const FrameId m = tree.add(spec("m", FrameTree::kWorld, FrameType::kMovable, initial));
  State state = tree.makeState();
  EXPECT_TRANSFORM_NEAR(tree.frame(m).localTransform(state), initial, 1e-15);
  Transform3D moved = translation(-1, 0, 2);
  tree.frame(m).setMovableTransform(state, moved);
  EXPECT_TRANSFORM_NEAR(rw::kinematics::worldTransform(tree, state, m), moved, 1e-15);
}

TEST(FrameTree, DafCanBeAttachedToALaterFrame) {
  FrameTree tree;
  FrameSpec objSpec =
      spec("object", FrameTree::kWorld, FrameType::kMovable, translation(0, 0, 0.1));
  objSpec.daf = true;
  const FrameId object = tree.add(objSpec);
  const FrameId hand =
      tree.add(spec("hand", FrameTree::kWorld, FrameType::kFixed, translation(5, 0, 0)));
  State state = tree.makeState();
  state.setParent(object, hand);
  const FKTable fk(tree, state);
  EXPECT_NEAR((fk.worldTransform(object).translation() - Vector3D(5, 0, 0.1)).norm(), 0.0, 1e-15);
  EXPECT_TRANSFORM_NEAR(fk.worldTransform(object),
                        rw::kinematics::worldTransform(tree, state, object), 1e-15);
}

TEST(FrameTree, RelativeTransformIsPoseOfToInFrom) {
  TwoLinkArm arm;
  State state = arm.tree.makeState();
  arm.tree.frame(arm.j2).setJointValue(state, M_PI / 2);
  // The tool sits 0.3 m along j2's rotated x, i.e. (0, 0.3, 0) in j2's parent frame j1.
  const Transform3D X_j1_tool =
      rw::kinematics::relativeTransform(arm.tree, state, arm.j1, arm.tool);
  EXPECT_NEAR((X_j1_tool.translation() - Vector3D(0.5, 0.3, 0)).norm(), 0.0, 1e-15);
}

TEST(FrameTree, RejectsBadFrames) {
  FrameTree tree;
  const FrameId fixed = tree.add(spec("a", FrameTree::kWorld, FrameType::kFixed, {}));
  EXPECT_THROW(tree.add(spec("a", FrameTree::kWorld, FrameType::kFixed, {})),
               std::invalid_argument);
  EXPECT_THROW(tree.add(spec("", FrameTree::kWorld, FrameType::kFixed, {})), std::invalid_argument);
  EXPECT_THROW(tree.add(spec("b", FrameId{42}, FrameType::kFixed, {})), std::invalid_argument);
  FrameSpec onFixed = spec("c", FrameTree::kWorld, FrameType::kRevolute, {});
  onFixed.dependency = JointDependency{fixed, 1, 0};
  EXPECT_THROW(tree.add(onFixed), std::invalid_argument);
  const FrameId joint = tree.add(spec("j", FrameTree::kWorld, FrameType::kRevolute, {}));
  FrameSpec fixedDep = spec("d", FrameTree::kWorld, FrameType::kFixed, {});
  fixedDep.dependency = JointDependency{joint, 1, 0};
  EXPECT_THROW(tree.add(fixedDep), std::invalid_argument);
}

}  // namespace
