// ContactDetector on a dynamic workcell built in code: which body pairs it checks, and the
// merged, reduced contacts it reports.
#include "rwsim/contacts/contact_detector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "contact_test_util.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "support/test_support.hpp"

namespace rwsim::contacts {
namespace {

using rw::kinematics::FrameId;
using rw::kinematics::FrameSpec;
using rw::kinematics::FrameType;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::Body;
using rwsim::dynamics::BodyId;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DynamicWorkCell;
using test::Geometry;
using test::kPen;
using test::pose;

/// Body indices of the scene below.
enum : std::size_t { kFloor, kBox, kPusher, kWall, kDumbbell };

/// The id of body `k` of the scene below.
BodyId idOf(std::size_t k) { return BodyId(k); }

/// Pairs of body ids.
using IdPairs = std::vector<std::pair<BodyId, BodyId>>;

/// A floor (fixed, a Plane), a box resting on it (rigid), a kinematic sphere pusher touching
/// the box's +x face, a fixed wall, and a rigid "dumbbell" of two boxes on two frames resting
/// on the floor. The rule excludes the box against the wall.
std::unique_ptr<DynamicWorkCell> scene() {
  auto wc = std::make_unique<rw::models::WorkCell>("contacts");
  auto& frames = wc->frames();
  const auto world = rw::kinematics::FrameTree::kWorld;
  const auto add = [&](const std::string& name, FrameId parent, FrameType type,
                       const Transform3D& X) {
    FrameSpec spec;
    spec.name = name;
    spec.parent = parent;
    spec.type = type;
    spec.transform = X;
    return frames.add(spec);
  };
  const auto geometry = [&](FrameId frame, std::shared_ptr<const Geometry> g,
                            const Transform3D& X = Transform3D::Identity()) {
    rw::models::GeometryInstance instance;
    instance.name = "g";
    instance.geometry = std::move(g);
    instance.X_frame_geometry = X;
    wc->objectOf(frame).collision.push_back(instance);
  };
  const FrameId floor = add("Floor", world, FrameType::kFixed, pose({0, 0, 0}));
  geometry(floor, Geometry::plane());
  const FrameId box = add("Box", world, FrameType::kMovable, pose({0, 0, 0.05 - kPen}, 0.3));
  geometry(box, Geometry::box(0.1, 0.1, 0.1));
  const FrameId pusher = add("Pusher", world, FrameType::kMovable, pose({0, 0, 0}));
  geometry(pusher, Geometry::sphere(0.02), pose({0, 0, 0.05}));
  const FrameId wall = add("Wall", world, FrameType::kFixed, pose({1, 0, 0.5}));
  geometry(wall, Geometry::box(0.1, 2, 1));
  const FrameId bell = add("Dumbbell", world, FrameType::kMovable, pose({0, 0.5, 0.02 - kPen}));
  geometry(bell, Geometry::box(0.04, 0.04, 0.04), pose({-0.1, 0, 0}));
  const FrameId end = add("Dumbbell.end", bell, FrameType::kFixed, pose({0.1, 0, 0}));
  geometry(end, Geometry::box(0.04, 0.04, 0.04));
  wc->proximitySetup().rules.push_back({"Box", "Wall", false});

  auto dwc = std::make_unique<DynamicWorkCell>(std::move(wc));
  dwc->materials().addMaterial("Plastic");
  const auto addBody = [&](const std::string& name, FrameId frame, BodyKind kind) {
    Body b;
    b.name = name;
    b.frame = frame;
    b.kind = kind;
    b.material = "Plastic";
    if (kind == BodyKind::kRigid) {
      b.mass.mass = 1.0;
      b.mass.inertia = Eigen::Matrix3d::Identity() * 1e-3;
    }
    return dwc->addBody(std::move(b));
  };
  EXPECT_EQ(addBody("Floor", floor, BodyKind::kFixed), idOf(kFloor));
  EXPECT_EQ(addBody("Box", box, BodyKind::kRigid), idOf(kBox));
  EXPECT_EQ(addBody("Pusher", pusher, BodyKind::kKinematic), idOf(kPusher));
  EXPECT_EQ(addBody("Wall", wall, BodyKind::kFixed), idOf(kWall));
  EXPECT_EQ(addBody("Dumbbell", bell, BodyKind::kRigid), idOf(kDumbbell));
  return dwc;
}

/// Body poses: the workcell's default ones, the pusher moved against the box's face.
std::vector<Transform3D> defaultPoses(const DynamicWorkCell& dwc) {
  const auto& wc = dwc.workcell();
  const rw::kinematics::FKTable fk(wc.frames(), wc.defaultState());
  std::vector<Transform3D> poses;
  for (const Body& b : dwc.bodies()) poses.push_back(fk.worldTransform(b.frame));
  return poses;
}

const BodyContact* find(const std::vector<BodyContact>& contacts, std::size_t a, std::size_t b) {
  for (const BodyContact& c : contacts) {
    if (c.bodyA == idOf(a) && c.bodyB == idOf(b)) return &c;
  }
  return nullptr;
}

TEST(ContactDetector, ChecksPairsWithARigidBodyThatTheSetupAllows) {
  const auto dwc = scene();
  const ContactDetector detector(*dwc);
  const IdPairs expected = {{idOf(kFloor), idOf(kBox)},       {idOf(kFloor), idOf(kDumbbell)},
                            {idOf(kBox), idOf(kPusher)},      {idOf(kBox), idOf(kDumbbell)},
                            {idOf(kPusher), idOf(kDumbbell)}, {idOf(kWall), idOf(kDumbbell)}};
  EXPECT_EQ(detector.candidatePairs(), expected);
}

TEST(ContactDetector, SkipsExcludedPairsInEitherOrder) {
  const auto dwc = scene();
  const ContactDetector detector(
      *dwc, ContactOptions{}, IdPairs{{idOf(kDumbbell), idOf(kBox)}, {idOf(kFloor), idOf(kBox)}});
  const IdPairs expected = {{idOf(kFloor), idOf(kDumbbell)},
                            {idOf(kBox), idOf(kPusher)},
                            {idOf(kPusher), idOf(kDumbbell)},
                            {idOf(kWall), idOf(kDumbbell)}};
  EXPECT_EQ(detector.candidatePairs(), expected);
  std::vector<BodyContact> out;
  detector.detect(defaultPoses(*dwc), out);
  EXPECT_EQ(find(out, kFloor, kBox), nullptr);
}

TEST(ContactDetector, ReportsRestingContactsSortedByPair) {
  const auto dwc = scene();
  const ContactDetector detector(*dwc);
  std::vector<Transform3D> poses = defaultPoses(*dwc);
  // Put the pusher's sphere (0.05 above its frame) against the box's face, 0.1 mm deep.
  const Vector3D face = poses[kBox] * Vector3D(0.05, 0, 0);
  const Vector3D outward = poses[kBox].linear() * Vector3D::UnitX();
  poses[kPusher].translation() = face + (0.02 - kPen) * outward - Vector3D(0, 0, 0.05);
  std::vector<BodyContact> out(3);  // stale entries are replaced
  detector.detect(poses, out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_TRUE(std::is_sorted(out.begin(), out.end(), [](const auto& x, const auto& y) {
    return std::pair(x.bodyA, x.bodyB) < std::pair(y.bodyA, y.bodyB);
  }));
  const BodyContact* resting = find(out, kFloor, kBox);
  ASSERT_NE(resting, nullptr);
  ASSERT_EQ(resting->points.size(), 4u);
  for (const ContactPoint& p : resting->points) {
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    EXPECT_VECTOR_NEAR(p.normal, Vector3D::UnitZ(), 1e-12);
  }
  const BodyContact* pushed = find(out, kBox, kPusher);
  ASSERT_NE(pushed, nullptr);
  ASSERT_EQ(pushed->points.size(), 1u);
  EXPECT_NEAR(pushed->points[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(pushed->points[0].normal, outward, 1e-9);
  EXPECT_NE(find(out, kFloor, kDumbbell), nullptr);
}

TEST(ContactDetector, MergesAllGeometriesOfAPairIntoOneManifold) {
  // The dumbbell's two boxes give eight corners on the floor; the four outermost are kept.
  const auto dwc = scene();
  const ContactDetector detector(*dwc);
  std::vector<BodyContact> out;
  detector.detect(defaultPoses(*dwc), out);
  const BodyContact* bell = find(out, kFloor, kDumbbell);
  ASSERT_NE(bell, nullptr);
  ASSERT_EQ(bell->points.size(), 4u);
  for (const ContactPoint& p : bell->points) {
    EXPECT_NEAR(std::abs(p.position.x()), 0.12, 1e-9);
    EXPECT_NEAR(std::abs(p.position.y() - 0.5), 0.02, 1e-9);
    EXPECT_NEAR(p.depth, kPen, 1e-9);
  }
}

TEST(ContactDetector, LiftedBodiesHaveNoContacts) {
  const auto dwc = scene();
  const ContactDetector detector(*dwc);
  std::vector<Transform3D> poses = defaultPoses(*dwc);
  poses[kBox].translation().z() += 1.0;
  poses[kDumbbell].translation().z() += 2.0;
  poses[kPusher].translation().z() += 3.0;
  poses[kWall].translation().z() += 5.0;
  std::vector<BodyContact> out;
  detector.detect(poses, out);
  EXPECT_TRUE(out.empty());
}

TEST(ContactDetector, RejectsAWrongNumberOfPoses) {
  const auto dwc = scene();
  const ContactDetector detector(*dwc);
  std::vector<BodyContact> out;
  EXPECT_THROW(detector.detect(std::vector<Transform3D>(2), out), std::invalid_argument);
}

TEST(ContactDetector, ThreadsGetTheSameBitsAsOneThread) {
  const auto dwc = scene();
  const ContactDetector detector(*dwc);
  const auto poses = defaultPoses(*dwc);
  std::vector<BodyContact> reference;
  detector.detect(poses, reference);
  std::vector<std::vector<BodyContact>> results(2);
  std::vector<std::thread> threads;
  threads.reserve(results.size());
  for (auto& r : results) {
    threads.emplace_back([&detector, &poses, &r] {
      for (int i = 0; i < 50; ++i) detector.detect(poses, r);
    });
  }
  for (auto& t : threads) t.join();
  for (const auto& r : results) {
    ASSERT_EQ(r.size(), reference.size());
    for (std::size_t i = 0; i < r.size(); ++i) {
      ASSERT_EQ(r[i].points.size(), reference[i].points.size());
      EXPECT_EQ(std::memcmp(r[i].points.data(), reference[i].points.data(),
                            r[i].points.size() * sizeof(ContactPoint)),
                0);
    }
  }
}

}  // namespace
}  // namespace rwsim::contacts
