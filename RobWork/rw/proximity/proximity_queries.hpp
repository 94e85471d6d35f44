#pragma once

#include <limits>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"
#include "rw/proximity/distance_result.hpp"
#include "rw/proximity/proximity_model.hpp"

/// Pairwise collision and distance queries between placed geometries. Pairs of convex shapes
/// (Box, Sphere, Cylinder, Cone, convex meshes) are exact solids (GJK); a Plane is the
/// half-space z <= 0 of its frame; non-convex meshes and Tubes are their triangle surfaces (as
/// in RobWork's PQP strategy: a shape wholly inside a closed non-convex mesh does not touch it),
/// met by primitives as exact solids. All functions are thread-safe; the model overloads
/// allocate nothing unless a hierarchy is more than about 100 levels deep.
namespace rw::proximity {

/// True when the geometries overlap or lie within kContactTolerance of each other.
bool collides(const ProximityModel& a, const rw::math::Transform3D& X_W_a, const ProximityModel& b,
              const rw::math::Transform3D& X_W_b);

/// Distance and closest points (world coordinates) of the geometries; 0 and a common point when
/// they overlap. If the distance is at least `upperBound`, the result has distance +infinity.
DistanceResult distance(const ProximityModel& a, const rw::math::Transform3D& X_W_a,
                        const ProximityModel& b, const rw::math::Transform3D& X_W_b,
                        double upperBound = std::numeric_limits<double>::infinity());

/// collides() on models built for this call (convenient, not fast).
/// @throws std::invalid_argument for a mesh without triangles.
bool collides(const rw::geometry::Geometry& a, const rw::math::Transform3D& X_W_a,
              const rw::geometry::Geometry& b, const rw::math::Transform3D& X_W_b);

/// distance() on models built for this call (convenient, not fast).
/// @throws std::invalid_argument for a mesh without triangles.
DistanceResult distance(const rw::geometry::Geometry& a, const rw::math::Transform3D& X_W_a,
                        const rw::geometry::Geometry& b, const rw::math::Transform3D& X_W_b);

}  // namespace rw::proximity
