// Structure of the triangle hierarchy: complete, containing, shallow and deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "proximity_test_util.hpp"
#include "rw/proximity/bvh.hpp"

namespace rw::proximity {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

bool insideBox(const Obb& box, const Vector3D& p) {
  const Vector3D local = box.axes.transpose() * (p - box.center);
  return (local.cwiseAbs() - box.halfExtents).maxCoeff() <= 1e-12;
}

// Checks node `index` and returns the number of triangles below it.
int checkNode(const Bvh& bvh, std::int32_t index) {
  const Bvh::Node& node = bvh.nodes()[static_cast<std::size_t>(index)];
  EXPECT_NEAR(node.box.axes.determinant(), 1.0, 1e-9);
  if (node.isLeaf()) {
    EXPECT_LE(node.count, Bvh::kMaxLeafTriangles);
    for (std::int32_t t = node.first; t < node.first + node.count; ++t) {
      for (const Vector3D& v : bvh.triangles()[static_cast<std::size_t>(t)].v) {
        EXPECT_TRUE(insideBox(node.box, v)) << "node " << index;
      }
    }
    return node.count;
  }
  const auto checkChild = [&](std::int32_t child) {
    const Bvh::Node& c = bvh.nodes()[static_cast<std::size_t>(child)];
    if (c.isLeaf()) {
      for (std::int32_t t = c.first; t < c.first + c.count; ++t) {
        for (const Vector3D& v : bvh.triangles()[static_cast<std::size_t>(t)].v) {
          EXPECT_TRUE(insideBox(node.box, v)) << "node " << index;
        }
      }
    }
    return checkNode(bvh, child);
  };
  return checkChild(index + 1) + checkChild(node.second);
}

TEST(Bvh, EveryTriangleOnceInsideItsBoxes) {
  const auto sphere = rw::geometry::Geometry::sphere(0.3);
  const Bvh bvh(sphere->triangles());
  const auto triangles = static_cast<int>(sphere->triangles().triangles.size());
  EXPECT_EQ(static_cast<int>(bvh.triangles().size()), triangles);
  EXPECT_EQ(checkNode(bvh, 0), triangles);
  EXPECT_LE(bvh.nodes().size(), static_cast<std::size_t>(2 * triangles - 1));
  // Balanced enough: log2(triangles) levels plus a small margin.
  EXPECT_LE(bvh.depth(), static_cast<int>(std::ceil(std::log2(triangles))) + 6);
}

TEST(Bvh, SameMeshSameTree) {
  const auto l = test::lShape();
  const Bvh a(l->triangles());
  const Bvh b(l->triangles());
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  for (std::size_t i = 0; i < a.nodes().size(); ++i) {
    EXPECT_EQ(a.nodes()[i].second, b.nodes()[i].second);
    EXPECT_EQ(a.nodes()[i].first, b.nodes()[i].first);
    EXPECT_EQ(a.nodes()[i].count, b.nodes()[i].count);
    EXPECT_EQ(a.nodes()[i].box.center, b.nodes()[i].box.center);
  }
}

TEST(Bvh, RejectsEmptyAndBrokenMeshes) {
  rw::geometry::TriMesh empty;
  EXPECT_THROW(Bvh{empty}, std::invalid_argument);
  rw::geometry::TriMesh broken;
  broken.vertices = {Vector3D::Zero(), Vector3D::UnitX()};
  broken.triangles = {{0, 1, 2}};
  EXPECT_THROW(Bvh{broken}, std::invalid_argument);
}

}  // namespace
}  // namespace rw::proximity
