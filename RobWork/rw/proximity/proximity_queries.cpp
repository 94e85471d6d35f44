#include "rw/proximity/proximity_queries.hpp"

#include <utility>

#include "rw/proximity/bvh_queries.hpp"
#include "rw/proximity/gjk.hpp"

namespace rw::proximity {

using rw::math::Transform3D;
using rw::math::Vector3D;
using Kind = ProximityModel::Kind;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Two half-spaces n.x <= n.o: they overlap unless their normals are opposite and they face
// away from each other.
DistanceResult planePlane(const Transform3D& X_W_a, const Transform3D& X_W_b) {
  const Vector3D na = X_W_a.linear().col(2);
  const Vector3D nb = X_W_b.linear().col(2);
  const Vector3D oa = X_W_a.translation();
  const double da = na.dot(oa);
  const double db = nb.dot(X_W_b.translation());
  const double cosine = na.dot(nb);
  if (cosine <= -1.0 + 1e-12) {
    const double gap = -db - da;
    if (gap > 0.0) return DistanceResult{gap, oa, oa + gap * na};
    return DistanceResult{0.0, oa, oa};
  }
  Vector3D p = oa;
  const double excess = nb.dot(p) - db;
  if (excess > 0.0) {
    const Vector3D u = nb - cosine * na;
    p -= u.squaredNorm() > 1e-12 ? Vector3D(u * (excess / u.squaredNorm())) : Vector3D(nb * excess);
  }
  return DistanceResult{0.0, p, p};
}

// Plane `plane` against any non-plane `other`; pointA on the plane, pointB on the other.
// Stops at the first point found within `stopAtOrBelow` of the half-space.
DistanceResult planeOther(const Transform3D& X_W_plane, const ProximityModel& other,
                          const Transform3D& X_W_other, double stopAtOrBelow) {
  const Transform3D X_po = X_W_plane.inverse() * X_W_other;
  LowestPoint low;
  if (other.kind() == Kind::kConvex) {
    const ConvexShape shape = other.convexShape();
    const Vector3D down = X_po.linear().transpose() * Vector3D(0.0, 0.0, -1.0);
    low.point = X_po * shape.support(down) - Vector3D(0.0, 0.0, shape.margin());
    low.height = low.point.z();
  } else {
    low = bvhLowestPoint(*other.bvh(), X_po, stopAtOrBelow);
  }
  if (low.height <= 0.0) {
    const Vector3D p = X_W_plane * low.point;
    return DistanceResult{0.0, p, p};
  }
  const Vector3D onPlane(low.point.x(), low.point.y(), 0.0);
  return DistanceResult{low.height, X_W_plane * onPlane, X_W_plane * low.point};
}

DistanceResult swapped(DistanceResult r) {
  std::swap(r.pointA, r.pointB);
  return r;
}

DistanceResult planeDistance(const ProximityModel& a, const Transform3D& X_W_a,
                             const ProximityModel& b, const Transform3D& X_W_b,
                             double stopAtOrBelow) {
  if (a.kind() == Kind::kPlane && b.kind() == Kind::kPlane) return planePlane(X_W_a, X_W_b);
  if (a.kind() == Kind::kPlane) return planeOther(X_W_a, b, X_W_b, stopAtOrBelow);
  return swapped(planeOther(X_W_b, a, X_W_a, stopAtOrBelow));
}

DistanceResult toWorld(DistanceResult r, const Transform3D& X_W_a) {
  if (r.distance < kInfinity) {
    r.pointA = X_W_a * r.pointA;
    r.pointB = X_W_a * r.pointB;
  }
  return r;
}

// Distance of a convex primitive `b` to the triangles of `a`, in a's frame.
DistanceResult meshPrimitive(const ProximityModel& a, const ProximityModel& b,
                             const Transform3D& X_ab, double upperBound) {
  return bvhConvexDistance(*a.bvh(), b.convexShape(), b.convexBox(), X_ab, upperBound);
}

}  // namespace

bool collides(const ProximityModel& a, const Transform3D& X_W_a, const ProximityModel& b,
              const Transform3D& X_W_b) {
  if (a.kind() == Kind::kPlane || b.kind() == Kind::kPlane) {
    return planeDistance(a, X_W_a, b, X_W_b, kContactTolerance).distance <= kContactTolerance;
  }
  const Transform3D X_ab = X_W_a.inverse() * X_W_b;
  if (a.kind() == Kind::kConvex && b.kind() == Kind::kConvex) {
    const GjkResult r =
        gjkDistance(a.convexShape(), b.convexShape(), X_ab, kContactTolerance, kContactTolerance);
    return !r.exceeded && r.distance <= kContactTolerance;
  }
  if (b.isPrimitive()) {
    return bvhConvexCollides(*a.bvh(), b.convexShape(), b.convexBox(), X_ab, kContactTolerance);
  }
  if (a.isPrimitive()) {
    return bvhConvexCollides(*b.bvh(), a.convexShape(), a.convexBox(), X_ab.inverse(),
                             kContactTolerance);
  }
  return bvhCollides(*a.bvh(), *b.bvh(), X_ab, kContactTolerance);
}

DistanceResult distance(const ProximityModel& a, const Transform3D& X_W_a, const ProximityModel& b,
                        const Transform3D& X_W_b, double upperBound) {
  if (a.kind() == Kind::kPlane || b.kind() == Kind::kPlane) {
    DistanceResult r = planeDistance(a, X_W_a, b, X_W_b, 0.0);
    if (r.distance >= upperBound) r.distance = kInfinity;
    return r;
  }
  const Transform3D X_ab = X_W_a.inverse() * X_W_b;
  if (a.kind() == Kind::kConvex && b.kind() == Kind::kConvex) {
    const GjkResult r = gjkDistance(a.convexShape(), b.convexShape(), X_ab, 0.0, upperBound);
    if (r.exceeded || r.distance >= upperBound) return DistanceResult{};
    return toWorld(DistanceResult{r.distance, r.pointA, r.pointB}, X_W_a);
  }
  if (b.isPrimitive()) return toWorld(meshPrimitive(a, b, X_ab, upperBound), X_W_a);
  if (a.isPrimitive()) {
    return swapped(toWorld(meshPrimitive(b, a, X_ab.inverse(), upperBound), X_W_b));
  }
  return toWorld(bvhDistance(*a.bvh(), *b.bvh(), X_ab, upperBound), X_W_a);
}

bool collides(const rw::geometry::Geometry& a, const Transform3D& X_W_a,
              const rw::geometry::Geometry& b, const Transform3D& X_W_b) {
  return collides(ProximityModel(a), X_W_a, ProximityModel(b), X_W_b);
}

DistanceResult distance(const rw::geometry::Geometry& a, const Transform3D& X_W_a,
                        const rw::geometry::Geometry& b, const Transform3D& X_W_b) {
  return distance(ProximityModel(a), X_W_a, ProximityModel(b), X_W_b);
}

}  // namespace rw::proximity
