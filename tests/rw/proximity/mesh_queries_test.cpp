// Queries involving meshes and tubes: convex meshes (GJK), non-convex meshes (triangle
// hierarchies) and mixed pairs, against hand-computed distances.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "proximity_test_util.hpp"
#include "rw/proximity/bvh_queries.hpp"
#include "rw/proximity/proximity_queries.hpp"
#include "support/test_support.hpp"

namespace rw::proximity {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

using rw::geometry::Geometry;
using test::lShape;
using test::meshSurfaceDistance;
using test::pose;
using test::tetrahedron;

constexpr double kMeshTol = 1e-9;

// A's slanted face x + y + z = 1 has its centroid at c; B's apex sits `gap` above it along the
// face normal n and B extends away from A.
struct TetraPair {
  std::shared_ptr<const Geometry> a;
  std::shared_ptr<const Geometry> b;
};

TetraPair tetrahedraApart(double gap) {
  const Vector3D n = Vector3D(1, 1, 1).normalized();
  const Vector3D c = Vector3D::Constant(1.0 / 3.0);
  const Vector3D u = Vector3D(1, -1, 0).normalized();
  const Vector3D w = n.cross(u);
  const Vector3D apex = c + gap * n;
  return {tetrahedron(Vector3D::Zero(), Vector3D::UnitX(), Vector3D::UnitY(), Vector3D::UnitZ()),
          tetrahedron(apex, 0.5 * n + 0.3 * w, 0.5 * n - 0.3 * u, 0.5 * n + 0.3 * u)};
}

TEST(Tetrahedra, TouchingAndJustSeparated) {
  for (const double gap : {1e-4, 0.25}) {
    const TetraPair t = tetrahedraApart(gap);
    ASSERT_TRUE(t.a->isConvex());
    ASSERT_TRUE(t.b->isConvex());
    const DistanceResult r = distance(*t.a, pose({0, 0, 0}), *t.b, pose({0, 0, 0}));
    EXPECT_NEAR(r.distance, gap, kMeshTol);
    EXPECT_VECTOR_NEAR(r.pointA, Vector3D::Constant(1.0 / 3.0), 1e-7);
    EXPECT_FALSE(collides(*t.a, pose({0, 0, 0}), *t.b, pose({0, 0, 0})));
  }
  const TetraPair touching = tetrahedraApart(0.0);
  EXPECT_TRUE(collides(*touching.a, pose({0, 0, 0}), *touching.b, pose({0, 0, 0})));
  EXPECT_NEAR(distance(*touching.a, pose({0, 0, 0}), *touching.b, pose({0, 0, 0})).distance, 0.0,
              kMeshTol);
}

TEST(Tetrahedra, TriangleHierarchiesAgreeWithGjk) {
  // The same pairs through the triangle path (used for non-convex meshes).
  for (const double gap : {1e-4, 0.25}) {
    const TetraPair t = tetrahedraApart(gap);
    const Bvh a(t.a->triangles());
    const Bvh b(t.b->triangles());
    const DistanceResult r = bvhDistance(a, b, Transform3D::Identity(), 1e9);
    EXPECT_NEAR(r.distance, gap, kMeshTol);
    EXPECT_FALSE(bvhCollides(a, b, Transform3D::Identity(), kContactTolerance));
    // Both moved by the same pose: the relative pose, hence the distance, is unchanged.
    const Transform3D X = pose({0.1, -0.2, 0.3}, 10, 20, 30);
    const DistanceResult moved = distance(*t.a, X, *t.b, X);
    EXPECT_NEAR(moved.distance, gap, kMeshTol);
  }
  const TetraPair touching = tetrahedraApart(0.0);
  EXPECT_TRUE(bvhCollides(Bvh(touching.a->triangles()), Bvh(touching.b->triangles()),
                          Transform3D::Identity(), kContactTolerance));
}

TEST(ConvexMesh, ClimbingSupportFindsTheFarthestVertex) {
  // A tessellated sphere as a mesh: closed and convex, so its support climbs the vertex graph.
  const auto ball = Geometry::mesh(Geometry::sphere(0.3)->trianglesPtr(), "ball (test)");
  ASSERT_TRUE(ball->isConvex());
  const ProximityModel model(*ball);
  const ConvexShape shape = model.convexShape();
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  std::int32_t hint = 0;
  for (int i = 0; i < 500; ++i) {
    const Vector3D d(normal(random), normal(random), normal(random));
    double best = -1e300;
    for (const Vector3D& v : ball->triangles().vertices) best = std::max(best, v.dot(d));
    EXPECT_NEAR(shape.support(d).dot(d), best, 1e-12);
    EXPECT_NEAR(shape.support(d, hint).dot(d), best, 1e-12);
  }
}

TEST(LShape, IsNotConvexAndTheNotchIsFree) {
  const auto l = lShape();
  ASSERT_FALSE(l->isConvex());
  const ProximityModel model(*l);
  EXPECT_EQ(model.kind(), ProximityModel::Kind::kMesh);
  // A 0.8 cube in the notch [1,2]x[1,2]: 0.1 from the inner faces x = 1 and y = 1.
  const auto cube = Geometry::box(0.8, 0.8, 0.8);
  const Transform3D Xl = pose({0, 0, 0});
  const Transform3D Xc = pose({1.5, 1.5, 0.5});
  EXPECT_FALSE(collides(*l, Xl, *cube, Xc));
  const DistanceResult r = distance(*l, Xl, *cube, Xc);
  EXPECT_NEAR(r.distance, 0.1, kMeshTol);
  EXPECT_NEAR(meshSurfaceDistance(r.pointA, Xl, l->triangles()), 0.0, kMeshTol);
  // The same cube as a (convex) mesh goes through the triangle-triangle path.
  const auto cubeMesh = Geometry::mesh(cube->trianglesPtr(), "cube (test)");
  EXPECT_NEAR(distance(*l, Xl, *cubeMesh, Xc).distance, 0.1, kMeshTol);
  EXPECT_FALSE(collides(*cubeMesh, Xc, *l, Xl));
  // Moved 0.15 toward the corner, it cuts into both inner faces.
  EXPECT_TRUE(collides(*l, Xl, *cube, pose({1.35, 1.35, 0.5})));
  EXPECT_TRUE(collides(*l, Xl, *cubeMesh, pose({1.35, 1.35, 0.5})));
}

TEST(LShape, StackedTouchingSeparatedAndPenetrating) {
  const auto l = lShape();
  const Transform3D Xa = pose({0, 0, 0});
  EXPECT_TRUE(collides(*l, Xa, *l, pose({0.5, 0.5, 1.0})));
  const Transform3D apart = pose({0.5, 0.5, 1.0 + 1e-4});
  EXPECT_FALSE(collides(*l, Xa, *l, apart));
  const DistanceResult r = distance(*l, Xa, *l, apart);
  EXPECT_NEAR(r.distance, 1e-4, kMeshTol);
  EXPECT_NEAR(r.pointA.z(), 1.0, kMeshTol);
  EXPECT_NEAR(r.pointB.z(), 1.0 + 1e-4, kMeshTol);
  const DistanceResult sunk = distance(*l, Xa, *l, pose({0.5, 0.5, 0.9}));
  EXPECT_EQ(sunk.distance, 0.0);
  EXPECT_NEAR(meshSurfaceDistance(sunk.pointA, Xa, l->triangles()), 0.0, kMeshTol);
  EXPECT_NEAR(meshSurfaceDistance(sunk.pointB, pose({0.5, 0.5, 0.9}), l->triangles()), 0.0,
              kMeshTol);
}

TEST(LShape, FacingCornersJustSeparated) {
  // B is A turned by 180 degrees about z and moved to (3 + g, 3 + g): A's corner (2, 1) faces
  // B's corner (2 + g, 1 + g) and likewise (1, 2), so the distance is g * sqrt(2).
  const auto l = lShape();
  const double g = 1e-4 / std::sqrt(2.0);
  const Transform3D Xa = pose({0, 0, 0});
  const Transform3D Xb = pose({3 + g, 3 + g, 0}, 180, 0, 0);
  const DistanceResult r = distance(*l, Xa, *l, Xb);
  EXPECT_NEAR(r.distance, 1e-4, kMeshTol);
  EXPECT_FALSE(collides(*l, Xa, *l, Xb));
  EXPECT_TRUE(collides(*l, Xa, *l, pose({3, 3, 0}, 180, 0, 0)));
  EXPECT_NEAR(meshSurfaceDistance(r.pointA, Xa, l->triangles()), 0.0, kMeshTol);
  EXPECT_NEAR(meshSurfaceDistance(r.pointB, Xb, l->triangles()), 0.0, kMeshTol);
}

// Smallest triangle-pair distance between meshes a (at Xa) and b (at Xb), by brute force.
double bruteForce(const rw::geometry::TriMesh& a, const Transform3D& Xa,
                  const rw::geometry::TriMesh& b, const Transform3D& Xb) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& ta : a.triangles) {
    const Triangle pa{{Xa * a.vertices[ta[0]], Xa * a.vertices[ta[1]], Xa * a.vertices[ta[2]]}};
    for (const auto& tb : b.triangles) {
      const Triangle pb{{Xb * b.vertices[tb[0]], Xb * b.vertices[tb[1]], Xb * b.vertices[tb[2]]}};
      best = std::min(best, triangleDistance(pa, pb).distance);
    }
  }
  return best;
}

