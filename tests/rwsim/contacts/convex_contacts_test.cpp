// collide() on primitives and convex shapes, against hand-worked contact geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "contact_test_util.hpp"
#include "support/test_support.hpp"

namespace rwsim::contacts {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using test::contacts;
using test::expectAllNormals;
using test::Geometry;
using test::kPen;
using test::kPi;
using test::pose;

constexpr double kTol = 1e-9;
/// True when some point of `points` is within tol of p.
bool containsPoint(const std::vector<ContactPoint>& points, const Vector3D& p, double tol) {
  for (const ContactPoint& c : points) {
    if ((c.position - p).norm() <= tol) return true;
  }
  return false;
}

TEST(BoxOnHalfSpace, FourCornersAtThePenetration) {
  const auto plane = Geometry::plane();
  const auto box = Geometry::box(0.2, 0.1, 0.05);
  const auto c = contacts(*plane, pose({0, 0, 0}), *box, pose({0.3, -0.2, 0.025 - kPen}));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) EXPECT_NEAR(p.depth, kPen, kTol);
  for (const double x : {0.2, 0.4}) {
    for (const double y : {-0.25, -0.15}) {
      EXPECT_TRUE(containsPoint(c, Vector3D(x, y, -kPen / 2), kTol)) << x << " " << y;
    }
  }
}

TEST(BoxOnHalfSpace, TiltedBoxGivesTheLowEdge) {
  // Rotated 0.01 rad about y: the +x bottom edge is lowest, the -x edge is out of the margin.
  const auto box = Geometry::box(0.2, 0.1, 0.05);
  const Transform3D X = pose({0, 0, 0.025 - kPen + 0.1 * std::sin(0.01)}, 0.01, Vector3D::UnitY());
  const auto c = contacts(*Geometry::plane(), pose({0, 0, 0}), *box, X);
  ASSERT_EQ(c.size(), 2u);
  for (const ContactPoint& p : c) {
    EXPECT_GT(p.position.x(), 0.09);
    EXPECT_GT(p.depth, 0.0);
  }
}

/// The intersection of the unit square with itself rotated 30 degrees about its centre: an
/// octagon with vertices R(90k) (0.5, 0.5 tan 15) and R(90k) (0.5, -0.5 tan 30).
std::vector<Eigen::Vector2d> octagon() {
  std::vector<Eigen::Vector2d> v;
  const double a = 0.5 * std::tan(15.0 * rw::math::kDeg2Rad);
  const double b = 0.5 * std::tan(30.0 * rw::math::kDeg2Rad);
  for (int k = 0; k < 4; ++k) {
    const Eigen::Rotation2Dd R(k * kPi / 2);
    v.push_back(R * Eigen::Vector2d(0.5, -b));
    v.push_back(R * Eigen::Vector2d(0.5, a));
  }
  return v;
}

TEST(BoxOnBox, RotatedThirtyDegreesKeepsExtremeOctagonCorners) {
  const auto box = Geometry::box(1, 1, 1);
  const auto c =
      contacts(*box, pose({0, 0, 0}), *box, pose({0, 0, 1 - kPen}, 30 * rw::math::kDeg2Rad));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  const auto corners = octagon();
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.depth, kPen, kTol);
    EXPECT_NEAR(p.position.z(), 0.5 - kPen / 2, kTol);
    bool isCorner = false;
    for (const auto& q : corners) isCorner |= (p.position.head<2>() - q).norm() < 1e-9;
    EXPECT_TRUE(isCorner) << p.position.transpose();
  }
  // The best four of the octagon's eight corners span 2/3 m^2 (of 0.845).
  EXPECT_NEAR(test::hullArea(test::xy(c)), 2.0 / 3.0, 1e-9);
}

