#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rw/math/types.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/objects/object_model.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace visgrab::generator {

/// Where the shared assets of a generated database live, relative to its folder: one copy of
/// every object, table surface and hand, which the scene files include.
struct AssetLayout {
  /// Objects: `objects/<name>/<name>.obj`, `<name>_hull<k>.stl` (box and handle pieces only).
  std::string objects = "objects";
  /// Table surfaces: `tables/<plain|textured>/<name>.obj`.
  std::string tables = "tables";
  /// The hand: `hands/sdh/sdh.wc.xml` and `sdh_dynamics.dwc.xml`.
  std::string hand = "hands/sdh";
  /// The material map (VisGraB's friction values).
  std::string materials = "materials.xml";
};

/// The table every scene stands on: its top is the table (world) frame's z = 0 plane.
struct TableGeometry {
  /// Size along x, m.
  double x = 1.2;
  /// Size along y, m.
  double y = 0.8;
  /// Thickness of the collision box under the top, m.
  double thickness = 0.04;
};

/// The hand's parking pose: its mount frame in the world, far from the table's objects so that
/// a scene loads with the hand in it but nothing touches it.
inline rw::math::Transform3D defaultHandParking() {
  rw::math::Transform3D X =
      rw::math::Transform3D(Eigen::AngleAxisd(3.14159265358979323846, rw::math::Vector3D::UnitY()));
  X.pretranslate(rw::math::Vector3D(0.0, 0.9, 0.6));
  return X;
}

/// The text of a scene's workcell (.wc.xml): the table (textured surface to draw, a box to
/// collide with), each object as a Movable frame at its pose, and the hand (included) parked
/// at `X_W_handMount`. `toDatabase` is the relative path from the scene file's folder to the
/// database folder (e.g. "../../../../.."), `objectPoses` one per model.
std::string sceneWorkcellXml(const database::SceneConditions& scene,
                             const std::vector<const objects::ObjectModel*>& models,
                             const std::vector<rw::math::Transform3D>& objectPoses,
                             const std::string& toDatabase, const AssetLayout& layout = {},
                             const TableGeometry& table = {},
                             const rw::math::Transform3D& X_W_handMount = defaultHandParking());

/// The text of a scene's dynamic workcell (.dwc.xml) for `workcellFile` (its name, in the same
/// folder): gravity, the materials, the table fixed, each object a rigid body (with ODE
/// damping `objectDamping` when > 0: the generator's second settle), the hand.
std::string sceneDynamicsXml(const database::SceneConditions& scene,
                             const std::vector<const objects::ObjectModel*>& models,
                             const std::string& workcellFile, const std::string& toDatabase,
                             const AssetLayout& layout = {}, double objectDamping = 0.0);

/// The catalog of a spec's objects (ids, names) and pairs (<Pair a b>, ids in that order), for
/// GeneratorOptions::catalog. @throws std::invalid_argument as ObjectCatalog::make does.
database::ObjectCatalog objectCatalog(const objects::ObjectDatabaseSpec& spec);

/// Copies `from` to `to` (creating its folder), replacing it.
/// @throws std::runtime_error naming both files.
void copyFile(const std::filesystem::path& from, const std::filesystem::path& to);

/// Copies the regular files of a hand's folder (its workcell includes its collision setup and
/// meshes) into `to`. @throws std::runtime_error naming the folder or file.
void copyHandFolder(const std::filesystem::path& handFolder, const std::filesystem::path& to);

/// The text of a workcell's HandMount frame at `X_W_handMount` and the Include of the hand's
/// workcell `handWorkcell` (a path as the scene file writes it), which hangs from it.
std::string handMountXml(const rw::math::Transform3D& X_W_handMount,
                         const std::string& handWorkcell);

/// The relative path from folder `from` to folder `to` with '/' separators ("." if equal).
std::string relativeFolder(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace visgrab::generator
