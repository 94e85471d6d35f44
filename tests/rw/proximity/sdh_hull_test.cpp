// RobWork's SDH convex hulls (compatibility data): exact GJK answers against brute force over
// every pair of triangles.
#include <gtest/gtest.h>

#include <random>

#include "proximity_test_util.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "rw/proximity/proximity_queries.hpp"
#include "support/test_support.hpp"

namespace rw::proximity {
namespace {

using rw::geometry::Geometry;
using rw::math::Transform3D;
using rw::math::Vector3D;
using test::pose;

// Smallest distance between any triangle of `a` (at X_a) and any of `b` (at X_b).
double bruteForceHullDistance(const rw::geometry::TriMesh& a, const Transform3D& X_a,
                              const rw::geometry::TriMesh& b, const Transform3D& X_b) {
  const auto placed = [](const rw::geometry::TriMesh& m, const Transform3D& X) {
    std::vector<Triangle> out;
    for (const auto& t : m.triangles) {
      out.push_back(Triangle{{X * m.vertices[t[0]], X * m.vertices[t[1]], X * m.vertices[t[2]]}});
    }
    return out;
  };
  double best = std::numeric_limits<double>::infinity();
  for (const Triangle& ta : placed(a, X_a)) {
    for (const Triangle& tb : placed(b, X_b))
      best = std::min(best, triangleDistance(ta, tb).distance);
  }
  return best;
}

TEST(SdhHull, ConvexHullQueriesMatchBruteForce) {
  REQUIRE_COMPAT_DATA(data);
  const auto box = Geometry::box(0.03, 0.02, 0.05);
  const ProximityModel boxModel(*box);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> angle(-180.0, 180.0);
  std::uniform_real_distribution<double> offset(-0.06, 0.06);
  int overlapping = 0;
  for (const char* name : {"FingerTip_hull.stl", "FingerMid_hull.stl"}) {
    const auto mesh = rw::geometry::loadMesh(data / "devices/SDH2/geometry" / name);
    const auto hull = Geometry::mesh(mesh, name);
    ASSERT_TRUE(hull->isConvex()) << name;
    const ProximityModel hullModel(*hull);
    ASSERT_EQ(hullModel.kind(), ProximityModel::Kind::kConvex);
    int separated = 0;
    for (int i = 0; i < 4; ++i) {
      const Transform3D X_hull = pose({0.01, -0.02, 0.03}, angle(random), angle(random), 0.0);
      const Transform3D X_box = pose({offset(random), offset(random), 0.03 + offset(random)},
                                     angle(random), angle(random), angle(random));
      const double truth = bruteForceHullDistance(*mesh, X_hull, box->triangles(), X_box);
      const DistanceResult r = distance(hullModel, X_hull, boxModel, X_box);
      if (truth > 1e-6) {
        ++separated;
        EXPECT_NEAR(r.distance, truth, 1e-9) << name << " pose " << i;
        EXPECT_FALSE(collides(hullModel, X_hull, boxModel, X_box)) << name << " pose " << i;
      } else if (truth == 0.0) {
        ++overlapping;
        EXPECT_EQ(r.distance, 0.0) << name << " pose " << i;
        EXPECT_TRUE(collides(hullModel, X_hull, boxModel, X_box)) << name << " pose " << i;
      }
    }
    EXPECT_GT(separated, 0) << name;
  }
  EXPECT_GT(overlapping, 0);
}

}  // namespace
}  // namespace rw::proximity
