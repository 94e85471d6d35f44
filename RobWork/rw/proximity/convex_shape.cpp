#include "rw/proximity/convex_shape.hpp"

#include <cmath>

namespace rw::proximity {

using rw::math::Vector3D;

ConvexShape ConvexShape::sphere(double radius) {
  return ConvexShape(Kind::kPoint, Vector3D::Zero(), radius, {});
}

ConvexShape ConvexShape::box(const Vector3D& halfExtents) {
  return ConvexShape(Kind::kBox, halfExtents, 0.0, {});
}

ConvexShape ConvexShape::cylinder(double radius, double halfHeight) {
  return ConvexShape(Kind::kCylinder, Vector3D(radius, 0.0, halfHeight), 0.0, {});
}

ConvexShape ConvexShape::cone(double radius, double halfHeight) {
  return ConvexShape(Kind::kCone, Vector3D(radius, 0.0, halfHeight), 0.0, {});
}

ConvexShape ConvexShape::frustum(double radiusBottom, double radiusTop, double halfHeight) {
  return ConvexShape(Kind::kFrustum, Vector3D(radiusBottom, radiusTop, halfHeight), 0.0, {});
}

ConvexShape ConvexShape::hull(std::span<const Vector3D> points) {
  return ConvexShape(Kind::kHull, Vector3D::Zero(), 0.0, points);
}

ConvexShape ConvexShape::hull(std::span<const Vector3D> points, const HullGraph& graph) {
  ConvexShape shape(Kind::kHull, Vector3D::Zero(), 0.0, points);
  shape.graph_ = graph;
  return shape;
}

namespace {

// Point of a disk of `radius` (at height z, normal z) farthest along d, whose length in the
// disk's plane is `planar`.
Vector3D diskSupport(const Vector3D& d, double planar, double radius, double z) {
  if (planar <= 0.0) return Vector3D(0.0, 0.0, z);
  const double s = radius / planar;
  return Vector3D(d.x() * s, d.y() * s, z);
}

}  // namespace

// On a closed convex surface a vertex no neighbour of which lies farther along d is a farthest
// vertex: the edges to the neighbours span the surface's tangent cone there.
Vector3D ConvexShape::hullSupport(const Vector3D& d, std::int32_t& hint) const {
  if (graph_.offsets.empty()) {
    std::size_t best = 0;
    double bestDot = points_[0].dot(d);
    for (std::size_t i = 1; i < points_.size(); ++i) {
      const double dot = points_[i].dot(d);
      if (dot > bestDot) {
        bestDot = dot;
        best = i;
      }
    }
    return points_[best];
  }
  std::int32_t current = hint;
  if (current < 0 || static_cast<std::size_t>(current) >= points_.size()) {
    int axis = 0;
    d.cwiseAbs().maxCoeff(&axis);
    current = graph_.anchors[static_cast<std::size_t>(2 * axis + (d[axis] < 0.0 ? 1 : 0))];
  }
  double currentDot = points_[static_cast<std::size_t>(current)].dot(d);
  for (;;) {
    std::int32_t next = current;
    double nextDot = currentDot;
    const auto node = static_cast<std::size_t>(current);
    const auto begin = static_cast<std::size_t>(graph_.offsets[node]);
    const auto end = static_cast<std::size_t>(graph_.offsets[node + 1]);
    for (std::size_t k = begin; k < end; ++k) {
      const std::int32_t candidate = graph_.neighbours[k];
      const double dot = points_[static_cast<std::size_t>(candidate)].dot(d);
      if (dot > nextDot) {
        nextDot = dot;
        next = candidate;
      }
    }
    if (next == current) break;
    current = next;
    currentDot = nextDot;
  }
  hint = current;
  return points_[static_cast<std::size_t>(current)];
}

Vector3D ConvexShape::support(const Vector3D& d, std::int32_t& hint) const {
  switch (kind_) {
    case Kind::kPoint:
      return Vector3D::Zero();
    case Kind::kBox:
      return Vector3D(d.x() < 0.0 ? -dims_.x() : dims_.x(), d.y() < 0.0 ? -dims_.y() : dims_.y(),
                      d.z() < 0.0 ? -dims_.z() : dims_.z());
    case Kind::kCylinder:
      return diskSupport(d, std::hypot(d.x(), d.y()), dims_.x(),
                         d.z() < 0.0 ? -dims_.z() : dims_.z());
    case Kind::kCone: {
      const Vector3D rim = diskSupport(d, std::hypot(d.x(), d.y()), dims_.x(), dims_.z());
      const Vector3D apex(0.0, 0.0, -dims_.z());
      return rim.dot(d) >= apex.dot(d) ? rim : apex;
    }
    case Kind::kFrustum: {
      const double planar = std::hypot(d.x(), d.y());
      const Vector3D top = diskSupport(d, planar, dims_.y(), dims_.z());
      const Vector3D bottom = diskSupport(d, planar, dims_.x(), -dims_.z());
      return top.dot(d) >= bottom.dot(d) ? top : bottom;
    }
    case Kind::kHull:
      return hullSupport(d, hint);
  }
  return Vector3D::Zero();
}

Vector3D ConvexShape::corePoint() const {
  if (kind_ == Kind::kHull) return points_[0];
  return Vector3D::Zero();
}

}  // namespace rw::proximity
