#pragma once

#include <cstdint>
#include <span>

#include "rw/math/types.hpp"

namespace rw::proximity {

/// A convex shape given by its support mapping in its own frame: a point (a sphere is a point
/// with a margin), a box, a cylinder, a cone, a frustum or the convex hull of points. The shape is
/// the core grown by `margin()` in every direction. Hull points are borrowed, not owned.
class ConvexShape {
 public:
  /// Kinds of core.
  enum class Kind { kPoint, kBox, kCylinder, kCone, kFrustum, kHull };

  /// A sphere of `radius` about the origin (a point core with that margin).
  static ConvexShape sphere(double radius);
  /// A box with the given half edge lengths, centred.
  static ConvexShape box(const rw::math::Vector3D& halfExtents);
  /// A cylinder along z from -halfHeight to +halfHeight.
  static ConvexShape cylinder(double radius, double halfHeight);
  /// A cone along z: base disk of `radius` at +halfHeight, apex at -halfHeight.
  static ConvexShape cone(double radius, double halfHeight);
  /// A frustum along z: disk of `radiusBottom` at -halfHeight, of `radiusTop` at +halfHeight.
  static ConvexShape frustum(double radiusBottom, double radiusTop, double halfHeight);
  /// The convex hull of `points`. Precondition: not empty; the points outlive the shape.
  static ConvexShape hull(std::span<const rw::math::Vector3D> points);
  /// The vertex graph of a closed convex triangulated surface, for climbing to the support.
  struct HullGraph {
    /// Neighbours of point i are neighbours[offsets[i]] .. neighbours[offsets[i + 1] - 1].
    std::span<const std::int32_t> offsets;
    /// Concatenated neighbour lists.
    std::span<const std::int32_t> neighbours;
    /// Farthest points along +x, -x, +y, -y, +z, -z: where searches without a hint start.
    std::span<const std::int32_t> anchors;
  };
  /// The convex hull of `points` with their surface graph. Precondition: offsets has
  /// points.size() + 1 entries, anchors 6; all spans outlive the shape.
  static ConvexShape hull(std::span<const rw::math::Vector3D> points, const HullGraph& graph);

  /// The kind of core.
  Kind kind() const { return kind_; }
  /// Radius by which the core is grown (spheres), else 0.
  double margin() const { return margin_; }
  /// A point of the core farthest along `direction` (any core point when it is zero).
  rw::math::Vector3D support(const rw::math::Vector3D& direction) const {
    std::int32_t hint = -1;
    return support(direction, hint);
  }
  /// Same, starting a hull's search at point `hint` (if >= 0) and leaving the found point's
  /// index there (queries with slowly turning directions pass the same hint along).
  rw::math::Vector3D support(const rw::math::Vector3D& direction, std::int32_t& hint) const;
  /// Some point of the core (where a search may start).
  rw::math::Vector3D corePoint() const;

 private:
  ConvexShape(Kind kind, const rw::math::Vector3D& dims, double margin,
              std::span<const rw::math::Vector3D> points)
      : kind_(kind), dims_(dims), margin_(margin), points_(points) {}
  rw::math::Vector3D hullSupport(const rw::math::Vector3D& direction, std::int32_t& hint) const;

  Kind kind_;
  rw::math::Vector3D dims_;  // box: half extents; cylinder, cone: (radius, unused, half height);
                             // frustum: (bottom radius, top radius, half height)
  double margin_;
  std::span<const rw::math::Vector3D> points_;
  HullGraph graph_;
};

}  // namespace rw::proximity
