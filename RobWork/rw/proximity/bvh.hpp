#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"

namespace rw::proximity {

/// An oriented bounding box: centre, unit axes (columns) and half extents along them.
struct Obb {
  /// Centre.
  rw::math::Vector3D center = rw::math::Vector3D::Zero();
  /// Orthonormal, right-handed axes as columns.
  rw::math::Rotation3D axes = rw::math::Rotation3D::Identity();
  /// Half extents along the axes.
  rw::math::Vector3D halfExtents = rw::math::Vector3D::Zero();
};

/// A triangle with its vertices stored inline.
struct Triangle {
  /// Vertices in counter-clockwise order seen from outside.
  std::array<rw::math::Vector3D, 3> v;
};

/// A small box around `points`: the smaller of the box along their principal axes and the
/// axis-aligned box. Precondition: `points` is not empty.
Obb fitObb(std::span<const rw::math::Vector3D> points);

/// True when boxes `a` and `b` (b given in a's frame by R_ab, t_ab) are certainly farther
/// apart than `tolerance` (separating-axis test over the 15 axes).
bool obbDisjoint(const Obb& a, const Obb& b, const rw::math::Rotation3D& R_ab,
                 const rw::math::Vector3D& t_ab, double tolerance);

/// A lower bound on the distance between boxes `a` and `b` (b in a's frame by R_ab, t_ab): the
/// largest gap along the 15 separating axes and the line through the centres, 0 when none
/// separates.
double obbDistanceLowerBound(const Obb& a, const Obb& b, const rw::math::Rotation3D& R_ab,
                             const rw::math::Vector3D& t_ab);

/// A bounding-volume hierarchy of oriented boxes over the triangles of a mesh, built once,
/// top-down and deterministically; queried concurrently without locks.
class Bvh {
 public:
  /// Largest number of triangles in a leaf.
  static constexpr int kMaxLeafTriangles = 2;

  /// One node. Internal nodes have their first child at index + 1 and the second at `second`;
  /// leaves hold triangles [first, first + count).
  struct Node {
    /// Box around all triangles below the node.
    Obb box;
    /// Index of the second child (internal nodes).
    std::int32_t second = -1;
    /// First triangle (leaves).
    std::int32_t first = 0;
    /// Number of triangles; 0 for internal nodes.
    std::int32_t count = 0;
    /// True for leaves.
    bool isLeaf() const { return count > 0; }
  };

  /// Builds the hierarchy. @throws std::invalid_argument if the mesh has no triangles or an
  /// index is out of range.
  explicit Bvh(const rw::geometry::TriMesh& mesh);

  /// Nodes; the root is node 0.
  const std::vector<Node>& nodes() const { return nodes_; }
  /// Triangles in leaf order.
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// Number of node levels (1 for a single leaf).
  int depth() const { return depth_; }

 private:
  std::vector<Node> nodes_;
  std::vector<Triangle> triangles_;
  int depth_ = 0;
};

}  // namespace rw::proximity
