// Contacts of round shapes (cylinders, cones) as curved surfaces, against hand-worked geometry:
// depths, normals and points on the true circle or the true side line.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "contact_test_util.hpp"
#include "rwsim/contacts/round_contact.hpp"

namespace rwsim::contacts {
namespace {

using test::contacts;
using test::expectAllNormals;
using test::Geometry;
using test::kPen;
using test::kPi;
using test::pose;

/// A cylinder lying along y (its z axis turned onto -y), rolled by `roll` about its own axis.
Transform3D lyingAlongY(const Vector3D& p, double roll) {
  return pose(p, kPi / 2, Vector3D::UnitX()) * pose({0, 0, 0}, roll);
}

ContactOptions manyPoints() {
  ContactOptions options;
  options.maxPointsPerManifold = detail::kRimPoints;
  return options;
}

TEST(RoundContacts, LyingCylinderOnABoxTouchesAlongItsSideLineAtAnyRoll) {
  const double r = 0.03;
  const auto can = Geometry::cylinder(r, 0.1);
  const auto table = Geometry::box(1, 1, 0.1);
  for (const double roll : {0.0, 0.37, kPi / 32, 2.0}) {
    const auto c =
        contacts(*table, pose({0, 0, -0.05}), *can, lyingAlongY({0.1, 0, r - kPen}, roll));
    ASSERT_EQ(c.size(), 2u) << "roll " << roll;
    expectAllNormals(c, Vector3D::UnitZ());
    for (const ContactPoint& p : c) {
      EXPECT_NEAR(p.depth, kPen, 1e-12);
      EXPECT_NEAR(p.position.x(), 0.1, 1e-12);
      EXPECT_NEAR(std::abs(p.position.y()), 0.05, 1e-12);
      EXPECT_NEAR(p.position.z(), -kPen / 2, 1e-12);
    }
  }
}

TEST(RoundContacts, StandingCylinderOnABoxGivesRimPointsOnTheTrueCircle) {
  const double r = 0.03;
  const auto can = Geometry::cylinder(r, 0.1);
  const auto table = Geometry::box(1, 1, 0.1);
  const auto c =
      contacts(*table, pose({0, 0, -0.05}), *can, pose({0.2, 0.1, 0.05 - kPen}, 0.2), manyPoints());
  ASSERT_EQ(c.size(), static_cast<std::size_t>(detail::kRimPoints));
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(std::hypot(p.position.x() - 0.2, p.position.y() - 0.1), r, 1e-12);
    EXPECT_NEAR(p.depth, kPen, 1e-12);
  }
}

TEST(RoundContacts, TiltedCylinderOnAPlaneTouchesAtItsLowestRimPoint) {
  // Tilted 30 degrees about x: the lowest point is the bottom rim's point at local y = -r,
  // at z = -r sin 30 - h/2 cos 30 and y = -r cos 30 + h/2 sin 30 from the centre.
  const double r = 0.04;
  const double h = 0.12;
  const double t = 30.0 * kPi / 180.0;
  const double zc = r * std::sin(t) + h / 2 * std::cos(t) - kPen;
  const auto c = contacts(*Geometry::plane(), pose({0, 0, 0}), *Geometry::cylinder(r, h),
                          pose({0.1, 0, zc}, t, Vector3D::UnitX()));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-12);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-15);
  EXPECT_VECTOR_NEAR(c[0].position,
                     Vector3D(0.1, -r * std::cos(t) + h / 2 * std::sin(t), -kPen / 2), 1e-12);
}

TEST(RoundContacts, ParallelCylindersTouchAlongTheirCommonSideLine) {
  // Radii 0.03 and 0.02 along y, axes 0.05 - kPen apart in x; lengths 0.1 and 0.06 (offset
  // 0.01), so the lines overlap for y in [-0.02, 0.04].
  const auto a = Geometry::cylinder(0.03, 0.1);
  const auto b = Geometry::cylinder(0.02, 0.06);
  const auto c =
      contacts(*a, lyingAlongY({0, 0, 0}, 0.4), *b, lyingAlongY({0.05 - kPen, 0.01, 0}, -1.1));
  ASSERT_EQ(c.size(), 2u);
  expectAllNormals(c, Vector3D::UnitX());
  double ymin = 1;
  double ymax = -1;
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.depth, kPen, 1e-12);
    EXPECT_NEAR(p.position.x(), 0.03 - kPen / 2, 1e-12);
    EXPECT_NEAR(p.position.z(), 0.0, 1e-12);
    ymin = std::min(ymin, p.position.y());
    ymax = std::max(ymax, p.position.y());
  }
  EXPECT_NEAR(ymin, -0.02, 1e-12);
  EXPECT_NEAR(ymax, 0.04, 1e-12);
}

TEST(RoundContacts, CrossedCylindersTouchAtOnePoint) {
  // A (r 0.03) along y, B (r 0.02) along x above it: one point between the axes.
  const auto a = Geometry::cylinder(0.03, 0.1);
  const auto b = Geometry::cylinder(0.02, 0.1);
  const auto c = contacts(*a, lyingAlongY({0, 0, 0}, 0.0), *b,
                          pose({0, 0, 0.05 - kPen}, kPi / 2, Vector3D::UnitY()));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-9);
  EXPECT_VECTOR_NEAR(c[0].position, Vector3D(0, 0, 0.03 - kPen / 2), 1e-9);
}

