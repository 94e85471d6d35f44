#pragma once

#include <Eigen/Core>

#include "rw/geometry/geometry.hpp"
#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::view {

/// A drawable mesh of `mesh` in one colour: every triangle gets its own three vertices, and each
/// vertex normal averages (by area) the normals of the triangles around that vertex position
/// whose normal is within `creaseDegrees` of the triangle's own, so that a cylinder's side looks
/// round while its rim and a box's edges stay sharp. Degenerate triangles are dropped.
visual::VisualMesh shadedMesh(const rw::geometry::TriMesh& mesh, const Eigen::Vector3f& colour,
                              double creaseDegrees = 35.0);

/// A closed cylinder of radius 1 along z from 0 to 1 (an arrow's shaft, scaled per arrow).
visual::VisualMesh unitShaft(int segments = 16);

/// A closed cone with its base disk (radius 1) at z = 0 and its apex at z = 1 (an arrow's head).
visual::VisualMesh unitHead(int segments = 16);

}  // namespace visgrab::view
