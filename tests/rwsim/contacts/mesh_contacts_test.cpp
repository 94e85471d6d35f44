// collide() on meshes: large convex meshes, non-convex meshes, flat patches, tubes and
// RobWork's SDH fingertip hull.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact_test_util.hpp"
#include "rw/geometry/mesh_loader.hpp"
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

/// The L of side 0.2 with a 0.1 x 0.1 notch, 0.05 thick, bottom at z = 0 (area 0.03 m^2).
std::shared_ptr<const Geometry> lShape() {
  const std::vector<Eigen::Vector2d> l = {{0, 0},     {0.2, 0},   {0.2, 0.1},
                                          {0.1, 0.1}, {0.1, 0.2}, {0, 0.2}};
  return test::meshGeometry(test::prism(l, 0, 0.05));
}

bool inL(double x, double y, double tol) {
  const bool inSquare = x >= -tol && x <= 0.2 + tol && y >= -tol && y <= 0.2 + tol;
  const bool inNotch = x > 0.1 + tol && y > 0.1 + tol;
  return inSquare && !inNotch;
}

TEST(ConvexMesh, FineSphereOnPlaneTouchesAtItsPole) {
  const auto ball = test::meshGeometry(test::uvSphere(0.05, 40, 26));
  ASSERT_GE(ball->triangles().triangles.size(), 1000u);
  // The next ring lies 0.36 mm above the pole, inside the default margin: use a smaller one.
  ContactOptions options;
  options.margin = 1e-4;
  const auto c =
      contacts(*Geometry::plane(), pose({0, 0, 0}), *ball, pose({0.3, 0, 0.05 - kPen}), options);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-12);
  EXPECT_VECTOR_NEAR(c[0].position, Vector3D(0.3, 0, -kPen / 2), 1e-12);
}

TEST(ConvexMesh, FineCylinderStandingOnBox) {
  const auto can = test::meshGeometry(test::fineCylinder(0.03, 0.1, 600));
  ASSERT_GE(can->triangles().triangles.size(), 1000u);
  const auto table = Geometry::box(1, 1, 0.1);
  const auto c = contacts(*table, pose({0, 0, -0.05}), *can, pose({0.1, 0.1, 0.05 - kPen}, 0.2));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(std::hypot(p.position.x() - 0.1, p.position.y() - 0.1), 0.03, 1e-9);
    EXPECT_NEAR(p.depth, kPen, 1e-9);
  }
  EXPECT_NEAR(test::hullArea(test::xy(c)), 2 * 0.03 * 0.03, 1e-6);
}

TEST(ConvexMesh, FineCylinderLyingOnBox) {
  const auto can = test::meshGeometry(test::fineCylinder(0.03, 0.1, 600));
  const auto table = Geometry::box(1, 1, 0.1);
  // Vertex 450 of 600 (270 degrees) is lowest after the quarter turn about x; its neighbours
  // are 1.6 um higher, so their lines are in contact too.
  const auto c = contacts(*table, pose({0, 0, -0.05}), *can,
                          pose({0, 0, 0.03 - kPen}, kPi / 2, Vector3D::UnitX()));
  ASSERT_GE(c.size(), 2u);
  double ymin = 1;
  double ymax = -1;
  for (const ContactPoint& p : c) {
    EXPECT_LE(std::abs(p.position.x()), 0.03 * std::sin(2 * kPi / 600) + 1e-9);
    EXPECT_NEAR(p.depth, kPen, 2e-6);
    ymin = std::min(ymin, p.position.y());
    ymax = std::max(ymax, p.position.y());
  }
  EXPECT_NEAR(ymax - ymin, 0.1, 1e-9);
}

TEST(NonConvexMesh, LShapeLyingOnABox) {
  const auto table = Geometry::box(1, 1, 0.1);
  const auto c = contacts(*table, pose({0, 0, -0.05}), *lShape(), pose({0, 0, -kPen}));
  ASSERT_FALSE(c.empty());
  ASSERT_LE(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    EXPECT_TRUE(inL(p.position.x(), p.position.y(), 1e-9)) << p.position.transpose();
  }
  // Four of the L's corners: at least the 0.2 x 0.1 + half-notch quadrilateral.
  EXPECT_GT(test::hullArea(test::xy(c)), 0.025);
}

TEST(NonConvexMesh, BoxOnTheLShapeInBothArgumentOrders) {
  const auto small = Geometry::box(0.06, 0.06, 0.02);
  const Transform3D X_box = pose({0.05, 0.1, 0.06 - kPen}, 0.3);
  const auto c = contacts(*lShape(), pose({0, 0, 0}), *small, X_box);
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) EXPECT_NEAR(p.depth, kPen, 1e-9);
  const auto swapped = contacts(*small, X_box, *lShape(), pose({0, 0, 0}));
  ASSERT_EQ(swapped.size(), 4u);
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(c[i].position, swapped[i].position);
    EXPECT_EQ(c[i].normal, Vector3D(-swapped[i].normal));
  }
}