TEST(BoxOnBox, EdgeOnFaceGivesTheEdgeEnds) {
  const auto base = Geometry::box(2, 2, 1);
  const auto box = Geometry::box(1, 1, 1);
  const double h = 0.5 + std::sqrt(0.5) - kPen;
  const auto c =
      contacts(*base, pose({0, 0, 0}), *box, pose({0, 0, h}, kPi / 4, Vector3D::UnitX()));
  ASSERT_EQ(c.size(), 2u);
  expectAllNormals(c, Vector3D::UnitZ());
  EXPECT_TRUE(containsPoint(c, Vector3D(0.5, 0, 0.5 - kPen / 2), 1e-9));
  EXPECT_TRUE(containsPoint(c, Vector3D(-0.5, 0, 0.5 - kPen / 2), 1e-9));
  for (const ContactPoint& p : c) EXPECT_NEAR(p.depth, kPen, 1e-9);
}

TEST(BoxOnBox, CrossedEdgesGiveOnePoint) {
  // Upper box rotated 45 deg about x (edge along x at the bottom), lower box rotated 45 deg about
  // y (edge along y at the top): the edges cross at the origin column.
  const auto box = Geometry::box(1, 1, 1);
  const double r = std::sqrt(0.5);
  const auto c = contacts(*box, pose({0, 0, 0}, kPi / 4, Vector3D::UnitY()), *box,
                          pose({0, 0, 2 * r - kPen}, kPi / 4, Vector3D::UnitX()));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-9);
  EXPECT_NEAR(c[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].position, Vector3D(0, 0, r - kPen / 2), 1e-9);
}

TEST(SphereContacts, OnPlaneOnePointAtDepth) {
  const double r = 0.05;
  const double h = 0.0499;
  const auto c =
      contacts(*Geometry::plane(), pose({0, 0, 0}), *Geometry::sphere(r), pose({1, 2, h}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, r - h, kTol);
  EXPECT_VECTOR_NEAR(c[0].position, Vector3D(1, 2, (h - r) / 2), kTol);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), kTol);
}

TEST(SphereContacts, OnBoxFaceEdgeAndInside) {
  const auto box = Geometry::box(1, 1, 1);
  const auto sphere = Geometry::sphere(0.1);
  // Above the top face.
  auto c = contacts(*box, pose({0, 0, 0}), *sphere, pose({0.2, 0, 0.6 - kPen}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-9);
  // Beside a vertical edge, along the diagonal.
  const double d = 0.1 - kPen;
  c = contacts(*box, pose({0, 0, 0}), *sphere,
               pose({0.5 + d / std::sqrt(2.0), 0.5 + d / std::sqrt(2.0), 0}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D(1, 1, 0).normalized(), 1e-9);
  // Centre inside, 0.05 below the top face: pushed out through the top.
  c = contacts(*box, pose({0, 0, 0}), *sphere, pose({0, 0.1, 0.45}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, 0.15, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-9);
}

TEST(SphereContacts, TwoSpheres) {
  const auto a = Geometry::sphere(0.1);
  const auto b = Geometry::sphere(0.2);
  const auto c = contacts(*a, pose({0, 0, 0}), *b, pose({0.3 - kPen, 0, 0}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-12);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitX(), 1e-12);
  EXPECT_NEAR(c[0].position.x(), 0.1 - kPen / 2, 1e-12);
}

TEST(CylinderOnPlane, StandingGivesFourRimPoints) {
  const double r = 0.04;
  const auto can = Geometry::cylinder(r, 0.12);
  const auto c = contacts(*Geometry::plane(), pose({0, 0, 0}), *can, pose({0.1, 0.1, 0.06 - kPen}));
  ASSERT_EQ(c.size(), 4u);
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(std::hypot(p.position.x() - 0.1, p.position.y() - 0.1), r, 1e-9);
    EXPECT_NEAR(p.depth, kPen, kTol);
  }
  // The best quadrilateral in a circle is the inscribed square, 2 r^2.
  EXPECT_NEAR(test::hullArea(test::xy(c)), 2 * r * r, 1e-9);
}

TEST(CylinderOnPlane, LyingGivesALineContact) {
  const double r = 0.04;
  const double h = 0.12;
  const auto can = Geometry::cylinder(r, h);
  const auto c = contacts(*Geometry::plane(), pose({0, 0, 0}), *can,
                          pose({0, 0, r - kPen}, kPi / 2, Vector3D::UnitX()));
  ASSERT_GE(c.size(), 2u);
  double ymin = 1;
  double ymax = -1;
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.position.x(), 0.0, 1e-9);
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    ymin = std::min(ymin, p.position.y());
    ymax = std::max(ymax, p.position.y());
  }
  EXPECT_NEAR(ymax - ymin, h, 1e-9);
  // The side is a true circle: rolled by any angle the can still touches along one line, at
  // the same height and depth (a polygon would have its side faces at r cos(pi / 32)).
  const auto rolled =
      contacts(*Geometry::plane(), pose({0, 0, 0}), *can,
               pose({0, 0, r - kPen}, kPi / 2, Vector3D::UnitX()) * pose({0, 0, 0}, kPi / 32));
  ASSERT_EQ(rolled.size(), 2u);
  for (const ContactPoint& p : rolled) {
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    EXPECT_NEAR(p.position.x(), 0.0, 1e-9);
  }
}

