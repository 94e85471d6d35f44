#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/geometry/mass_properties.hpp"
#include "rw/math/types.hpp"
#include "visgrab/objects/object_spec.hpp"
#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::objects {

/// One drawable part of an object (a box's shell, a can's label, its lids, a handle), each with
/// its own texture and specularity.
struct VisualPart {
  /// Part name, unique in the object ("box", "side0_label", "top", "handle", ...).
  std::string name;
  /// The mesh in the object frame; its texture is sRGB-encoded, `colour` is white.
  visual::VisualMesh mesh;
  /// The surface's material class, for renderers that give materials a finish of their own
  /// (a camera profile's glossy metal, glass and plastic); nullopt for printed paper labels.
  std::optional<SurfaceMaterial> material = std::nullopt;
};

/// A way the object rests on a table: its pose relative to a table frame whose z = 0 is the
/// table top, with the collision geometry touching z = 0 from above and the collision bounding
/// box centred on the table frame's z axis. Scene generation turns it about the table's z axis.
struct RestingPose {
  /// "standing", "lying-x" (turned about the object's x axis), "lying-y", "lying".
  std::string name;
  /// True for the lying poses (the object's z axis horizontal).
  bool lying = false;
  /// Pose of the object frame in the table frame.
  rw::math::Transform3D X_TO = rw::math::Transform3D::Identity();
  /// The object-frame direction that points up in this pose.
  rw::math::Vector3D up = rw::math::Vector3D::UnitZ();
};

/// One convex collision piece: the shape the workcell holds and its triangles.
struct CollisionPiece {
  /// The shape as written to the workcell: a Cylinder or Frustum primitive (centred on its own
  /// origin, axis z) for a round lathe segment, else a mesh in the object frame (box, handle).
  std::shared_ptr<const rw::geometry::Geometry> geometry;
  /// Pose of `geometry` in the object frame (identity for meshes).
  rw::math::Transform3D X_OG = rw::math::Transform3D::Identity();
  /// The piece as a closed mesh in the object frame, wound outwards (for a round piece a
  /// 32-sided polygon inscribed in its circles, with vertices on the +-x and +-y axes).
  std::shared_ptr<const rw::geometry::TriMesh> triangles;

  /// True when the piece is a primitive (written as Cylinder or Frustum, not as STL).
  bool isRound() const { return geometry->type() != rw::geometry::GeometryType::kMesh; }
};

/// A generated object: what the cameras see, what the simulator touches, and how heavy it is.
/// Frame: origin at the centre of the bottom face when standing, z up.
struct ObjectModel {
  /// Number in the paper's tables.
  int id = 0;
  /// Lower-case name.
  std::string name;
  /// Visual parts; together they form a closed surface (when vertices are joined by position).
  std::vector<VisualPart> visual;
  /// Convex collision pieces (a box mesh; a cylinder or frustum per lathe profile segment;
  /// handle segment meshes).
  std::vector<CollisionPiece> collision;
  /// Mass, COG and inertia about the COG, uniform density over the collision pieces' exact
  /// shapes (true cylinders and frusta, not their tessellation).
  rw::geometry::BodyMassProperties mass;
  /// Standing first, then the lying poses.
  std::vector<RestingPose> restingPoses;
  /// Mesh objects: the pose of the mesh file's frame, scaled to metres, in the object frame
  /// (a point p of the file is at X_O_mesh * (scale p)); identity for the other objects.
  rw::math::Transform3D X_O_mesh = rw::math::Transform3D::Identity();
  /// Mesh objects: what was done to the input (holes filled, pieces replaced by their hulls,
  /// the automatic decomposition's piece count and volume), one line each.
  std::vector<std::string> notes;

  /// Bounding box of the collision pieces' triangles in the object frame (exact for the round
  /// pieces in x, y and z: their polygons have vertices on the axes).
  rw::geometry::Aabb collisionBounds() const;
};

/// A generated table surface: a textured rectangle at z = 0 centred at the origin, facing up.
struct TableModel {
  /// "plain" or "textured".
  std::string name;
  /// The surface mesh (normals +z) with its texture.
  visual::VisualMesh surface;
  /// Size along x in metres.
  double x = 0.0;
  /// Size along y in metres.
  double y = 0.0;
};

/// Generates the object described by `spec` (deterministic: the same spec gives the same
/// meshes and textures, bit for bit); a mesh object through generateMeshObject.
/// @throws std::invalid_argument if `spec` breaks the rules loadObjectSpecs checks;
/// rw::common::LoadError (spec file and line) for a mesh object's unusable files.
ObjectModel generateObject(const ObjectSpec& spec);

/// Generates a table surface (deterministic).
/// @throws std::invalid_argument unless the size is positive.
TableModel generateTable(const TableSpec& spec);

}  // namespace visgrab::objects
