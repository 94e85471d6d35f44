// Building blocks: closest points on triangles and segments, triangle pairs, boxes, GJK.
#include <gtest/gtest.h>

#include <cmath>

#include "proximity_test_util.hpp"
#include "rw/proximity/bvh.hpp"
#include "rw/proximity/gjk.hpp"
#include "rw/proximity/triangle_queries.hpp"
#include "support/test_support.hpp"

namespace rw::proximity {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

using test::pose;

constexpr double kTriangleTol = 1e-12;

const Triangle kUnit{{Vector3D(0, 0, 0), Vector3D(1, 0, 0), Vector3D(0, 1, 0)}};

TEST(ClosestPointOnTriangle, EveryRegion) {
  EXPECT_VECTOR_NEAR(closestPointOnTriangle({0.2, 0.3, 5}, kUnit), Vector3D(0.2, 0.3, 0),
                     kTriangleTol);
  EXPECT_VECTOR_NEAR(closestPointOnTriangle({-1, -2, 1}, kUnit), Vector3D(0, 0, 0), kTriangleTol);
  EXPECT_VECTOR_NEAR(closestPointOnTriangle({3, -1, 0}, kUnit), Vector3D(1, 0, 0), kTriangleTol);
  EXPECT_VECTOR_NEAR(closestPointOnTriangle({0.5, -1, 0}, kUnit), Vector3D(0.5, 0, 0),
                     kTriangleTol);
  EXPECT_VECTOR_NEAR(closestPointOnTriangle({-1, 0.5, 0}, kUnit), Vector3D(0, 0.5, 0),
                     kTriangleTol);
  EXPECT_VECTOR_NEAR(closestPointOnTriangle({1, 1, 0}, kUnit), Vector3D(0.5, 0.5, 0), kTriangleTol);
}

TEST(ClosestPointsOnSegments, SkewParallelAndDegenerate) {
  Vector3D c1;
  Vector3D c2;
  // Skew: x axis segment and a y-parallel segment 2 above.
  EXPECT_NEAR(closestPointsOnSegments({-1, 0, 0}, {1, 0, 0}, {0.3, -1, 2}, {0.3, 1, 2}, c1, c2),
              4.0, kTriangleTol);
  EXPECT_VECTOR_NEAR(c1, Vector3D(0.3, 0, 0), kTriangleTol);
  EXPECT_VECTOR_NEAR(c2, Vector3D(0.3, 0, 2), kTriangleTol);
  // Parallel, overlapping in x: distance 1.
  EXPECT_NEAR(closestPointsOnSegments({0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 1, 0}, c1, c2), 1.0,
              kTriangleTol);
  // Clamped ends.
  EXPECT_NEAR(closestPointsOnSegments({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, c1, c2), 1.0,
              kTriangleTol);
  // A point against a segment.
  EXPECT_NEAR(closestPointsOnSegments({0, 0, 0}, {1, 0, 0}, {0.5, 3, 4}, {0.5, 3, 4}, c1, c2), 25.0,
              kTriangleTol);
}

Triangle moved(const Triangle& t, const Transform3D& X) {
  return Triangle{{X * t.v[0], X * t.v[1], X * t.v[2]}};
}

TEST(TrianglePair, ParallelAndCrossing) {
  const Triangle up = moved(kUnit, pose({0.1, 0.1, 0.5}));
  EXPECT_FALSE(trianglesIntersect(kUnit, up, 1e-9));
  const DistanceResult r = triangleDistance(kUnit, up);
  EXPECT_NEAR(r.distance, 0.5, kTriangleTol);
  // Standing up through the first one: (0.25, y, z) for y, z around 0.
  const Triangle crossing{{Vector3D(0.25, 0.2, -1), Vector3D(0.25, 0.2, 1), Vector3D(0.25, -1, 0)}};
  EXPECT_TRUE(trianglesIntersect(kUnit, crossing, 1e-9));
  const DistanceResult c = triangleDistance(kUnit, crossing);
  EXPECT_EQ(c.distance, 0.0);
  EXPECT_NEAR(c.pointA.z(), 0.0, kTriangleTol);
  EXPECT_NEAR(c.pointA.x(), 0.25, kTriangleTol);
}

TEST(TrianglePair, CoplanarOverlapAndGap) {
  const Triangle shifted = moved(kUnit, pose({0.3, 0.3, 0}));
  EXPECT_TRUE(trianglesIntersect(kUnit, shifted, 1e-9));
  EXPECT_EQ(triangleDistance(kUnit, shifted).distance, 0.0);
  // Mirrored across x + y = 1 and moved away by 0.1 along (1, 1)/sqrt(2).
  const double s = 0.1 / std::sqrt(2.0);
  const Triangle mirrored{
      {Vector3D(1 + s, 1 + s, 0), Vector3D(s, 1 + s, 0), Vector3D(1 + s, s, 0)}};
  EXPECT_FALSE(trianglesIntersect(kUnit, mirrored, 1e-9));
  EXPECT_NEAR(triangleDistance(kUnit, mirrored).distance, 0.1, kTriangleTol);
}

TEST(Obb, SeparationAndLowerBound) {
  Obb unit;
  unit.halfExtents = Vector3D::Constant(0.5);
  const rw::math::Rotation3D I = rw::math::Rotation3D::Identity();
  EXPECT_TRUE(obbDisjoint(unit, unit, I, Vector3D(2, 0, 0), 1e-9));
  EXPECT_NEAR(obbDistanceLowerBound(unit, unit, I, Vector3D(2, 0, 0)), 1.0, 1e-9);
  EXPECT_FALSE(obbDisjoint(unit, unit, I, Vector3D(0.9, 0.9, 0.9), 1e-9));
  EXPECT_EQ(obbDistanceLowerBound(unit, unit, I, Vector3D(0.9, 0.9, 0.9)), 0.0);
  // Diagonal: the lower bound never exceeds the true distance sqrt(2) * 0.5.
  const double bound = obbDistanceLowerBound(unit, unit, I, Vector3D(1.5, 1.5, 0));
  EXPECT_GT(bound, 0.0);
  EXPECT_LE(bound, std::sqrt(0.5) + kTriangleTol);
  // Rotated 45 degrees about z: its edge reaches sqrt(1/2) towards the other box.
  const Transform3D X = pose({1.5, 0, 0}, 45, 0, 0);
  EXPECT_NEAR(obbDistanceLowerBound(unit, unit, X.linear(), X.translation()), 1.0 - std::sqrt(0.5),
              1e-9);
}

TEST(FitObb, ContainsThePointsAndIsTightForABox) {
  const auto box = rw::geometry::Geometry::box(1, 2, 3);
  const auto& vertices = box->triangles().vertices;
  const Obb fitted = fitObb(vertices);
  EXPECT_NEAR(fitted.halfExtents.prod(), 0.5 * 1.0 * 1.5, 1e-9);
  for (const Vector3D& v : vertices) {
    const Vector3D local = fitted.axes.transpose() * (v - fitted.center);
    EXPECT_LE((local.cwiseAbs() - fitted.halfExtents).maxCoeff(), 1e-12);
  }
}

TEST(Gjk, BoxAgainstBoxAndSphere) {
  const ConvexShape box = ConvexShape::box(Vector3D::Constant(0.5));
  const GjkResult r = gjkDistance(box, box, pose({2, 0.1, 0.2}));
  EXPECT_NEAR(r.distance, 1.0, 1e-10);
  EXPECT_FALSE(r.exceeded);
  const GjkResult cut = gjkDistance(box, box, pose({2, 0.1, 0.2}), 0.0, 0.5);
  EXPECT_TRUE(cut.exceeded);
  EXPECT_GT(cut.distance, 0.5);
  const ConvexShape sphere = ConvexShape::sphere(0.5);
  EXPECT_NEAR(gjkDistance(sphere, sphere, pose({0, 3, 4})).distance, 4.0, 1e-12);
  EXPECT_EQ(gjkDistance(box, sphere, pose({0.2, 0.3, 0.1})).distance, 0.0);
}

}  // namespace
}  // namespace rw::proximity
