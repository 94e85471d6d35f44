#pragma once

#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"

namespace visgrab::objects {

/// The convex hull of a point set in 3-D (reentrant Qhull), as a closed triangle mesh wound
/// outwards (coplanar facets merged by Qhull, then triangulated), holding only hull vertices.
/// @throws std::invalid_argument when the points span less than 3 dimensions (fewer than 4
/// points, or all on a plane or line); std::runtime_error with Qhull's message if it fails.
rw::geometry::TriMesh convexHull(const std::vector<rw::math::Vector3D>& points);

/// Volume of the solid bounded by a closed mesh (signed tetrahedra; positive when wound
/// outwards).
double meshVolume(const rw::geometry::TriMesh& mesh);

}  // namespace visgrab::objects