TEST(LShape, RandomPosesMatchBruteForceOverTriangles) {
  // The hierarchy may prune only what cannot be closer: compare with every triangle pair.
  const auto l = lShape();
  const auto tube = Geometry::tube(0.3, 0.1, 0.8);
  const ProximityModel ml(*l);
  const ProximityModel mt(*tube);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> angle(-180.0, 180.0);
  std::uniform_real_distribution<double> offset(-2.5, 2.5);
  int separated = 0;
  int overlapping = 0;
  for (int i = 0; i < 24; ++i) {
    const Transform3D Xa = pose({0, 0, 0}, angle(random), angle(random), angle(random));
    const Transform3D Xb = pose({offset(random), offset(random), offset(random)}, angle(random),
                                angle(random), angle(random));
    const ProximityModel& other = i % 2 == 0 ? ml : mt;
    const rw::geometry::TriMesh& otherMesh = i % 2 == 0 ? l->triangles() : tube->triangles();
    const double truth = bruteForce(l->triangles(), Xa, otherMesh, Xb);
    const DistanceResult r = distance(ml, Xa, other, Xb);
    EXPECT_NEAR(r.distance, truth, kMeshTol) << "pose " << i;
    EXPECT_NEAR((r.pointA - r.pointB).norm(), r.distance, kMeshTol);
    EXPECT_EQ(collides(ml, Xa, other, Xb), truth <= kContactTolerance) << "pose " << i;
    (truth > 0.0 ? separated : overlapping) += 1;
  }
  EXPECT_GT(separated, 5);
  EXPECT_GT(overlapping, 3);
}

