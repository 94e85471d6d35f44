// Manifold reduction and normal clustering on hand-made candidate sets.
#include "rwsim/contacts/manifold.hpp"

#include <gtest/gtest.h>

#include "support/test_support.hpp"

namespace rwsim::contacts::detail {
namespace {

using rw::math::Vector3D;

ContactPoint point(double x, double y, double depth, const Vector3D& n = Vector3D::UnitZ()) {
  return {Vector3D(x, y, 0), n, depth};
}

bool contains(const std::vector<ContactPoint>& points, double x, double y) {
  for (const ContactPoint& p : points) {
    if ((p.position - Vector3D(x, y, 0)).norm() < 1e-12) return true;
  }
  return false;
}

TEST(ReduceManifold, GridKeepsDeepestThenCorners) {
  std::vector<ContactPoint> grid;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) grid.push_back(point(i * 0.1, j * 0.1, 1e-4));
  }
  grid[4].depth = 2e-4;  // the centre is deepest
  ReduceScratch scratch;
  std::vector<ContactPoint> out;
  reduceManifold(grid, Vector3D::UnitZ(), 5, out, scratch);
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0].depth, 2e-4);
  for (const double x : {0.0, 0.2}) {
    for (const double y : {0.0, 0.2}) EXPECT_TRUE(contains(out, x, y)) << x << " " << y;
  }
}

TEST(ReduceManifold, EqualDepthsGiveTheFourCorners) {
  std::vector<ContactPoint> grid;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) grid.push_back(point(i * 0.1, j * 0.1, 1e-4));
  }
  ReduceScratch scratch;
  std::vector<ContactPoint> out;
  reduceManifold(grid, Vector3D::UnitZ(), 4, out, scratch);
  ASSERT_EQ(out.size(), 4u);
  for (const double x : {0.0, 0.3}) {
    for (const double y : {0.0, 0.3}) EXPECT_TRUE(contains(out, x, y));
  }
}

TEST(ReduceManifold, DuplicatesAndCollinearExtrasAreDropped) {
  const std::vector<ContactPoint> line = {point(0, 0, 1e-4), point(0, 0, 1e-4), point(0.1, 0, 1e-4),
                                          point(0.2, 0, 1e-4), point(0.2, 0, 1e-4)};
  ReduceScratch scratch;
  std::vector<ContactPoint> out;
  reduceManifold(line, Vector3D::UnitZ(), 4, out, scratch);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(contains(out, 0, 0));
  EXPECT_TRUE(contains(out, 0.2, 0));
  out.clear();
  const std::vector<ContactPoint> same(6, point(1, 1, 1e-4));
  reduceManifold(same, Vector3D::UnitZ(), 4, out, scratch);
  EXPECT_EQ(out.size(), 1u);
}

TEST(ReduceManifold, OnePointKeepsTheDeepest) {
  const std::vector<ContactPoint> pts = {point(0, 0, 1e-4), point(1, 0, 3e-4), point(0, 1, 2e-4)};
  ReduceScratch scratch;
  std::vector<ContactPoint> out;
  reduceManifold(pts, Vector3D::UnitZ(), 1, out, scratch);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].depth, 3e-4);
}

TEST(ClusterAndReduce, SeparatesNormalsMoreThanTenDegreesApart) {
  std::vector<ContactPoint> pts;
  const Vector3D tilted = Vector3D(std::sin(0.1), 0, std::cos(0.1));  // 5.7 degrees: same cluster
  pts.reserve(12);
  for (int i = 0; i < 6; ++i) {
    pts.push_back(point(i * 0.01, (i % 2) * 0.01, 1e-4, i % 2 ? tilted : Vector3D::UnitZ()));
  }
  for (int i = 0; i < 6; ++i) pts.push_back(point(0.5, i * 0.01, 1e-4, Vector3D::UnitX()));
  ReduceScratch scratch;
  std::vector<ContactPoint> out;
  clusterAndReduce(pts, 4, out, scratch);
  int up = 0;
  int side = 0;
  for (const ContactPoint& p : out) (p.normal.x() > 0.9 ? side : up) += 1;
  EXPECT_EQ(up, 4);
  EXPECT_EQ(side, 2);  // a line of points along the normal's cluster plane keeps its two ends
}

}  // namespace
}  // namespace rwsim::contacts::detail
