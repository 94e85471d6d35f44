// Exact queries between convex primitives and planes, checked against hand-computed distances.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "proximity_test_util.hpp"
#include "rw/proximity/proximity_queries.hpp"
#include "support/test_support.hpp"

namespace rw::proximity {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

using rw::geometry::Geometry;
using test::boxSurfaceDistance;
using test::pose;
using test::sphereSurfaceDistance;

constexpr double kConvexTol = 1e-9;
const double kHalfDiagonal = std::sqrt(0.5);  // half the face diagonal of a unit box

// Checks the result's consistency: |pointA - pointB| equals the distance.
void expectConsistent(const DistanceResult& r) {
  EXPECT_NEAR((r.pointA - r.pointB).norm(), r.distance, kConvexTol);
}

TEST(BoxBox, AxisAlignedFaceToFace) {
  const auto box = Geometry::box(1, 1, 1);
  const Transform3D Xa = pose({0, 0, 0});
  const Transform3D Xb = pose({1.5, 0.2, -0.1});
  const DistanceResult r = distance(*box, Xa, *box, Xb);
  EXPECT_NEAR(r.distance, 0.5, kConvexTol);
  EXPECT_NEAR(r.pointA.x(), 0.5, kConvexTol);
  EXPECT_NEAR(r.pointB.x(), 1.0, kConvexTol);
  expectConsistent(r);
  EXPECT_NEAR(boxSurfaceDistance(r.pointA, Xa, Vector3D::Constant(0.5)), 0.0, kConvexTol);
  EXPECT_NEAR(boxSurfaceDistance(r.pointB, Xb, Vector3D::Constant(0.5)), 0.0, kConvexTol);
  EXPECT_FALSE(collides(*box, Xa, *box, Xb));
}

TEST(BoxBox, DiagonalOffsetEdgeToEdge) {
  // The boxes' z-parallel edges at (0.5, 0.5) and (1, 1) are closest.
  const auto box = Geometry::box(1, 1, 1);
  const DistanceResult r = distance(*box, pose({0, 0, 0}), *box, pose({1.5, 1.5, 0}));
  EXPECT_NEAR(r.distance, kHalfDiagonal, kConvexTol);
  EXPECT_NEAR(r.pointA.x(), 0.5, kConvexTol);
  EXPECT_NEAR(r.pointA.y(), 0.5, kConvexTol);
  EXPECT_NEAR(r.pointB.x(), 1.0, kConvexTol);
  EXPECT_NEAR(r.pointB.y(), 1.0, kConvexTol);
}

TEST(BoxBox, RotatedFortyFiveDegreesAboutZ) {
  // B's vertical edge points at A's +x face from d - sqrt(1/2).
  const auto box = Geometry::box(1, 1, 1);
  const Transform3D Xa = pose({0, 0, 0});
  const double d = 1.5;
  const Transform3D Xb = pose({d, 0, 0}, 45, 0, 0);
  const DistanceResult r = distance(*box, Xa, *box, Xb);
  EXPECT_NEAR(r.distance, d - kHalfDiagonal - 0.5, kConvexTol);
  EXPECT_NEAR(r.pointA.x(), 0.5, kConvexTol);
  EXPECT_NEAR(r.pointA.y(), 0.0, kConvexTol);
  EXPECT_NEAR(r.pointB.x(), d - kHalfDiagonal, kConvexTol);
  EXPECT_NEAR(r.pointB.y(), 0.0, kConvexTol);
  EXPECT_NEAR(boxSurfaceDistance(r.pointB, Xb, Vector3D::Constant(0.5)), 0.0, kConvexTol);
  expectConsistent(r);
}

TEST(BoxBox, RotatedTouchingAndJustSeparated) {
  const auto box = Geometry::box(1, 1, 1);
  const Transform3D Xa = pose({0, 0, 0});
  const double contact = 0.5 + kHalfDiagonal;
  EXPECT_TRUE(collides(*box, Xa, *box, pose({contact - 0.1, 0, 0}, 45, 0, 0)));
  EXPECT_TRUE(collides(*box, Xa, *box, pose({contact, 0, 0}, 45, 0, 0)));
  const Transform3D apart = pose({contact + 1e-4, 0, 0}, 45, 0, 0);
  EXPECT_FALSE(collides(*box, Xa, *box, apart));
  EXPECT_NEAR(distance(*box, Xa, *box, apart).distance, 1e-4, kConvexTol);
}

TEST(BoxBox, OverlapGivesACommonPoint) {
  const auto box = Geometry::box(1, 1, 1);
  const Transform3D Xa = pose({0, 0, 0}, 10, 20, 30);
  const Transform3D Xb = pose({0.7, 0.3, 0.2}, -15, 5, 45);
  const DistanceResult r = distance(*box, Xa, *box, Xb);
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_VECTOR_NEAR(r.pointA, r.pointB, 0.0);
  const Vector3D localA = Xa.inverse() * r.pointA;
  const Vector3D localB = Xb.inverse() * r.pointB;
  EXPECT_LE(localA.cwiseAbs().maxCoeff(), 0.5 + kConvexTol);
  EXPECT_LE(localB.cwiseAbs().maxCoeff(), 0.5 + kConvexTol);
  EXPECT_TRUE(collides(*box, Xa, *box, Xb));
}

TEST(SphereSphere, SeparatedAndOverlapping) {
  const auto a = Geometry::sphere(0.3);
  const auto b = Geometry::sphere(0.2);
  const Vector3D cb(0.3, 0.4, 1.2);  // 1.3 from the origin
  const DistanceResult r = distance(*a, pose({0, 0, 0}), *b, pose(cb));
  EXPECT_NEAR(r.distance, 0.8, kConvexTol);
  EXPECT_VECTOR_NEAR(r.pointA, Vector3D(cb * (0.3 / 1.3)), kConvexTol);
  EXPECT_VECTOR_NEAR(r.pointB, Vector3D(cb * (1.1 / 1.3)), kConvexTol);
  EXPECT_FALSE(collides(*a, pose({0, 0, 0}), *b, pose(cb)));

  const Vector3D close(0.0, 0.4, 0.0);
  const DistanceResult o = distance(*a, pose({0, 0, 0}), *b, pose(close));
  EXPECT_EQ(o.distance, 0.0);
  EXPECT_LE(o.pointA.norm(), 0.3 + kConvexTol);
  EXPECT_LE((o.pointA - close).norm(), 0.2 + kConvexTol);
  EXPECT_TRUE(collides(*a, pose({0, 0, 0}), *b, pose(close)));
  EXPECT_TRUE(collides(*a, pose({0, 0, 0}), *b, pose({0.5, 0, 0})));  // touching
}

// Sphere of radius 0.25 around a unit box in its face, edge and corner regions.
struct SphereBoxCase {
  Vector3D centre;  // sphere centre in box coordinates
  Vector3D onBox;   // closest box point in box coordinates
  double expected;  // distance
};

class SphereBox : public ::testing::TestWithParam<SphereBoxCase> {};

TEST_P(SphereBox, ExactDistanceInEveryRegion) {
  const SphereBoxCase c = GetParam();
  const auto box = Geometry::box(1, 1, 1);
  const auto sphere = Geometry::sphere(0.25);
  for (const Transform3D& X_box : {pose({0, 0, 0}), pose({0.3, -1.0, 2.0}, 30, -40, 70)}) {
    const Transform3D X_sphere = X_box * pose(c.centre);
    const DistanceResult r = distance(*box, X_box, *sphere, X_sphere);
    EXPECT_NEAR(r.distance, c.expected, kConvexTol);
    EXPECT_VECTOR_NEAR(r.pointA, Vector3D(X_box * c.onBox), kConvexTol);
    EXPECT_NEAR(sphereSurfaceDistance(r.pointB, X_sphere.translation(), 0.25), 0.0, kConvexTol);
    expectConsistent(r);
    // The same query with the shapes swapped.
    const DistanceResult s = distance(*sphere, X_sphere, *box, X_box);
    EXPECT_NEAR(s.distance, c.expected, kConvexTol);
    EXPECT_VECTOR_NEAR(s.pointB, Vector3D(X_box * c.onBox), kConvexTol);
    EXPECT_FALSE(collides(*box, X_box, *sphere, X_sphere));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Regions, SphereBox,
    ::testing::Values(SphereBoxCase{{1.0, 0.1, -0.2}, {0.5, 0.1, -0.2}, 0.25},
                      SphereBoxCase{{1.0, 1.0, 0.2}, {0.5, 0.5, 0.2}, std::sqrt(0.5) - 0.25},
                      SphereBoxCase{{1.0, 1.0, 1.0}, {0.5, 0.5, 0.5}, std::sqrt(0.75) - 0.25},
                      SphereBoxCase{{-0.2, -0.9, 0.0}, {-0.2, -0.5, 0.0}, 0.15}));

TEST(SphereBox, PenetratingSphereCollides) {
  const auto box = Geometry::box(1, 1, 1);
  const auto sphere = Geometry::sphere(0.25);
  const DistanceResult r = distance(*box, pose({0, 0, 0}), *sphere, pose({0.6, 0, 0}));
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_LE(r.pointA.cwiseAbs().maxCoeff(), 0.5 + kConvexTol);
  EXPECT_LE((r.pointA - Vector3D(0.6, 0, 0)).norm(), 0.25 + kConvexTol);
  EXPECT_TRUE(collides(*box, pose({0, 0, 0}), *sphere, pose({0.6, 0, 0})));
}

TEST(CylinderBox, SideCapAndRim) {
  const auto cylinder = Geometry::cylinder(0.2, 1.0);  // z from -0.5 to 0.5
  const auto box = Geometry::box(1, 1, 1);
  const Transform3D Xc = pose({0, 0, 0});
  // Side: the box's -x face at 0.5, the cylinder's side at 0.2.
  EXPECT_NEAR(distance(*cylinder, Xc, *box, pose({1.0, 0.3, 0})).distance, 0.3, kConvexTol);
  // Cap: the box's bottom at 0.7, the cap at 0.5.
  EXPECT_NEAR(distance(*cylinder, Xc, *box, pose({0.1, 0.1, 1.2})).distance, 0.2, kConvexTol);
  // Rim: the box's edge (0.5, y, 0.8) against the rim point (0.2, 0, 0.5).
  const DistanceResult rim = distance(*cylinder, Xc, *box, pose({1.0, 0, 1.3}));
  EXPECT_NEAR(rim.distance, std::sqrt(0.18), kConvexTol);
  // Points on curved surfaces are only accurate to about the square root of the distance's
  // precision (the distance is flat in the tangential direction).
  EXPECT_VECTOR_NEAR(rim.pointA, Vector3D(0.2, 0, 0.5), 1e-7);
  EXPECT_NEAR(rim.pointB.x(), 0.5, kConvexTol);
  EXPECT_NEAR(rim.pointB.z(), 0.8, kConvexTol);
  // Lying cylinder (axis along y) under a box: round side at 0.2, box bottom at 0.5.
  EXPECT_NEAR(distance(*cylinder, pose({0, 0, 0}, 0, 0, 90), *box, pose({0, 0.3, 1.0})).distance,
              0.3, kConvexTol);
  EXPECT_TRUE(collides(*cylinder, Xc, *box, pose({0.65, 0, 0})));
  EXPECT_FALSE(collides(*cylinder, Xc, *box, pose({0.7 + 1e-4, 0, 0})));
}

TEST(Cone, ApexAndSlantedSide) {
  const auto cone = Geometry::cone(0.3, 1.0);  // apex (0, 0, -0.5), base disk at +0.5
  const auto box = Geometry::box(1, 1, 1);
  const DistanceResult apex = distance(*cone, pose({0, 0, 0}), *box, pose({0, 0, -1.5}));
  EXPECT_NEAR(apex.distance, 0.5, kConvexTol);
  EXPECT_VECTOR_NEAR(apex.pointA, Vector3D(0, 0, -0.5), kConvexTol);
  // A sphere beside the slanted side: the side line runs from (0, -0.5) to (0.3, 0.5) in x-z,
  // so the point (1, 0) lies 0.85 / sqrt(1.09) from it.
  const auto sphere = Geometry::sphere(0.1);
  const DistanceResult side = distance(*cone, pose({0, 0, 0}), *sphere, pose({1, 0, 0}));
  EXPECT_NEAR(side.distance, 0.85 / std::sqrt(1.09) - 0.1, kConvexTol);
  EXPECT_NEAR(side.pointA.y(), 0.0, kConvexTol);
  EXPECT_NEAR(side.pointA.x(), 0.3 * (side.pointA.z() + 0.5), kConvexTol);  // on the slanted side
}

TEST(Plane, BoxRestingLiftedAndPenetrating) {
  const auto plane = Geometry::plane();
  const auto box = Geometry::box(1, 1, 1);
  const Transform3D Xp = pose({0, 0, 0});
  EXPECT_TRUE(collides(*plane, Xp, *box, pose({3, -2, 0.5})));  // resting
  EXPECT_EQ(distance(*plane, Xp, *box, pose({3, -2, 0.5})).distance, 0.0);
  const Transform3D lifted = pose({3, -2, 0.5 + 1e-4});
  EXPECT_FALSE(collides(*plane, Xp, *box, lifted));
  const DistanceResult r = distance(*plane, Xp, *box, lifted);
  EXPECT_NEAR(r.distance, 1e-4, kConvexTol);
  EXPECT_NEAR(r.pointA.z(), 0.0, kConvexTol);
  EXPECT_NEAR(r.pointB.z(), 1e-4, kConvexTol);
  const DistanceResult sunk = distance(*box, pose({0, 0, 0.3}), *plane, Xp);
  EXPECT_EQ(sunk.distance, 0.0);
  EXPECT_LE(sunk.pointA.z(), 0.0);
  EXPECT_TRUE(collides(*box, pose({0, 0, 0.3}), *plane, Xp));
  // Standing on an edge: rotated 45 degrees about x, the lowest edge is sqrt(1/2) below centre.
  EXPECT_NEAR(distance(*plane, Xp, *box, pose({0, 0, 1.0}, 0, 0, 45)).distance, 1.0 - kHalfDiagonal,
              kConvexTol);
}

TEST(Plane, TiltedPlaneAndSphere) {
  const auto plane = Geometry::plane();
  const auto sphere = Geometry::sphere(0.25);
  const Transform3D Xp = pose({1, 2, 3}, 20, 30, 40);
  const Vector3D normal = Xp.linear().col(2);
  const Vector3D centre = Xp * Vector3D(0.7, -0.4, 1.0);  // 1 m above the plane
  const DistanceResult r = distance(*sphere, pose(centre), *plane, Xp);
  EXPECT_NEAR(r.distance, 0.75, kConvexTol);
  EXPECT_VECTOR_NEAR(r.pointA, Vector3D(centre - 0.25 * normal), kConvexTol);
  EXPECT_VECTOR_NEAR(r.pointB, Vector3D(centre - 1.0 * normal), kConvexTol);
  EXPECT_TRUE(collides(*sphere, pose(Vector3D(centre - 0.9 * normal)), *plane, Xp));
}

TEST(Plane, TwoPlanes) {
  const auto plane = Geometry::plane();
  // A floor (z <= 0) and a ceiling at z = 2 facing down (z >= 2): 2 m apart.
  const DistanceResult r = distance(*plane, pose({0, 0, 0}), *plane, pose({0, 0, 2}, 0, 0, 180));
  EXPECT_NEAR(r.distance, 2.0, kConvexTol);
  EXPECT_FALSE(collides(*plane, pose({0, 0, 0}), *plane, pose({0, 0, 2}, 0, 0, 180)));
  EXPECT_TRUE(collides(*plane, pose({0, 0, 0}), *plane, pose({0, 0, 2}, 0, 30, 0)));
}

TEST(BoxBox, RandomPosesMatchTheirTriangles) {
  // Boxes are exactly their 12 triangles: GJK must agree with brute force over triangle pairs.
  const auto a = Geometry::box(0.3, 0.5, 0.2);
  const auto b = Geometry::box(0.4, 0.1, 0.25);
  const ProximityModel ma(*a);
  const ProximityModel mb(*b);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> angle(-180.0, 180.0);
  std::uniform_real_distribution<double> offset(-0.6, 0.6);
  int separated = 0;
  for (int i = 0; i < 200; ++i) {
    const Transform3D Xa = pose({0, 0, 0}, angle(random), angle(random), angle(random));
    const Transform3D Xb = pose({offset(random), offset(random), offset(random)}, angle(random),
                                angle(random), angle(random));
    double truth = std::numeric_limits<double>::infinity();
    for (const auto& ta : a->triangles().triangles) {
      const auto& va = a->triangles().vertices;
      const Triangle ta3{{Xa * va[ta[0]], Xa * va[ta[1]], Xa * va[ta[2]]}};
      for (const auto& tb : b->triangles().triangles) {
        const auto& vb = b->triangles().vertices;
        const Triangle tb3{{Xb * vb[tb[0]], Xb * vb[tb[1]], Xb * vb[tb[2]]}};
        truth = std::min(truth, triangleDistance(ta3, tb3).distance);
      }
    }
    if (truth < 1e-6) continue;  // overlapping or nearly touching: checked elsewhere
    ++separated;
    const DistanceResult r = distance(ma, Xa, mb, Xb);
    EXPECT_NEAR(r.distance, truth, kConvexTol) << "pose " << i;
    expectConsistent(r);
    EXPECT_NEAR(boxSurfaceDistance(r.pointA, Xa, Vector3D(0.15, 0.25, 0.1)), 0.0, kConvexTol);
    EXPECT_NEAR(boxSurfaceDistance(r.pointB, Xb, Vector3D(0.2, 0.05, 0.125)), 0.0, kConvexTol);
    EXPECT_FALSE(collides(ma, Xa, mb, Xb));
  }
  EXPECT_GT(separated, 50);
}

TEST(UpperBound, CutsOffFartherResults) {
  const auto box = Geometry::box(1, 1, 1);
  const ProximityModel model(*box);
  const DistanceResult far = distance(model, pose({0, 0, 0}), model, pose({3, 0, 0}), 1.0);
  EXPECT_TRUE(std::isinf(far.distance));
  const DistanceResult near = distance(model, pose({0, 0, 0}), model, pose({1.5, 0, 0}), 1.0);
  EXPECT_NEAR(near.distance, 0.5, kConvexTol);
}

}  // namespace
}  // namespace rw::proximity
