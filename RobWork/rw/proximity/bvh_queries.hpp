#pragma once

#include "rw/math/types.hpp"
#include "rw/proximity/bvh.hpp"
#include "rw/proximity/convex_shape.hpp"
#include "rw/proximity/distance_result.hpp"

/// Traversals of bounding-volume hierarchies. The second shape is placed in the first one's frame
/// by X_ab and results are in the first one's frame. No allocation unless a traversal goes
/// deeper than about 100 levels.
namespace rw::proximity {

/// True when some triangle of `a` and some triangle of `b` are within `tolerance`.
bool bvhCollides(const Bvh& a, const Bvh& b, const rw::math::Transform3D& X_ab, double tolerance);

/// Distance between the triangle sets; when it is at least `upperBound`, distance = +infinity.
DistanceResult bvhDistance(const Bvh& a, const Bvh& b, const rw::math::Transform3D& X_ab,
                           double upperBound);

/// True when some triangle of `a` is within `tolerance` of convex `b` (inside box `boxB`).
bool bvhConvexCollides(const Bvh& a, const ConvexShape& b, const Obb& boxB,
                       const rw::math::Transform3D& X_ab, double tolerance);

/// Distance between the triangles of `a` and convex `b` (inside box `boxB`); +infinity when at
/// least `upperBound`.
DistanceResult bvhConvexDistance(const Bvh& a, const ConvexShape& b, const Obb& boxB,
                                 const rw::math::Transform3D& X_ab, double upperBound);

/// The lowest vertex of a mesh: its height (z) and position in the frame P.
struct LowestPoint {
  /// Height above z = 0 of frame P (negative below).
  double height = 0.0;
  /// The vertex in frame P.
  rw::math::Vector3D point = rw::math::Vector3D::Zero();
};

/// The lowest vertex of mesh `a` placed in frame P by X_pa; the search may stop at the first
/// vertex found at or below `stopAtOrBelow`.
LowestPoint bvhLowestPoint(const Bvh& a, const rw::math::Transform3D& X_pa, double stopAtOrBelow);

}  // namespace rw::proximity