TEST(CylinderOnBox, StandingCanRestsOnFourRimPoints) {
  const auto can = Geometry::cylinder(0.03, 0.1);
  const auto table = Geometry::box(1, 1, 0.1);
  const auto c = contacts(*table, pose({0, 0, -0.05}), *can, pose({0.2, 0, 0.05 - kPen}));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(std::hypot(p.position.x() - 0.2, p.position.y()), 0.03, 1e-9);
    EXPECT_NEAR(p.depth, kPen, 1e-9);
  }
}

TEST(Margin, SeparatedBeyondMarginGivesNothing) {
  const auto box = Geometry::box(1, 1, 1);
  const auto sphere = Geometry::sphere(0.1);
  const double gap = 0.0006;
  EXPECT_TRUE(contacts(*Geometry::plane(), pose({0, 0, 0}), *box, pose({0, 0, 0.5 + gap})).empty());
  EXPECT_TRUE(contacts(*box, pose({0, 0, 0}), *box, pose({0.3, 0.2, 1 + gap}, 0.3)).empty());
  EXPECT_TRUE(contacts(*box, pose({0, 0, 0}), *sphere, pose({0, 0, 0.6 + gap})).empty());
  EXPECT_TRUE(contacts(*sphere, pose({0, 0, 0}), *sphere, pose({0.2 + gap, 0, 0})).empty());
  EXPECT_TRUE(
      contacts(*Geometry::plane(), pose({0, 0, 0}), *sphere, pose({0, 0, 0.1 + gap})).empty());
}

TEST(Margin, WithinMarginGivesNegativeDepth) {
  const auto box = Geometry::box(1, 1, 1);
  const double gap = 0.0003;
  auto c = contacts(*box, pose({0, 0, 0}), *box, pose({0.3, 0.2, 1 + gap}, 0.3));
  ASSERT_EQ(c.size(), 4u);
  for (const ContactPoint& p : c) EXPECT_NEAR(p.depth, -gap, 1e-12);
  c = contacts(*Geometry::plane(), pose({0, 0, 0}), *Geometry::sphere(0.1),
               pose({0, 0, 0.1 + gap}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, -gap, 1e-12);
  ContactOptions tight;
  tight.margin = 0.0001;
  EXPECT_TRUE(contacts(*box, pose({0, 0, 0}), *box, pose({0.3, 0.2, 1 + gap}, 0.3), tight).empty());
}

TEST(Options, MaxPointsPerManifold) {
  const auto box = Geometry::box(1, 1, 1);
  ContactOptions options;
  for (const int n : {1, 2, 3, 4, 5, 8}) {
    options.maxPointsPerManifold = n;
    const auto c = contacts(*box, pose({0, 0, 0}), *box, pose({0, 0, 1 - kPen}, 0.5), options);
    EXPECT_EQ(c.size(), static_cast<std::size_t>(n));
  }
}

/// Cases for the invariance, symmetry and determinism tests: pairs of geometries and poses.
struct Case {
  std::shared_ptr<const Geometry> a;
  Transform3D X_a;
  std::shared_ptr<const Geometry> b;
  Transform3D X_b;
};

std::vector<Case> cases() {
  const auto box = Geometry::box(1, 1, 1);
  const auto can = Geometry::cylinder(0.2, 0.5);
  return {
      {box, pose({0, 0, 0}), box, pose({0.1, 0.05, 1 - kPen}, 0.5)},
      {box, pose({0, 0, 0}), can, pose({0.2, 0.1, 0.75 - kPen})},
      {box, pose({0, 0, 0}, kPi / 4, Vector3D::UnitY()), box,
       pose({0, 0, std::sqrt(2.0) - kPen}, kPi / 4, Vector3D::UnitX())},
      {Geometry::plane(), pose({0, 0, 0}), can, pose({0, 0, 0.25 - kPen}, 0.02, Vector3D::UnitX())},
      {box, pose({0, 0, 0}), Geometry::sphere(0.1), pose({0.5, 0.5, 0.6 - kPen})},
      {can, pose({0, 0, 0}), can, pose({0.05, 0, 0.5 - kPen}, 0.3)},
  };
}

Transform3D randomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector3D axis(u(rng), u(rng), u(rng));
  return pose(Vector3D(u(rng), u(rng), u(rng)), 3 * u(rng), axis);
}

