// The project's SDH (scenes/hands/sdh/sdh.wc.xml) against RobWork's SDH2 model: same device
// interface, same fingertip kinematics, collision geometry of the real hand's size.

#include <gtest/gtest.h>

#include <array>
#include <numbers>
#include <string>
#include <vector>

#include "rw/math/rpy.hpp"
#include "scene_test_helpers.hpp"

namespace {

using rw::kinematics::FrameId;
using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rw::models::Device;
using rw::models::WorkCell;
using visgrab::test::scenes::deviceOf;
using visgrab::test::scenes::frameOf;
using visgrab::test::scenes::load;
using visgrab::test::scenes::projectSdhFile;
using visgrab::test::scenes::worldPose;

// Five configurations: zero, VisGraB's cylinder, ball and parallel close pre-shapes (reference
// §7.1), and a mixed one with negative angles.
std::vector<Q> configurations() {
  std::vector<Q> qs(5, Q::Zero(7));
  qs[1] << 0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349;
  qs[2] << 0.0, 0.349, 1.047, 0.0, 0.349, 0.0, 0.349;
  qs[3] << -1.571, -1.571, 1.571, 0.0, 0.419, 0.0, 0.419;
  qs[4] << 0.3, -0.4, 0.7, 0.9, -1.2, -0.5, 1.1;
  return qs;
}

// A base pose away from the identity, so that rotations of the base matter too.
Transform3D basePose() {
  return rw::math::rpyTransform(Vector3D(0.4, -0.3, 0.2), Vector3D(0.1, -0.2, 0.7));
}

// The device's state with its Movable base at basePose() (relative to WORLD) and q set.
rw::kinematics::State stateAt(const WorkCell& wc, const Q& q) {
  const Device& hand = deviceOf(wc, "SchunkHand");
  rw::kinematics::State state = wc.defaultState();
  const auto& base = wc.frames().frame(hand.base());
  EXPECT_EQ(base.parent(), rw::kinematics::FrameTree::kWorld);
  base.setMovableTransform(state, basePose());
  hand.setQ(q, state);
  return state;
}

std::vector<std::string> jointNames(const WorkCell& wc, const std::vector<FrameId>& joints) {
  std::vector<std::string> names;
  for (const FrameId id : joints) names.push_back(wc.frames().frame(id).name());
  return names;
}

class SdhAgreement : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto data = visgrab::test::compatDataDir();
    if (!data) GTEST_SKIP() << "RW_COMPAT_DATA is not set: RobWork's SDH2 model is needed";
    robwork_ = load(*data / "devices" / "SDH2" / "SchunkHand.wc.xml");
    project_ = load(projectSdhFile());
  }

  std::unique_ptr<WorkCell> robwork_;
  std::unique_ptr<WorkCell> project_;
};

TEST_F(SdhAgreement, FingertipsAgreeWithinOneMillimetre) {
  for (const Q& q : configurations()) {
    const auto stateR = stateAt(*robwork_, q);
    const auto stateP = stateAt(*project_, q);
    for (const char* tcp :
         {"SchunkHand.f1.TCP", "SchunkHand.f2.TCP", "SchunkHand.f3.TCP", "SchunkHand.TCP"}) {
      SCOPED_TRACE(std::string(tcp) + " at q = [" + std::to_string(q[0]) + " " +
                   std::to_string(q[1]) + " " + std::to_string(q[2]) + " ...]");
      EXPECT_VECTOR_NEAR(worldPose(*project_, stateP, tcp).translation(),
                         worldPose(*robwork_, stateR, tcp).translation(), 1e-3);
    }
  }
}

TEST_F(SdhAgreement, SameJointOrderAndLimits) {
  const Device& r = deviceOf(*robwork_, "SchunkHand");
  const Device& p = deviceOf(*project_, "SchunkHand");
  EXPECT_EQ(jointNames(*project_, p.activeJoints()), jointNames(*robwork_, r.activeJoints()));
  EXPECT_EQ(jointNames(*project_, p.joints()), jointNames(*robwork_, r.joints()));
  EXPECT_VECTOR_NEAR(p.lowerLimits(), r.lowerLimits(), 1e-12);
  EXPECT_VECTOR_NEAR(p.upperLimits(), r.upperLimits(), 1e-12);
  EXPECT_VECTOR_NEAR(p.velocityLimits(), r.velocityLimits(), 1e-12);
  EXPECT_VECTOR_NEAR(p.accelerationLimits(), r.accelerationLimits(), 1e-12);
}

// The project's model on its own (no RobWork files needed).
class SdhModel : public ::testing::Test {
 protected:
  void SetUp() override { wc_ = rw::loaders::loadWorkCell(projectSdhFile(), &warnings_); }
  std::unique_ptr<WorkCell> wc_;
  std::vector<rw::common::Diagnostic> warnings_;
};

TEST_F(SdhModel, LoadsWithoutWarnings) {
  for (const auto& w : warnings_) ADD_FAILURE() << w.format();
}

