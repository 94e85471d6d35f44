// ContactDetector on a dynamic workcell built in code: which body pairs it checks, and the
// merged, reduced contacts it reports.
#include "rwsim/contacts/contact_detector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <random>
#include <stdexcept>
#include <thread>

#include "contact_test_util.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/proximity/proximity_filter.hpp"
#include "rwsim/contacts/manifold.hpp"
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

/// Adds frames and their collision geometry to a workcell being built.
struct FrameAdder {
  rw::models::WorkCell& wc;

  FrameId add(const std::string& name, FrameId parent, FrameType type, const Transform3D& X) const {
    FrameSpec spec;
    spec.name = name;
    spec.parent = parent;
    spec.type = type;
    spec.transform = X;
    return wc.frames().add(spec);
  }

  void geometry(FrameId frame, std::shared_ptr<const Geometry> g,
                const Transform3D& X = Transform3D::Identity()) const {
    rw::models::GeometryInstance instance;
    instance.name = "g";
    instance.geometry = std::move(g);
    instance.X_frame_geometry = X;
    wc.objectOf(frame).collision.push_back(instance);
  }
};

/// A floor (fixed, a Plane), a box resting on it (rigid), a kinematic sphere pusher touching
/// the box's +x face, a fixed wall, and a rigid "dumbbell" of two boxes on two frames resting
/// on the floor. The rule excludes the box against the wall.
std::unique_ptr<DynamicWorkCell> scene() {
  auto wc = std::make_unique<rw::models::WorkCell>("contacts");
  const auto world = rw::kinematics::FrameTree::kWorld;
  const FrameAdder adder{*wc};
  const FrameId floor = adder.add("Floor", world, FrameType::kFixed, pose({0, 0, 0}));
  adder.geometry(floor, Geometry::plane());
  const FrameId box = adder.add("Box", world, FrameType::kMovable, pose({0, 0, 0.05 - kPen}, 0.3));
  adder.geometry(box, Geometry::box(0.1, 0.1, 0.1));
  const FrameId pusher = adder.add("Pusher", world, FrameType::kMovable, pose({0, 0, 0}));
  adder.geometry(pusher, Geometry::sphere(0.02), pose({0, 0, 0.05}));
  const FrameId wall = adder.add("Wall", world, FrameType::kFixed, pose({1, 0, 0.5}));
  adder.geometry(wall, Geometry::box(0.1, 2, 1));
  const FrameId bell =
      adder.add("Dumbbell", world, FrameType::kMovable, pose({0, 0.5, 0.02 - kPen}));
  adder.geometry(bell, Geometry::box(0.04, 0.04, 0.04), pose({-0.1, 0, 0}));
  const FrameId end = adder.add("Dumbbell.end", bell, FrameType::kFixed, pose({0.1, 0, 0}));
  adder.geometry(end, Geometry::box(0.04, 0.04, 0.04));
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

TEST(ContactDetector, AFixedBodyMovedFromItsConstructionPoseIsPlacedThere) {
  // The wall's shapes are placed once at construction; a different pose must still count.
  const auto dwc = scene();
  const ContactDetector detector(*dwc);
  std::vector<Transform3D> poses = defaultPoses(*dwc);
  std::vector<BodyContact> out;
  detector.detect(poses, out);
  EXPECT_EQ(find(out, kWall, kDumbbell), nullptr);
  // The wall (0.1 thick, 2 wide, 1 high about its frame) moved so that its -x face presses
  // the dumbbell's +x end (x = 0.12) by kPen.
  poses[kWall].translation() = Vector3D(0.12 + 0.05 - kPen, 0.5, 0.5);
  detector.detect(poses, out);
  const BodyContact* wall = find(out, kWall, kDumbbell);
  ASSERT_NE(wall, nullptr);
  ASSERT_FALSE(wall->points.empty());
  for (const ContactPoint& p : wall->points) {
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    EXPECT_VECTOR_NEAR(p.normal, -Vector3D::UnitX(), 1e-9);
  }
  detector.detect(defaultPoses(*dwc), out);
  EXPECT_EQ(find(out, kWall, kDumbbell), nullptr);
}

TEST(ContactDetector, BodiesWithinTheMarginStillTouchAndBeyondItDoNot) {
  // The body-level broad phase must not cut a pair whose shapes are within the margin.
  const auto dwc = scene();
  const double margin = ContactOptions{}.margin;
  const ContactDetector detector(*dwc);
  for (const double gap : {0.9 * margin, 1.1 * margin}) {
    std::vector<Transform3D> poses = defaultPoses(*dwc);
    poses[kBox] = pose({0, 0, 0.05 - kPen});
    // The dumbbell's first box (x in [-0.02, 0.02] once moved) faces the box's +y face.
    poses[kDumbbell] = pose({0.1, 0.05 + gap + 0.02, 0.02 - kPen});
    std::vector<BodyContact> out;
    detector.detect(poses, out);
    const BodyContact* side = find(out, kBox, kDumbbell);
    if (gap > margin) {
      EXPECT_EQ(side, nullptr) << "gap " << gap;
      continue;
    }
    ASSERT_NE(side, nullptr) << "gap " << gap;
    ASSERT_FALSE(side->points.empty());
    for (const ContactPoint& p : side->points) {
      EXPECT_NEAR(p.depth, -gap, 1e-12);
      EXPECT_VECTOR_NEAR(p.normal, Vector3D::UnitY(), 1e-9);
    }
  }
}

/// A cluttered scene: a fixed table top (a box), five rigid objects of one to three shapes on
/// one or two frames (boxes, cylinders, spheres, cones, frusta, a convex and a non-convex mesh)
/// and a kinematic finger (a box and a cylinder), all allowed to touch.
std::unique_ptr<DynamicWorkCell> clutter() {
  auto wc = std::make_unique<rw::models::WorkCell>("clutter");
  auto& frames = wc->frames();
  const auto world = rw::kinematics::FrameTree::kWorld;
  const FrameAdder adder{*wc};
  const FrameId table = adder.add("Table", world, FrameType::kFixed, pose({0, 0, 0}));
  adder.geometry(table, Geometry::box(0.4, 0.4, 0.04), pose({0, 0, -0.02}));
  const FrameId can = adder.add("Can", world, FrameType::kMovable, pose({0, 0, 0}));
  adder.geometry(can, Geometry::cylinder(0.03, 0.08), pose({0, 0, 0.04}));
  adder.geometry(can, Geometry::frustum(0.03, 0.02, 0.02), pose({0, 0, 0.09}));
  const FrameId brick = adder.add("Brick", world, FrameType::kMovable, pose({0, 0, 0}));
  adder.geometry(brick, Geometry::box(0.08, 0.04, 0.03), pose({0, 0, 0.015}, 0.4));
  adder.geometry(brick, Geometry::sphere(0.015), pose({0.04, 0, 0.03}));
  const FrameId cone = adder.add("Cone", world, FrameType::kMovable, pose({0, 0, 0}));
  adder.geometry(cone, Geometry::cone(0.03, 0.05), pose({0, 0, 0.025}, 0.3, Vector3D::UnitX()));
  const FrameId lshape = adder.add("LShape", world, FrameType::kMovable, pose({0, 0, 0}));
  const std::vector<Eigen::Vector2d> l = {{0, 0},       {0.06, 0},    {0.06, 0.03},
                                          {0.03, 0.03}, {0.03, 0.06}, {0, 0.06}};
  adder.geometry(lshape, test::meshGeometry(test::prism(l, 0, 0.03)));
  const FrameId ball = adder.add("Ball", world, FrameType::kMovable, pose({0, 0, 0}));
  adder.geometry(ball, test::meshGeometry(test::uvSphere(0.025, 16, 10)), pose({0, 0, 0.025}));
  const FrameId ballTop = adder.add("Ball.top", ball, FrameType::kFixed, pose({0, 0, 0.05}));
  adder.geometry(ballTop, Geometry::box(0.02, 0.02, 0.02));
  const FrameId finger = adder.add("Finger", world, FrameType::kMovable, pose({0, 0, 0}));
  adder.geometry(finger, Geometry::box(0.02, 0.02, 0.06), pose({0, 0, 0.03}));
  adder.geometry(finger, Geometry::cylinder(0.01, 0.02),
                 pose({0, 0, -0.01}, 0.5 * test::kPi, Vector3D::UnitX()));

  auto dwc = std::make_unique<DynamicWorkCell>(std::move(wc));
  dwc->materials().addMaterial("Plastic");
  const auto addBody = [&](const std::string& name, FrameId frame, BodyKind kind) {
    Body b;
    b.name = name;
    b.frame = frame;
    b.kind = kind;
    b.material = "Plastic";
    if (kind == BodyKind::kRigid) {
      b.mass.mass = 0.2;
      b.mass.inertia = Eigen::Matrix3d::Identity() * 1e-4;
    }
    dwc->addBody(std::move(b));
  };
  addBody("Table", table, BodyKind::kFixed);
  for (const char* name : {"Can", "Brick", "Cone", "LShape", "Ball"}) {
    addBody(name, frames.find(name), BodyKind::kRigid);
  }
  addBody("Finger", finger, BodyKind::kKinematic);
  return dwc;
}

/// The contacts of the plain algorithm detect() must reproduce bit for bit: every allowed
/// geometry pair of every candidate body pair placed from scratch (X_W_body times the
/// geometry's pose in the body frame), kept when their world boxes are within the margin,
/// collide()d, and merged per body pair (reduced when the pair has several geometry pairs).
std::vector<BodyContact> plainContacts(const DynamicWorkCell& dwc,
                                       const std::vector<Transform3D>& X_W_body,
                                       const ContactDetector& detector) {
  const auto& wc = dwc.workcell();
  const rw::kinematics::FKTable fk(wc.frames(), wc.defaultState());
  const rw::proximity::ProximityFilter filter(wc);
  struct Placed {
    std::shared_ptr<const ContactShape> shape;
    Transform3D X_body_shape;
    FrameId frame;
  };
  std::map<const Geometry*, std::shared_ptr<const ContactShape>> built;
  std::vector<std::vector<Placed>> shapes;
  for (const Body& body : dwc.bodies()) {
    const Transform3D X_body_W = fk.worldTransform(body.frame).inverse(Eigen::Isometry);
    auto& list = shapes.emplace_back();
    for (const FrameId frame : body.geometryFrames) {
      const rw::models::Object* object = wc.findObject(frame);
      if (object == nullptr) continue;
      for (const auto& g : object->collision) {
        auto& shape = built[g.geometry.get()];
        if (!shape) shape = ContactShape::build(*g.geometry);
        list.push_back({shape, X_body_W * fk.worldTransform(frame) * g.X_frame_geometry, frame});
      }
    }
  }
  const auto withinMargin = [&](const ContactShape& s, const Transform3D& X) {
    const rw::geometry::Aabb box = s.localBounds();
    struct {
      Vector3D center;
      Vector3D half;
      bool unbounded;
    } w{X * Vector3D(0.5 * (box.min + box.max)),
        X.linear().cwiseAbs() * Vector3D(0.5 * (box.max - box.min)),
        !(box.min.allFinite() && box.max.allFinite())};
    return w;
  };
  const double margin = detector.options().margin;
  std::vector<BodyContact> out;
  std::vector<ContactPoint> gathered;
  detail::ReduceScratch scratch;
  for (const auto& [a, b] : detector.candidatePairs()) {
    gathered.clear();
    std::size_t shapePairs = 0;
    for (const Placed& sa : shapes[a.index()]) {
      for (const Placed& sb : shapes[b.index()]) {
        if (sa.frame == sb.frame || !filter.contains(sa.frame, sb.frame)) continue;
        ++shapePairs;
        const Transform3D X_W_sa = X_W_body[a.index()] * sa.X_body_shape;
        const Transform3D X_W_sb = X_W_body[b.index()] * sb.X_body_shape;
        const auto ba = withinMargin(*sa.shape, X_W_sa);
        const auto bb = withinMargin(*sb.shape, X_W_sb);
        if (!ba.unbounded && !bb.unbounded &&
            ((ba.center - bb.center).cwiseAbs() - ba.half - bb.half).maxCoeff() > margin) {
          continue;
        }
        collide(*sa.shape, X_W_sa, *sb.shape, X_W_sb, detector.options(), gathered);
      }
    }
    if (gathered.empty()) continue;
    BodyContact& contact = out.emplace_back();
    contact.bodyA = a;
    contact.bodyB = b;
    if (shapePairs == 1) {
      contact.points = gathered;
    } else {
      detail::clusterAndReduce(gathered, detector.options().maxPointsPerManifold, contact.points,
                               scratch);
    }
  }
  return out;
}

TEST(ContactDetector, ClutteredScenesGiveThePlainAlgorithmsBits) {
  const auto dwc = clutter();
  const ContactDetector detector(*dwc);
  const std::size_t bodies = dwc->bodies().size();
  // Every pair has a rigid body except the table and the finger.
  EXPECT_EQ(detector.candidatePairs().size(), bodies * (bodies - 1) / 2 - 1);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<BodyContact> out;
  std::size_t touching = 0;
  std::size_t points = 0;
  std::size_t multiShapeTouching = 0;
  constexpr int kRounds = 200;
  for (int round = 0; round < kRounds; ++round) {
    std::vector<Transform3D> poses = defaultPoses(*dwc);
    for (std::size_t b = 1; b < bodies; ++b) {
      const Vector3D axis(unit(random), unit(random), unit(random));
      poses[b] = pose({0.07 * unit(random), 0.07 * unit(random), 0.03 + 0.03 * unit(random)},
                      3.0 * unit(random), axis.norm() > 1e-3 ? axis : Vector3D::UnitZ());
    }
    // Every third round the fixed table is moved away from its construction pose.
    if (round % 3 == 2) poses[0] = pose({0.01 * unit(random), 0, 0.01 * unit(random)}, 0.1);
    const std::vector<BodyContact> expected = plainContacts(*dwc, poses, detector);
    detector.detect(poses, out);
    ASSERT_EQ(out.size(), expected.size()) << "round " << round;
    for (std::size_t i = 0; i < out.size(); ++i) {
      EXPECT_EQ(out[i].bodyA, expected[i].bodyA) << "round " << round;
      EXPECT_EQ(out[i].bodyB, expected[i].bodyB) << "round " << round;
      ASSERT_EQ(out[i].points.size(), expected[i].points.size()) << "round " << round;
      EXPECT_EQ(std::memcmp(out[i].points.data(), expected[i].points.data(),
                            out[i].points.size() * sizeof(ContactPoint)),
                0)
          << "round " << round << ", pair " << i;
      points += out[i].points.size();
      const std::size_t a = out[i].bodyA.index();
      const std::size_t b = out[i].bodyB.index();
      if (a != 0 && (a == 1 || a == 2 || a == 5 || b == 1 || b == 2 || b == 5 || b == 6)) {
        ++multiShapeTouching;
      }
    }
    touching += out.size();
  }
  // The scenes are cluttered enough to test something: many touching pairs, also of bodies
  // with several shapes, and many pairs apart.
  EXPECT_GT(touching, 600u);
  EXPECT_GT(multiShapeTouching, 300u);
  EXPECT_GT(points, 2000u);
  EXPECT_LT(touching, kRounds * detector.candidatePairs().size() / 2);
}

}  // namespace
}  // namespace rwsim::contacts
