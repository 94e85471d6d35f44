#pragma once

#include "rw/math/types.hpp"
#include "rw/proximity/bvh.hpp"
#include "rw/proximity/distance_result.hpp"

namespace rw::proximity {

/// The point of triangle `t` closest to `p`.
rw::math::Vector3D closestPointOnTriangle(const rw::math::Vector3D& p, const Triangle& t);

/// Closest points `c1` on segment [p1, q1] and `c2` on [p2, q2]; returns their squared distance.
double closestPointsOnSegments(const rw::math::Vector3D& p1, const rw::math::Vector3D& q1,
                               const rw::math::Vector3D& p2, const rw::math::Vector3D& q2,
                               rw::math::Vector3D& c1, rw::math::Vector3D& c2);

/// True unless a separating axis shows the triangles farther apart than `tolerance`
/// (intersecting and touching triangles give true).
bool trianglesIntersect(const Triangle& a, const Triangle& b, double tolerance);

/// Distance and closest points of two triangles; 0 and a common point when they intersect.
DistanceResult triangleDistance(const Triangle& a, const Triangle& b);

}  // namespace rw::proximity
