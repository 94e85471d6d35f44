#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "rw/geometry/geometry.hpp"
#include "visgrab/objects/object_spec.hpp"
#include "visgrab/visual/visual_mesh.hpp"

/// Internal helpers of the object generator: meshes of boxes, lathes and handles.
namespace visgrab::objects::detail {

/// Sides of the polygon of a cylinder's or frustum's collision piece (a multiple of 4, so the
/// polygon's extent along x and y is the full diameter).
inline constexpr int kCollisionSides = 32;
/// Sides of a lathe's visual mesh (vertices on the true radius, outside the collision polygon by
/// at most r (1 - cos(pi/32)), under 0.5 mm for r < 0.1 m).
inline constexpr int kVisualSides = 64;
/// Convex collision pieces of a handle (even, so that one joint lies at the outermost point).
inline constexpr int kHandleSegments = 8;
/// Segments of a handle's visual tube along its arc.
inline constexpr int kHandleVisualSegments = 16;
/// Sides of a handle piece's cross-section.
inline constexpr int kHandleCollisionSides = 8;
/// Sides of the handle's visual tube.
inline constexpr int kHandleVisualSides = 16;

/// Where each face of a box lies in its texture atlas, in pixels.
struct BoxAtlas {
  /// Atlas size in pixels.
  int width = 0;
  /// Atlas height in pixels.
  int height = 0;
  /// Per face (+x, -x, +y, -y, +z, -z): left, top, width, height in pixels.
  std::array<std::array<int, 4>, 6> faces{};
  /// Per face: its size in metres (horizontal, vertical as seen from outside).
  std::array<Eigen::Vector2d, 6> faceSize{};
};

/// Lays out the six faces of a box of full edge lengths `size` at `texelsPerMetre`.
BoxAtlas boxAtlas(const Eigen::Vector3d& size, double texelsPerMetre);

/// A closed box mesh from z = 0 to size.z(), centred in x and y, edges rounded with `radius`
/// (0 = sharp), smooth normals on the rounding, UVs into `atlas`. Faces meet at identical
/// positions (split for the UV seams).
visual::VisualMesh roundedBoxMesh(const Eigen::Vector3d& size, double radius,
                                  const BoxAtlas& atlas);

/// The box from z = 0 to size.z(), centred in x and y: 8 vertices, 12 triangles.
rw::geometry::TriMesh boxPiece(const Eigen::Vector3d& size);

/// A closed frustum about z from (z0, r0) to (z1, r1) with `sides` sides, a vertex at angle 0.
rw::geometry::TriMesh frustumPiece(double z0, double r0, double z1, double r1, int sides);

/// Arc length of the profile from z = 0 to z (in the rz-plane).
double profileArcLength(const std::vector<ProfilePoint>& profile, double z);

/// The side of a lathe between heights z0 < z1: kVisualSides around (a duplicated seam column),
/// normals smooth across profile points that bend by less than 35 degrees, UVs u = angle/2pi and
/// v = 0 at z1 to 1 at z0 by arc length.
visual::VisualMesh latheSideMesh(const std::vector<ProfilePoint>& profile, double z0, double z1);

/// A flat disk of radius r at height z, facing up (`up`) or down, with kVisualSides rim vertices
/// at the same positions as latheSideMesh's rings; UVs map the disk's square to [0, 1]^2 as seen
/// from outside.
visual::VisualMesh diskMesh(double z, double r, bool up);

/// Points of a handle's centre line (segments + 1), from its lower to its upper attachment.
std::vector<Eigen::Vector3d> handleCentreLine(const ObjectSpec& spec, int segments);

/// The handle's convex pieces: mitred straight prisms along the centre line.
std::vector<rw::geometry::TriMesh> handlePieces(const ObjectSpec& spec);

/// The handle's closed visual tube, smooth normals, UVs u along the arc and v around.
visual::VisualMesh handleMesh(const ObjectSpec& spec);

/// Arc length of the handle's visual centre line.
double handleLength(const ObjectSpec& spec);

}  // namespace visgrab::objects::detail
