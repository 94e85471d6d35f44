#pragma once

#include <optional>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"
#include "rw/proximity/bvh.hpp"
#include "rw/proximity/convex_shape.hpp"

namespace rw::proximity {

/// What the queries need of one Geometry, built once: the exact convex description of
/// primitives and convex meshes, a bounding-volume hierarchy over the triangles of meshes and
/// tubes, and a bounding sphere. Immutable; safe to query from many threads.
class ProximityModel {
 public:
  /// How queries treat the geometry.
  enum class Kind {
    kConvex,  ///< Box, Sphere, Cylinder, Cone or a convex mesh: exact GJK queries
    kPlane,   ///< the half-space z <= 0 of the geometry frame
    kMesh,    ///< a non-convex mesh or a Tube: queries over its triangles
  };

  /// Builds the model of `geometry` (the geometry need not outlive the model).
  /// @throws std::invalid_argument if a mesh has no triangles or a bad vertex index.
  explicit ProximityModel(const rw::geometry::Geometry& geometry);

  /// How queries treat the geometry.
  Kind kind() const { return kind_; }
  /// The type of the geometry the model was built from.
  rw::geometry::GeometryType geometryType() const { return type_; }
  /// True for convex primitives (Box, Sphere, Cylinder, Cone): no triangles are used.
  bool isPrimitive() const { return kind_ == Kind::kConvex && !bvh_; }
  /// The convex shape in the geometry frame; it borrows this model's data.
  /// Precondition: kind() == Kind::kConvex.
  ConvexShape convexShape() const;
  /// A box around convexShape(). Precondition: kind() == Kind::kConvex.
  const Obb& convexBox() const { return convexBox_; }
  /// The hierarchy over the triangles of meshes and tubes, or nullptr for primitives and planes.
  const Bvh* bvh() const { return bvh_ ? &*bvh_ : nullptr; }
  /// Centre of a sphere around the geometry, in the geometry frame.
  const rw::math::Vector3D& boundCenter() const { return boundCenter_; }
  /// Radius of that sphere (+infinity for a plane).
  double boundRadius() const { return boundRadius_; }

 private:
  void buildHullGraph(const rw::geometry::TriMesh& mesh);

  Kind kind_ = Kind::kConvex;
  rw::geometry::GeometryType type_;
  rw::math::Vector3D dims_ = rw::math::Vector3D::Zero();
  std::vector<rw::math::Vector3D> hullPoints_;
  std::vector<std::int32_t> hullOffsets_;  // vertex graph of a closed hull (CSR), may be empty
  std::vector<std::int32_t> hullNeighbours_;
  std::vector<std::int32_t> hullAnchors_;
  std::optional<Bvh> bvh_;
  Obb convexBox_;
  rw::math::Vector3D boundCenter_ = rw::math::Vector3D::Zero();
  double boundRadius_ = 0.0;
};

}  // namespace rw::proximity
