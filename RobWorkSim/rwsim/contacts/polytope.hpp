#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"
#include "rw/proximity/bvh.hpp"

/// Convex polytopes prepared for contact generation (internal to rwsim_contacts).
namespace rwsim::contacts::detail {

/// A face of a convex polytope: a plane and the loop of its vertices.
struct Face {
  /// Outward unit normal.
  rw::math::Vector3D normal = rw::math::Vector3D::UnitZ();
  /// Plane offset: normal . x = offset on the face, smaller inside.
  double offset = 0.0;
  /// First entry of the face's loop in PolytopeView::faceVertices.
  std::int32_t first = 0;
  /// Number of loop vertices (counter-clockwise seen from outside).
  std::int32_t count = 0;
  /// Bounding box of the loop.
  rw::geometry::Aabb box;
};

/// An edge with its arc on the Gauss map: the edge supports the polytope in every direction on
/// the short great arc from `na` to `nb` (the normals of the faces meeting at the edge).
struct Edge {
  /// First end (vertex index).
  std::int32_t v0 = 0;
  /// Second end.
  std::int32_t v1 = 0;
  /// Start of the arc.
  rw::math::Vector3D na = rw::math::Vector3D::UnitZ();
  /// End of the arc.
  rw::math::Vector3D nb = rw::math::Vector3D::UnitZ();
  /// Bounding box of the edge.
  rw::geometry::Aabb box;
};

/// X * p for a point, without the homogeneous 4x4 product Eigen uses for isometries.
inline rw::math::Vector3D transformPoint(const rw::math::Transform3D& X,
                                         const rw::math::Vector3D& p) {
  return X.linear() * p + X.translation();
}

/// A box given by centre, axes and half extents, for culling features against another shape.
using Obb = rw::proximity::Obb;

/// A query box (another shape's box placed in this shape's frame, grown by a distance) with
/// what the overlap tests need precomputed.
class QueryBox {
 public:
  /// `box` grown by `grow` in every direction.
  QueryBox(const Obb& box, double grow);
  /// Conservative box-box test on the six face axes: false only when certainly disjoint.
  bool overlaps(const rw::math::Vector3D& min, const rw::math::Vector3D& max) const;
  /// True unless the plane n . x = offset is certainly farther than the growth from the box.
  bool nearPlane(const rw::math::Vector3D& n, double offset) const;

 private:
  Obb box_;
  Eigen::Matrix3d absAxes_;
  rw::math::Vector3D extent_;  // grown half extents along this frame's axes
  rw::math::Vector3D grown_;   // grown half extents along the box's axes
  double grow_;
};

/// A binary tree of axis-aligned boxes over features (faces or edges), to find the features of
/// a large polytope near another shape without visiting all of them.
class FeatureTree {
 public:
  /// Builds the tree over the boxes; empty input gives an empty tree.
  void build(std::span<const rw::geometry::Aabb> boxes);
  /// True when built over nothing.
  bool empty() const { return nodes_.empty(); }
  /// Appends to `out` the items in leaves whose boxes overlap `query`.
  void query(const QueryBox& query, std::vector<std::int32_t>& out) const;

 private:
  struct Node {
    rw::geometry::Aabb box;
    std::int32_t second = -1;  // internal: second child (first child is the next node)
    std::int32_t first = 0;    // leaf: first entry of order_
    std::int32_t count = 0;    // leaf: number of entries; 0 for internal nodes
  };
  std::int32_t buildNode(std::span<const rw::geometry::Aabb> boxes, std::int32_t begin,
                         std::int32_t end);

