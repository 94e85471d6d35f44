#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"
#include "visgrab/objects/object_model.hpp"
#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::objects {

/// The files written for one object.
struct ObjectFiles {
  /// The object's folder (`dir/<name>`).
  std::filesystem::path folder;
  /// The visual mesh, `<name>.obj` (all parts, one material each).
  std::filesystem::path obj;
  /// Its materials, `<name>.mtl`.
  std::filesystem::path mtl;
  /// One PNG per visual part, `<name>_<part>.png`.
  std::vector<std::filesystem::path> textures;
  /// One binary STL per mesh collision piece (box, handle), `<name>_hull<k>.stl` with k the
  /// piece's index in ObjectModel::collision; round pieces have no file.
  std::vector<std::filesystem::path> hulls;
  /// Example workcell holding just the object on WORLD, `<name>.wc.xml` (a mesh object's
  /// ObjectModel::notes as comments at its top).
  std::filesystem::path workcell;
  /// Example dynamic workcell for it, `<name>.dwc.xml`.
  std::filesystem::path dynamics;
};

/// Workcell XML of a Movable frame named after the object, on `refframe` at `X_parent`, with
/// a Drawable (colmodel="Disabled") reading `<meshPrefix><name>.obj` and one CollisionModel
/// `<name>_hull<k>` per collision piece: a `<Cylinder radius z/>` or `<Custom type="Frustum"
/// param="rb rt h"/>` at the piece's centre for a round piece, else a Polytope reading
/// `<meshPrefix><name>_hull<k>.stl`. `meshPrefix` is the folder of the files relative to the
/// workcell file that will hold the text, ending in '/' (or empty).
std::string objectFrameXml(
    const ObjectModel& model, const std::string& meshPrefix, const std::string& refframe = "WORLD",
    const rw::math::Transform3D& X_parent = rw::math::Transform3D::Identity());

/// Dynamic workcell XML of the object's RigidBody: Mass, Integrator Euler, MaterialID
/// `material`, COG and the full inertia about the COG (9 numbers, row-major); with `damping`
/// > 0 also the LinearDamping and AngularDamping properties (ODE's per-step scale).
std::string objectBodyXml(const ObjectModel& model, const std::string& material = "Object",
                          double damping = 0.0);

/// Writes `dir/<name>/`: the OBJ, MTL and PNG textures, the STLs of the mesh pieces, and the
/// example
/// `<name>.wc.xml` (a WorkCell with the object's frame) and `<name>.dwc.xml` (a DynamicWorkcell
/// for it, materials "Object" and "Table" declared inline). Creates the folders. The same model
/// gives the same bytes on every run.
/// @throws std::runtime_error naming the file if one cannot be written.
ObjectFiles writeObjectFiles(const ObjectModel& model, const std::filesystem::path& dir);

/// Writes `dir/<name>/<name>.obj`, `.mtl` and `<name>.png` for a table surface and returns the
/// OBJ's path. @throws std::runtime_error naming the file if one cannot be written.
std::filesystem::path writeTableFiles(const TableModel& table, const std::filesystem::path& dir);

/// Writes a triangle mesh as binary STL (little-endian floats, facet normals from the winding).
/// @throws std::runtime_error naming the file if it cannot be written.
void writeBinaryStl(const rw::geometry::TriMesh& mesh, const std::filesystem::path& file);

/// Writes an image as PNG (compression level 6, RGB). @throws std::runtime_error on failure.
void writePng(const visual::RgbImage& image, const std::filesystem::path& file);

}  // namespace visgrab::objects