TEST(LShape, SphereInTheNotchIsExact) {
  // Sphere centre (1.5, 1.5, 0.5): 0.5 from the inner faces; exact, not tessellated.
  const auto l = lShape();
  const auto sphere = Geometry::sphere(0.3);
  const DistanceResult r = distance(*sphere, pose({1.5, 1.5, 0.5}), *l, pose({0, 0, 0}));
  EXPECT_NEAR(r.distance, 0.2, kMeshTol);
  EXPECT_NEAR((r.pointA - Vector3D(1.5, 1.5, 0.5)).norm(), 0.3, kMeshTol);
  EXPECT_TRUE(collides(*sphere, pose({1.25, 1.5, 0.5}), *l, pose({0, 0, 0})));
}

TEST(LShape, OnAPlane) {
  const auto l = lShape();
  const auto plane = Geometry::plane();
  EXPECT_TRUE(collides(*plane, pose({0, 0, 0}), *l, pose({0, 0, 0})));  // resting
  EXPECT_NEAR(distance(*plane, pose({0, 0, 0}), *l, pose({0, 0, 0.25})).distance, 0.25, kMeshTol);
  // Turned 90 degrees about x: the outline now spans z in [0, 2] above the frame origin.
  EXPECT_NEAR(distance(*plane, pose({0, 0, -0.5}), *l, pose({0, 0, 0}, 0, 0, 90)).distance, 0.5,
              kMeshTol);
}

TEST(Tube, ThinCylinderInsideDoesNotCollide) {
  // The tube's inner wall is a 32-gon of circumradius 0.05 (apothem 0.05 cos(pi/32)).
  const auto tube = Geometry::tube(0.05, 0.01, 0.2);
  const auto rod = Geometry::cylinder(0.02, 0.4);
  const double apothem = 0.05 * std::cos(std::numbers::pi / 32);
  const Transform3D Xt = pose({0.3, 0.2, 0.1}, 10, 20, 30);
  EXPECT_FALSE(collides(*tube, Xt, *rod, Xt));
  const DistanceResult r = distance(*tube, Xt, *rod, Xt);
  EXPECT_GE(r.distance, apothem - 0.02 - kMeshTol);
  EXPECT_LE(r.distance, 0.03 + kMeshTol);
  EXPECT_NEAR((r.pointA - r.pointB).norm(), r.distance, kMeshTol);
  EXPECT_NEAR(meshSurfaceDistance(r.pointA, Xt, tube->triangles()), 0.0, kMeshTol);
  // Off the axis by 0.02 it still fits; by 0.04 it cuts into the wall.
  const Transform3D off = Xt * pose({0.02, 0, 0});
  EXPECT_FALSE(collides(*tube, Xt, *rod, off));
  EXPECT_GE(distance(*tube, Xt, *rod, off).distance, apothem - 0.04 - kMeshTol);
  EXPECT_TRUE(collides(*tube, Xt, *rod, Xt * pose({0.04, 0, 0})));
}

}  // namespace
}  // namespace rw::proximity