TEST(Invariance, MovingBothShapesMovesTheManifold) {
  std::mt19937 rng(7);
  for (const Case& k : cases()) {
    const auto reference = contacts(*k.a, k.X_a, *k.b, k.X_b);
    ASSERT_FALSE(reference.empty());
    for (int trial = 0; trial < 5; ++trial) {
      const Transform3D G = randomPose(rng);
      const auto moved = contacts(*k.a, G * k.X_a, *k.b, G * k.X_b);
      ASSERT_EQ(moved.size(), reference.size());
      for (std::size_t i = 0; i < moved.size(); ++i) {
        EXPECT_VECTOR_NEAR(moved[i].position, G * reference[i].position, 1e-9);
        EXPECT_VECTOR_NEAR(moved[i].normal, G.linear() * reference[i].normal, 1e-9);
        EXPECT_NEAR(moved[i].depth, reference[i].depth, 1e-9);
      }
    }
  }
}

TEST(Symmetry, SwappingShapesFlipsTheNormals) {
  for (const Case& k : cases()) {
    const auto ab = contacts(*k.a, k.X_a, *k.b, k.X_b);
    const auto ba = contacts(*k.b, k.X_b, *k.a, k.X_a);
    ASSERT_EQ(ab.size(), ba.size());
    for (std::size_t i = 0; i < ab.size(); ++i) {
      EXPECT_EQ(ab[i].position, ba[i].position);
      EXPECT_EQ(ab[i].normal, Vector3D(-ba[i].normal));
      EXPECT_EQ(ab[i].depth, ba[i].depth);
    }
  }
}

TEST(Determinism, SameInputGivesBitIdenticalOutput) {
  for (const Case& k : cases()) {
    const auto first = contacts(*k.a, k.X_a, *k.b, k.X_b);
    const auto second = contacts(*k.a, k.X_a, *k.b, k.X_b);
    ASSERT_EQ(first.size(), second.size());
    EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(ContactPoint)), 0);
  }
}

TEST(Stability, RestingManifoldKeepsItsPointsUnderNoise) {
  // Sub-micrometre jitter of a resting can must not move its four points around the rim.
  const auto can = Geometry::cylinder(0.04, 0.12);
  const auto reference =
      contacts(*Geometry::plane(), pose({0, 0, 0}), *can, pose({0, 0, 0.06 - kPen}));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1e-7, 1e-7);
  for (int trial = 0; trial < 20; ++trial) {
    const Transform3D X = pose({u(rng), u(rng), 0.06 - kPen + u(rng)}, u(rng), Vector3D(1, 1, 0));
    const auto c = contacts(*Geometry::plane(), pose({0, 0, 0}), *can, X);
    ASSERT_EQ(c.size(), reference.size());
    for (const ContactPoint& p : reference) EXPECT_TRUE(containsPoint(c, p.position, 1e-6));
  }
}

}  // namespace
}  // namespace rwsim::contacts