TEST(NonConvexMesh, OverhangingTheRimKeepsTheNormalUp) {
  // The box hangs over the L's +x rim by less than the penetration: no sideways normals from
  // the side wall, whose top edge it presses.
  const auto small = Geometry::box(0.06, 0.06, 0.02);
  const auto c =
      contacts(*lShape(), pose({0, 0, 0}), *small, pose({0.17 + 0.5 * kPen, 0.05, 0.06 - kPen}));
  ASSERT_FALSE(c.empty());
  expectAllNormals(c, Vector3D::UnitZ());
}

TEST(NonConvexMesh, SphereInTheNotchTouchesBothWalls) {
  // A ball of radius 0.02 in the notch corner, 0.02 - kPen from both inner walls, above the
  // bottom... the notch is open: it lies beside the L, touching the two reflex walls.
  const auto ball = Geometry::sphere(0.02);
  const auto c =
      contacts(*lShape(), pose({0, 0, 0}), *ball, pose({0.12 - kPen, 0.12 - kPen, 0.025}));
  ASSERT_EQ(c.size(), 2u);
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    EXPECT_TRUE(p.normal.isApprox(Vector3D::UnitX(), 1e-9) ||
                p.normal.isApprox(Vector3D::UnitY(), 1e-9));
  }
}

TEST(NonConvexMesh, LShapeOnLShape) {
  const auto c = contacts(*lShape(), pose({0, 0, 0}), *lShape(), pose({0.05, 0.05, 0.05 - kPen}));
  ASSERT_FALSE(c.empty());
  ASSERT_LE(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    EXPECT_TRUE(inL(p.position.x(), p.position.y(), 1e-9));
    EXPECT_TRUE(inL(p.position.x() - 0.05, p.position.y() - 0.05, 1e-9));
  }
}

TEST(NonConvexMesh, LShapeOnAHalfSpaceRestsOnItsCorners) {
  const auto c = contacts(*Geometry::plane(), pose({0, 0, 0}), *lShape(), pose({1, 1, -kPen}));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.depth, kPen, 1e-12);
    EXPECT_TRUE(inL(p.position.x() - 1, p.position.y() - 1, 1e-9));
  }
  EXPECT_GT(test::hullArea(test::xy(c)), 0.025);
}

TEST(NonConvexMesh, SphereOnTopAndBelow) {
  const auto ball = Geometry::sphere(0.02);
  auto c = contacts(*lShape(), pose({0, 0, 0}), *ball, pose({0.05, 0.05, 0.07 - kPen}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-12);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-12);
  c = contacts(*lShape(), pose({0, 0, 0}), *ball, pose({0.05, 0.05, -0.02 + kPen}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_VECTOR_NEAR(c[0].normal, -Vector3D::UnitZ(), 1e-12);
}

TEST(NonConvexMesh, MovingBothShapesMovesTheManifoldAndSwappingFlipsIt) {
  const auto box = Geometry::box(0.06, 0.06, 0.02);
  const Transform3D X_box = pose({0.05, 0.1, 0.06 - kPen}, 0.3);
  const auto reference = contacts(*lShape(), pose({0, 0, 0}), *box, X_box);
  ASSERT_EQ(reference.size(), 4u);
  const Transform3D G = pose({0.3, -0.2, 0.7}, 1.1, Vector3D(0.3, -1, 0.4));
  const auto moved = contacts(*lShape(), G, *box, G * X_box);
  const auto swapped = contacts(*box, G * X_box, *lShape(), G);
  ASSERT_EQ(moved.size(), reference.size());
  ASSERT_EQ(swapped.size(), reference.size());
  for (std::size_t i = 0; i < moved.size(); ++i) {
    EXPECT_VECTOR_NEAR(moved[i].position, G * reference[i].position, 1e-9);
    EXPECT_VECTOR_NEAR(moved[i].normal, G.linear() * reference[i].normal, 1e-9);
    EXPECT_EQ(swapped[i].position, moved[i].position);
    EXPECT_EQ(swapped[i].normal, Vector3D(-moved[i].normal));
  }
}

TEST(FlatMesh, FloorPatchUnderABox) {
  const auto floor = test::meshGeometry(test::floorPatch(2.5));
  const auto box = Geometry::box(0.2, 0.1, 0.05);
  const auto c = contacts(*floor, pose({0, 0, 0}), *box, pose({1, 1, 0.025 - kPen}, 0.4));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) EXPECT_NEAR(p.depth, kPen, 1e-9);
  // Two-sided: a box pressing from below is pushed down.
  const auto below = contacts(*floor, pose({0, 0, 0}), *box, pose({1, 1, -0.025 + kPen}));
  ASSERT_EQ(below.size(), 4u);
  expectAllNormals(below, -Vector3D::UnitZ());
}

TEST(FlatMesh, RobWorkFloorUnderACan) {
  REQUIRE_COMPAT_DATA(data);
  const auto floor =
      Geometry::mesh(rw::geometry::loadMesh(data / "objects/plane_5x5.stl"), "plane_5x5.stl");
  const auto can = Geometry::cylinder(0.04, 0.12);
  const Vector3D top = floor->bounds().max;
  const auto c = contacts(*floor, pose({0, 0, 0}), *can, pose({0.5, 0.5, top.z() + 0.06 - kPen}));
  ASSERT_EQ(c.size(), 4u);
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(p.depth, kPen, 1e-9);
    EXPECT_NEAR(std::abs(p.normal.z()), 1.0, 1e-9);
  }
}