  std::vector<Node> nodes_;
  std::vector<std::int32_t> order_;
};

/// Non-owning view of a convex polytope (or a flat convex polygon with both sides as faces).
/// All data is in the polytope's own frame.
struct PolytopeView {
  /// Vertices.
  std::span<const rw::math::Vector3D> vertices;
  /// Faces.
  std::span<const Face> faces;
  /// Concatenated vertex loops of the faces.
  std::span<const std::int32_t> faceVertices;
  /// Edges with their Gauss-map arcs (a flat polygon has two arcs per edge).
  std::span<const Edge> edges;
  /// Vertex graph for hill climbing (empty: supports are found by scanning all vertices).
  std::span<const std::int32_t> adjacencyOffsets;
  /// Concatenated neighbour lists.
  std::span<const std::int32_t> adjacency;
  /// Faces around each vertex (offsets, vertices().size() + 1 entries, or empty).
  std::span<const std::int32_t> vertexFaceOffsets;
  /// Concatenated face lists.
  std::span<const std::int32_t> vertexFaces;
  /// Farthest vertices along +x, -x, +y, -y, +z, -z (valid when adjacency is given).
  std::span<const std::int32_t> anchors;
  /// Tree over the face boxes, or null (then all faces are scanned).
  const FeatureTree* faceTree = nullptr;
  /// Tree over the edge boxes, or null.
  const FeatureTree* edgeTree = nullptr;
  /// Bounding box.
  rw::geometry::Aabb bounds;
};

/// Index of a vertex of `p` farthest along `d`; `hint` (a vertex index or -1) is where a hill
/// climb starts and receives the result.
std::int32_t supportVertex(const PolytopeView& p, const rw::math::Vector3D& d, std::int32_t& hint);

/// Index of the face of `p` whose normal is closest to `d` (unit), searched among the faces
/// around vertex `nearVertex` when the polytope has vertex-face lists.
std::int32_t mostAlignedFace(const PolytopeView& p, const rw::math::Vector3D& d,
                             std::int32_t nearVertex);

/// A convex polytope owning its data; built once, then read through view().
class Polytope {
 public:
  /// The convex polytope bounded by a closed, convex, outward-wound triangle mesh: vertices
  /// welded, degenerate triangles dropped, coplanar neighbours merged into polygon faces.
  /// Returns nullopt when the mesh is not a closed convex surface (open, non-manifold) or
  /// has no area.
  static std::optional<Polytope> fromConvexMesh(const rw::geometry::TriMesh& mesh);
  /// A flat convex polygon (vertices counter-clockwise about `normal`) with both sides as
  /// faces (0 front, 1 back) and each edge as a two-vertex face. Precondition: at least 3
  /// vertices, coplanar, convex.
  static Polytope flatPolygon(std::vector<rw::math::Vector3D> loop,
                              const rw::math::Vector3D& normal);

  /// Read-only view (valid while the polytope lives and is not moved).
  PolytopeView view() const;
  /// Vertices.
  const std::vector<rw::math::Vector3D>& vertices() const { return vertices_; }
  /// Faces.
  const std::vector<Face>& faces() const { return faces_; }
  /// Edges (a flat polygon has two arcs per edge, so twice its edge count).
  const std::vector<Edge>& edges() const { return edges_; }
  /// Bounding box.
  const rw::geometry::Aabb& bounds() const { return bounds_; }
  /// A small oriented box around the vertices.
  const Obb& obb() const { return obb_; }
  /// Vertex graph (offsets into adjacency(), vertices().size() + 1 entries).
  const std::vector<std::int32_t>& adjacencyOffsets() const { return adjacencyOffsets_; }
  /// Concatenated neighbour lists.
  const std::vector<std::int32_t>& adjacency() const { return adjacency_; }
  /// Farthest vertices along +x, -x, +y, -y, +z, -z.
  const std::array<std::int32_t, 6>& anchors() const { return anchors_; }
  /// True for a flat polygon.
  bool flat() const { return flat_; }

 private:
  void finish();
  void buildGraph();

  std::vector<rw::math::Vector3D> vertices_;
  std::vector<Face> faces_;
  std::vector<std::int32_t> faceVertices_;
  std::vector<Edge> edges_;
  std::vector<std::int32_t> adjacencyOffsets_;
  std::vector<std::int32_t> adjacency_;
  std::vector<std::int32_t> vertexFaceOffsets_;
  std::vector<std::int32_t> vertexFaces_;
  std::array<std::int32_t, 6> anchors_{};
  FeatureTree faceTree_;
  FeatureTree edgeTree_;
  rw::geometry::Aabb bounds_;
  Obb obb_;
  bool flat_ = false;
};

/// A triangle as a flat convex piece, built on the stack: front face (face 0), back face, and
/// each edge as a two-vertex face whose normal is the edge's outward direction in the plane
/// (the axes on which thin pieces meet edge-on); two Gauss arcs per edge (front normal to
/// outward direction to back normal).
class TrianglePiece {
 public:
  /// Builds the piece; `normal` is the triangle's unit front normal.
  TrianglePiece(const rw::proximity::Triangle& t, const rw::math::Vector3D& normal);
  /// Read-only view (valid while the piece lives).
  PolytopeView view() const;

 private:
  std::array<rw::math::Vector3D, 3> vertices_;
  std::array<Face, 5> faces_;
  std::array<std::int32_t, 12> loops_{0, 1, 2, 0, 2, 1, 0, 1, 1, 2, 2, 0};
  std::array<Edge, 6> edges_;
  rw::geometry::Aabb bounds_;
};

}  // namespace rwsim::contacts::detail
