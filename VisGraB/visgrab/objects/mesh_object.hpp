#pragma once

#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"
#include "visgrab/objects/object_model.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace visgrab::objects {

/// How far a triangle mesh (vertices joined by position) is from bounding a solid.
struct MeshClosure {
  /// Edges used by one triangle only.
  int openEdges = 0;
  /// Edges used by more than two triangles.
  int crowdedEdges = 0;
  /// Edges whose two triangles run along them in the same direction (inconsistent winding).
  int flippedEdges = 0;
  /// True when every edge joins exactly two consistently wound triangles.
  bool closed() const { return openEdges == 0 && crowdedEdges == 0 && flippedEdges == 0; }
};

/// Counts the edges of `mesh` that keep it from being closed.
MeshClosure checkClosure(const rw::geometry::TriMesh& mesh);

/// Closes every boundary loop of `mesh` (the open edges, followed against their triangles'
/// direction) with a fan of triangles wound like its neighbours; returns the number of loops.
int fillHoles(rw::geometry::TriMesh& mesh);

/// Resting poses on the faces of a convex hull: "standing" (identity: the object frame's z up)
/// first, then up to `maxLying` "lying-<k>" poses, one per hull face (coplanar hull triangles
/// joined) whose normal is within 60 degrees of horizontal and on which `cog` projects inside,
/// most stable first (largest distance from the projected COG to the face's edges); if no face
/// is near-horizontal, the most stable other faces except the bottom. Each pose centres the
/// hull's bounding box on the table frame's z axis with its lowest point at z = 0.
std::vector<RestingPose> hullRestingPoses(const rw::geometry::TriMesh& hull,
                                          const rw::math::Vector3D& cog, int maxLying = 4);

/// Generates a mesh object (ShapeKind::kMesh): reads the mesh (scale, rpy), checks that it is
/// closed (or fills its holes when asked) and encloses a positive volume, computes mass, COG and
/// inertia of the uniform solid (mass, or density x volume), places the object frame (the
/// mesh's lowest point at z = 0, its COG on the z axis, axes as in the file after rpy), builds
/// the visual (the file's own textured materials, else the Appearance wrapped around z by a
/// cylindrical projection, else the file's material colours) and the collision pieces (the
/// given CollisionPiece files, each replaced by its hull when not convex; else
/// decomposeConvex), and the resting poses (hullRestingPoses of the pieces' hull).
/// @throws rw::common::LoadError naming the spec file and the element's line: a mesh or piece
/// file that cannot be read, a mesh that is not closed (counts of open, crowded and flipped
/// edges), a volume that is not positive, a piece without volume.
ObjectModel generateMeshObject(const ObjectSpec& spec);

}  // namespace visgrab::objects