TEST(Tube, StandingOnAPlaneRestsOnItsOuterRim) {
  const auto tube = Geometry::tube(0.03, 0.005, 0.1);
  const auto c = contacts(*Geometry::plane(), pose({0, 0, 0}), *tube, pose({0, 0, 0.05 - kPen}));
  ASSERT_EQ(c.size(), 4u);
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), 0.035, 1e-9);
    EXPECT_NEAR(p.depth, kPen, 1e-9);
  }
}

TEST(Tube, SphereOnItsRim) {
  const auto tube = Geometry::tube(0.03, 0.01, 0.1);
  const auto c =
      contacts(*tube, pose({0, 0, 0}), *Geometry::sphere(0.01), pose({0.035, 0, 0.06 - kPen}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-9);
}

TEST(FlatMesh, SphereOnTheFloorPatch) {
  const auto floor = test::meshGeometry(test::floorPatch(2.5));
  const auto c =
      contacts(*floor, pose({0, 0, 0}), *Geometry::sphere(0.05), pose({1, -2, 0.05 - kPen}));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].depth, kPen, 1e-9);
  EXPECT_VECTOR_NEAR(c[0].normal, Vector3D::UnitZ(), 1e-9);
}

TEST(Tube, BoxOnItsRim) {
  const auto tube = Geometry::tube(0.03, 0.005, 0.1);
  const auto lid = Geometry::box(0.1, 0.1, 0.01);
  const auto c = contacts(*tube, pose({0, 0, 0}), *lid, pose({0, 0, 0.055 - kPen}));
  ASSERT_EQ(c.size(), 4u);
  expectAllNormals(c, Vector3D::UnitZ());
  for (const ContactPoint& p : c) {
    EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), 0.035, 1e-9);
    EXPECT_NEAR(p.depth, kPen, 1e-9);
  }
}

/// Largest signed distance of p (hull frame) to the planes of the hull's triangles: 0 on the
/// surface, negative inside.
double hullDistance(const test::TriMesh& m, const Vector3D& p) {
  double d = -std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles) {
    const Vector3D& a = m.vertices[t[0]];
    const Vector3D n = (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a);
    if (n.norm() < 1e-15) continue;
    d = std::max(d, n.normalized().dot(p - a));
  }
  return d;
}

TEST(RobWorkHull, FingerTipOnABoxFace) {
  REQUIRE_COMPAT_DATA(data);
  const auto mesh = rw::geometry::loadMesh(data / "devices/SDH2/geometry/FingerTip_hull.stl");
  const auto tip = Geometry::mesh(mesh, "FingerTip_hull.stl");
  const auto box = Geometry::box(0.2, 0.2, 0.1);
  for (const double angle : {0.0, 0.7, 1.9, 3.0}) {
    // Orient the tip, then lower it until its lowest vertex is kPen into the box's top face.
    Transform3D X = pose({0, 0, 0}, angle, Vector3D(1, 0.3, 0.2));
    double lowest = std::numeric_limits<double>::infinity();
    for (const Vector3D& v : mesh->vertices) lowest = std::min(lowest, (X * v).z());
    X.translation() = Vector3D(0.01, -0.02, -lowest - kPen);
    const auto c = contacts(*box, pose({0, 0, -0.05}), *tip, X);
    ASSERT_FALSE(c.empty()) << angle;
    ASSERT_LE(c.size(), 4u);
    EXPECT_NEAR(c[0].depth, kPen, 1e-7);
    for (const ContactPoint& p : c) {
      EXPECT_VECTOR_NEAR(p.normal, Vector3D::UnitZ(), 1e-12);
      EXPECT_GE(p.depth, -ContactOptions{}.margin);
      EXPECT_LE(p.depth, kPen + 1e-7);
      // The incident point on the hull is half the depth below the reported position.
      const Vector3D onHull = X.inverse() * (p.position - 0.5 * p.depth * p.normal);
      EXPECT_NEAR(hullDistance(*mesh, onHull), 0.0, 1e-6) << angle;
    }
  }
}

}  // namespace
}  // namespace rwsim::contacts
