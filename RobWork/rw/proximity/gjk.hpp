#pragma once

#include <limits>

#include "rw/math/types.hpp"
#include "rw/proximity/convex_shape.hpp"

namespace rw::proximity {

/// Result of a GJK query; points are in the frame of the first shape.
struct GjkResult {
  /// Distance between the shapes, 0 when they overlap.
  double distance = 0.0;
  /// Closest point on the first shape (a common point when overlapping).
  rw::math::Vector3D pointA = rw::math::Vector3D::Zero();
  /// Closest point on the second shape (equal to pointA when overlapping).
  rw::math::Vector3D pointB = rw::math::Vector3D::Zero();
  /// True when the query stopped because the distance exceeds `stopAbove`: then `distance` is
  /// only a lower bound above it and the points are meaningless.
  bool exceeded = false;
};

/// Distance between two convex shapes by the Gilbert-Johnson-Keerthi algorithm; `b` is placed
/// in `a`'s frame by X_ab. The search stops early once the distance is known to exceed
/// `stopAbove` (see GjkResult::exceeded) or to be at most `stopBelow` (then the points are real
/// points of the shapes whose distance is at most `stopBelow`, not necessarily the closest).
/// With the defaults the result is exact up to a relative error of about 1e-10.
GjkResult gjkDistance(const ConvexShape& a, const ConvexShape& b, const rw::math::Transform3D& X_ab,
                      double stopBelow = 0.0,
                      double stopAbove = std::numeric_limits<double>::infinity());

}  // namespace rw::proximity