TEST(RoundContacts, SphereOnACylinderSideIsRadial) {
  const double angle = 0.3;
  const Vector3D radial(std::cos(angle), std::sin(angle), 0);
  const auto c = contacts(*Geometry::cylinder(0.04, 0.12), pose({0, 0, 0}), *Geometry::sphere(0.01),
                          pose((0.05 - kPen) * radial + Vector3D(0, 0, 0.02)));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].normal, radial, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].position, (0.04 - kPen / 2) * radial + Vector3D(0, 0, 0.02), 1e-9);
}

TEST(RoundContacts, ConeStandsOnItsApexOrOnItsBaseRim) {
  // Cone: apex at -h/2, base disk of radius r at +h/2.
  const double r = 0.05;
  const double h = 0.1;
  const auto cone = Geometry::cone(r, h);
  const auto apex =
      contacts(*Geometry::plane(), pose({0, 0, 0}), *cone, pose({0.1, 0, h / 2 - kPen}));
  ASSERT_EQ(apex.size(), 1u);
  EXPECT_NEAR(apex[0].depth, kPen, 1e-12);
  EXPECT_VECTOR_NEAR(apex[0].position, Vector3D(0.1, 0, -kPen / 2), 1e-12);
  const auto base = contacts(*Geometry::box(1, 1, 0.1), pose({0, 0, -0.05}), *cone,
                             pose({0.1, 0, h / 2 - kPen}, kPi, Vector3D::UnitX()), manyPoints());
  ASSERT_EQ(base.size(), static_cast<std::size_t>(detail::kRimPoints));
  for (const ContactPoint& p : base) {
    EXPECT_NEAR(std::hypot(p.position.x() - 0.1, p.position.y()), r, 1e-12);
    EXPECT_NEAR(p.depth, kPen, 1e-12);
  }
}

TEST(RoundContacts, SlenderConeOnItsApexTouchesABoxAtOnce) {
  // A slender cone (base r 2 cm, 10 cm tall: apex angle 2 atan(0.2) = 22.6 deg) reaches past its
  // shrunk core by rounding / sin(11.3 deg) = 5.1 roundings at the apex. Standing on its apex on
  // a box, it touches there as soon as it overlaps, as on a half-space.
  const double h = 0.1;
  const auto cone = Geometry::cone(0.02, h);
  for (const double pen : {kPen, 0.003}) {
    const auto c = contacts(*Geometry::box(1, 1, 0.1), pose({0, 0, -0.05}), *cone,
                            pose({0.1, 0, h / 2 - pen}));
    ASSERT_EQ(c.size(), 1u) << "penetration " << pen;
    expectAllNormals(c, Vector3D::UnitZ());
    EXPECT_NEAR(c[0].depth, pen, 1e-9);
    EXPECT_VECTOR_NEAR(c[0].position, Vector3D(0.1, 0, -pen / 2), 1e-9);
  }
}

TEST(RoundContacts, FrustumStandsOnItsBottomRimAndLiesOnItsSideLine) {
  // Radii 0.04 (bottom, -h/2) and 0.02 (top), h 0.1: the side line rises at atan(0.02 / 0.1).
  const double h = 0.1;
  const auto frustum = Geometry::frustum(0.04, 0.02, h);
  const auto standing = contacts(*Geometry::box(1, 1, 0.1), pose({0, 0, -0.05}), *frustum,
                                 pose({0, 0, h / 2 - kPen}), manyPoints());
  ASSERT_EQ(standing.size(), static_cast<std::size_t>(detail::kRimPoints));
  for (const ContactPoint& p : standing) {
    EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), 0.04, 1e-12);
  }
  // Lying: turn it about y until the side line at +x is level, then lower it onto the plane.
  const double tilt = std::atan2(0.02, h);
  const Transform3D X = pose({0, 0, 0}, kPi / 2 + tilt, Vector3D::UnitY());
  const double lowest = (X * Vector3D(0.04, 0, -h / 2)).z();
  const auto lying =
      contacts(*Geometry::plane(), pose({0, 0, 0}), *frustum, pose({0, 0, -lowest - kPen}) * X);
  ASSERT_EQ(lying.size(), 2u);
  for (const ContactPoint& p : lying) EXPECT_NEAR(p.depth, kPen, 1e-12);
  EXPECT_NEAR((lying[0].position - lying[1].position).norm(), std::hypot(0.02, h), 1e-12);
}

TEST(RoundContacts, OverlapDeeperThanTheRoundingFallsBackToTheTessellation) {
  const auto can = Geometry::cylinder(0.03, 0.1);
  const auto c =
      contacts(*Geometry::box(1, 1, 0.1), pose({0, 0, -0.05}), *can, pose({0, 0, 0.05 - 0.005}));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) EXPECT_NEAR(p.depth, 0.005, 1e-9);
}

TEST(RoundContacts, RollingCylinderKeepsTwoPointsAtItsEnds) {
  // Step to step, a can rolling on a box keeps one point at each end, under the axis.
  const double r = 0.03;
  const auto can = Geometry::cylinder(r, 0.1);
  const auto table = Geometry::box(1, 1, 0.1);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1e-7, 1e-7);
  for (int step = 0; step < 50; ++step) {
    const double roll = 0.05 * step;
    const Vector3D p(-r * roll + u(rng), u(rng), r - kPen + u(rng));
    const auto c = contacts(*table, pose({0, 0, -0.05}), *can,
                            lyingAlongY(p, roll) * pose({0, 0, 0}, u(rng), Vector3D(1, 1, 0)));
    ASSERT_EQ(c.size(), 2u) << "step " << step;
    for (const ContactPoint& q : c) {
      EXPECT_NEAR(q.position.x(), p.x(), 1e-6);
      EXPECT_NEAR(std::abs(q.position.y()), 0.05, 1e-6);
    }
  }
}

}  // namespace
}  // namespace rwsim::contacts