TEST_F(SdhModel, HasSevenDofInVisGraBsOrderWithTheSdhLimits) {
  const Device& p = deviceOf(*wc_, "SchunkHand");
  EXPECT_EQ(p.kind(), Device::Kind::kTree);
  EXPECT_EQ(p.dof(), 7);
  EXPECT_EQ(jointNames(*wc_, p.activeJoints()),
            (std::vector<std::string>{"SchunkHand.f1.Joint2", "SchunkHand.f1.Joint3",
                                      "SchunkHand.F2Joint1", "SchunkHand.f2.Joint2",
                                      "SchunkHand.f2.Joint3", "SchunkHand.f3.Joint2",
                                      "SchunkHand.f3.Joint3"}));
  // Reference §6.1: Joint2/Joint3 -90..90 deg, 100 deg/s, 1000 deg/s^2; spread 0..90 deg,
  // 28 deg/s, 100 deg/s^2; in radians.
  const double d = std::numbers::pi / 180;
  Q lower(7), upper(7), velocity(7), acceleration(7);
  lower << -90 * d, -90 * d, 0, -90 * d, -90 * d, -90 * d, -90 * d;
  upper << 90 * d, 90 * d, 90 * d, 90 * d, 90 * d, 90 * d, 90 * d;
  velocity << 100 * d, 100 * d, 28 * d, 100 * d, 100 * d, 100 * d, 100 * d;
  acceleration << 1000 * d, 1000 * d, 100 * d, 1000 * d, 1000 * d, 1000 * d, 1000 * d;
  EXPECT_VECTOR_NEAR(p.lowerLimits(), lower, 1e-12);
  EXPECT_VECTOR_NEAR(p.upperLimits(), upper, 1e-12);
  EXPECT_VECTOR_NEAR(p.velocityLimits(), velocity, 1e-12);
  EXPECT_VECTOR_NEAR(p.accelerationLimits(), acceleration, 1e-12);
  ASSERT_TRUE(p.configurations().contains("Home"));
  EXPECT_VECTOR_NEAR(p.configurations().at("Home"), Q::Zero(7), 0.0);
}

TEST_F(SdhModel, SpreadIsCoupledThroughDependentF3Joint1) {
  const auto& f3 = wc_->frames().frame(frameOf(*wc_, "SchunkHand.F3Joint1"));
  ASSERT_TRUE(f3.isDependent());
  EXPECT_EQ(f3.dependency()->owner, frameOf(*wc_, "SchunkHand.F2Joint1"));
  EXPECT_EQ(f3.dependency()->gain, -1.0);
  EXPECT_EQ(f3.dependency()->offset, 0.0);
  // Listed among the joints, between f2.Joint3 and f3.Joint2 (RobWork's order), not in q.
  const Device& p = deviceOf(*wc_, "SchunkHand");
  const auto joints = jointNames(*wc_, p.joints());
  ASSERT_EQ(joints.size(), 8u);
  EXPECT_EQ(joints[5], "SchunkHand.F3Joint1");
  // Turning the spread turns finger 3's base the other way round.
  auto state = wc_->defaultState();
  Q q = Q::Zero(7);
  q[2] = 0.5;
  p.setQ(q, state);
  EXPECT_DOUBLE_EQ(f3.jointValue(state), -0.5);
}

TEST_F(SdhModel, BaseIsMovableAndTheHandTcpsSit15CentimetresAboveIt) {
  const auto& tree = wc_->frames();
  const Device& p = deviceOf(*wc_, "SchunkHand");
  EXPECT_EQ(tree.frame(p.base()).type(), rw::kinematics::FrameType::kMovable);
  const auto state = wc_->defaultState();
  for (const char* name : {"SchunkHand.TCP", "SchunkHand.SDHTCP"}) {
    SCOPED_TRACE(name);
    const Transform3D X_BT =
        rw::kinematics::relativeTransform(tree, state, p.base(), frameOf(*wc_, name));
    EXPECT_TRANSFORM_NEAR(X_BT, rw::math::makeTranslation(Vector3D(0, 0, 0.15)), 1e-12);
  }
}

// Fingertip links are bodies of their own: the distal joints carry geometry, separate from the
// proximal links.
TEST_F(SdhModel, EveryLinkCarriesCollisionGeometry) {
  for (const char* name :
       {"SchunkHand.Base", "SchunkHand.F2Joint1", "SchunkHand.F3Joint1", "SchunkHand.f1.Joint2",
        "SchunkHand.f1.Joint3", "SchunkHand.f2.Joint2", "SchunkHand.f2.Joint3",
        "SchunkHand.f3.Joint2", "SchunkHand.f3.Joint3"}) {
    const auto* object = wc_->findObject(frameOf(*wc_, name));
    ASSERT_NE(object, nullptr) << name;
    EXPECT_FALSE(object->collision.empty()) << name;
    for (const auto& instance : object->collision) {
      EXPECT_TRUE(instance.geometry->isConvex()) << name << " " << instance.name;
    }
  }
}

// The bounds of a frame's collision geometry in its own coordinates.
rw::geometry::Aabb collisionBounds(const WorkCell& wc, FrameId frame) {
  rw::geometry::Aabb box;
  const auto* object = wc.findObject(frame);
  if (object == nullptr) return box;
  for (const auto& instance : object->collision) {
    for (const Vector3D& v : instance.geometry->triangles().vertices) {
      box.extend(instance.X_frame_geometry * v);
    }
  }
  return box;
}

// The primitives are sized to the real hand: each finger link's collision bounds agree with
// those of RobWork's convex-hull meshes of the same link within 4 mm (the hulls' interleaved
// knuckles reach 3.7 mm further sideways than the primitives on the distal links).
TEST_F(SdhAgreement, FingerLinksHaveTheRealHandsSize) {
  for (const char* finger : {"f1", "f2", "f3"}) {
    for (const char* link : {"Joint2", "Joint3"}) {
      const std::string name = std::string("SchunkHand.") + finger + "." + link;
      SCOPED_TRACE(name);
      const auto real = collisionBounds(*robwork_, frameOf(*robwork_, name));
      const auto ours = collisionBounds(*project_, frameOf(*project_, name));
      ASSERT_FALSE(real.empty());
      ASSERT_FALSE(ours.empty());
      EXPECT_VECTOR_NEAR(ours.min, real.min, 4e-3);
      EXPECT_VECTOR_NEAR(ours.max, real.max, 4e-3);
    }
  }
}

}  // namespace
