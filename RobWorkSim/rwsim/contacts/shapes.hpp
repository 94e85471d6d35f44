#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "rw/proximity/bvh.hpp"
#include "rw/proximity/convex_shape.hpp"
#include "rwsim/contacts/contact_detector.hpp"
#include "rwsim/contacts/polytope.hpp"

/// The prepared shapes behind ContactShape (internal to rwsim_contacts).
namespace rwsim::contacts::detail {

/// A sphere about the origin.
class SphereShape final : public ContactShape {
 public:
  /// A sphere of `radius`.
  explicit SphereShape(double radius) : ContactShape(Kind::kSphere), radius_(radius) {}
  /// Radius.
  double radius() const { return radius_; }
  /// Bounding box.
  rw::geometry::Aabb localBounds() const override;

 private:
  double radius_;
};

/// The half-space z <= 0 of its frame.
class HalfSpaceShape final : public ContactShape {
 public:
  HalfSpaceShape() : ContactShape(Kind::kHalfSpace) {}
  /// Infinite in x and y and below z = 0.
  rw::geometry::Aabb localBounds() const override;
};

/// A convex core and the height of its centre on the z axis.
struct RoundCore {
  /// The core, centred on its own origin.
  rw::proximity::ConvexShape shape;
  /// Height of its centre.
  double offset = 0.0;
  /// Largest distance of a point of the frustum from the core (m): the rounding at a cap, more
  /// at a rim or apex sharper than a right angle (rounding / sin(half its angle)).
  double reach = 0.0;
};

/// A solid frustum about the z axis from z = -h to z = +h (a cylinder when the radii are equal,
/// a cone when one is zero): exact support and features for contacts, and two approximations:
/// a core (the frustum shrunk by `rounding()`, so that core + rounding is the frustum with its
/// rims rounded) for GJK, and its tessellation as a polytope for the fallbacks (non-convex
/// meshes, overlaps deeper than the rounding).
class RoundShape final : public ContactShape {
 public:
  /// A frustum of radii `bottom` (z = -halfHeight) and `top` (z = +halfHeight); `tessellation`
  /// is its polytope. Precondition: radii >= 0, not both 0; halfHeight > 0.
  RoundShape(double bottom, double top, double halfHeight, Polytope tessellation);
  /// Radius at z = -halfHeight().
  double bottomRadius() const { return bottom_; }
  /// Radius at z = +halfHeight().
  double topRadius() const { return top_; }
  /// Half the height.
  double halfHeight() const { return halfHeight_; }
  /// The point of the frustum farthest along `d` (the top or bottom rim, or a cap's centre).
  rw::math::Vector3D support(const rw::math::Vector3D& d) const;
  /// The core (see the class comment), centred at (0, 0, coreOffset()).
  const rw::proximity::ConvexShape& core() const { return core_.shape; }
  /// Height of the core's centre on the z axis.
  double coreOffset() const { return core_.offset; }
  /// How far the core is grown to give the rounded frustum (m).
  double rounding() const { return rounding_; }
  /// Largest distance of a point of the frustum from its core (m; see RoundCore::reach).
  double reach() const { return core_.reach; }
  /// The tessellation.
  const Polytope& polytope() const { return polytope_; }
  /// Bounding box.
  rw::geometry::Aabb localBounds() const override;

 private:
  double bottom_;
  double top_;
  double halfHeight_;
  double rounding_;
  RoundCore core_;
  Polytope polytope_;
};

/// One or more convex polytopes (one for primitives and convex or flat meshes, one per ring
/// segment for a tube).
class PolytopeShape final : public ContactShape {
 public:
  /// Takes the pieces. Precondition: not empty.
  explicit PolytopeShape(std::vector<Polytope> pieces);
  /// The pieces.
  const std::vector<Polytope>& pieces() const { return pieces_; }
  /// Bounding box of all pieces.
  rw::geometry::Aabb localBounds() const override { return bounds_; }

 private:
  std::vector<Polytope> pieces_;
  rw::geometry::Aabb bounds_;
};

/// The outward normals a triangle of a closed mesh gives without doubt (its Gauss image
/// without the vertex regions): its own normal and the arcs across its convex edges.
struct TriangleInfo {
  /// Unit front normal (zero for a degenerate triangle, which is skipped).
  rw::math::Vector3D normal = rw::math::Vector3D::Zero();
  /// For edge (v[k], v[k+1]) of a closed mesh: the neighbour's normal if the edge is convex,
  /// else zero.
  std::array<rw::math::Vector3D, 3> neighbour{};
};

/// A triangle mesh under a bounding-volume hierarchy. A closed mesh is one-sided (contacts
/// push out of it); an open one is two-sided.
class MeshShape final : public ContactShape {
 public:
  /// Prepares `mesh`. @throws std::invalid_argument if it has no triangles.
  explicit MeshShape(const rw::geometry::TriMesh& mesh);
  /// The hierarchy (triangles in leaf order).
  const rw::proximity::Bvh& bvh() const { return bvh_; }
  /// Per-triangle data, in the hierarchy's triangle order.
  const std::vector<TriangleInfo>& info() const { return info_; }
  /// True for a closed mesh.
  bool oneSided() const { return oneSided_; }
  /// Bounding box.
  rw::geometry::Aabb localBounds() const override { return bounds_; }

 private:
  rw::proximity::Bvh bvh_;
  std::vector<TriangleInfo> info_;
  bool oneSided_ = false;
  rw::geometry::Aabb bounds_;
};

/// The flat convex polygon covered by a mesh whose vertices are all coplanar, if the mesh covers
/// exactly its convex hull (within 1e-6 of the area); nullopt otherwise.
std::optional<Polytope> flatConvexPatch(const rw::geometry::TriMesh& mesh);

/// The convex pieces of a tube: one per segment of its ring.
std::vector<Polytope> tubePieces(double inner, double outer, double height, int segments);

}  // namespace rwsim::contacts::detail
