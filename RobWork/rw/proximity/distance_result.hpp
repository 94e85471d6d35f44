#pragma once

#include <limits>

#include "rw/math/types.hpp"

namespace rw::proximity {

/// Two shapes closer than this (metres) count as touching, hence colliding.
inline constexpr double kContactTolerance = 1e-9;

/// Result of a distance query: the distance and a pair of closest points. When the shapes
/// overlap, the distance is 0 and both points are the same point common to both shapes.
struct DistanceResult {
  /// Distance in metres (+infinity when the query was cut off by an upper bound).
  double distance = std::numeric_limits<double>::infinity();
  /// Closest point on the first shape.
  rw::math::Vector3D pointA = rw::math::Vector3D::Zero();
  /// Closest point on the second shape.
  rw::math::Vector3D pointB = rw::math::Vector3D::Zero();
};

}  // namespace rw::proximity
