#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rw/math/types.hpp"

namespace visgrab::generator {

/// One object of an ACRONYM grasp file (Eppner et al., ICRA 2021), as `visgrab db from-acronym`
/// makes a scene of it: the fields of the file's `object/` group.
struct AcronymObjectSource {
  /// The grasp file's name without folders (recorded as the scene's source; `visgrab import
  /// acronym FILE` finds the scene by it).
  std::string file;
  /// The object's mesh file (the file's `object/file`, found under the mesh root).
  std::filesystem::path mesh;
  /// Factor from the mesh file's units to metres (`object/scale`).
  double scale = 1.0;
  /// Mass, kg (`object/mass`).
  double mass = 0.0;
  /// Coulomb friction between the fingers and the object (`object/friction`).
  double friction = 1.0;
  /// Centre of mass in the scaled mesh frame, m (`object/com`).
  rw::math::Vector3D com = rw::math::Vector3D::Zero();
  /// Inertia about the centre of mass in the mesh frame's axes, kg m^2 (`object/inertia`).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// What an object of `db from-acronym` collides with.
enum class AcronymCollision {
  kMesh,    ///< the mesh itself (one non-convex piece: the simulator's triangle-mesh contacts)
  kPieces,  ///< the convex decomposition of mesh objects (objects::decomposeConvex)
};

/// Where `generateAcronymDatabase` reads the project's files from, and how it models objects.
struct AcronymDatabaseOptions {
  /// The hand copied into the database (scenes/hands/sdh: the database's hand, replaced by
  /// `--hand` when a run loads a scene).
  std::filesystem::path handFolder;
  /// The material map (scenes/materials.xml) the database's own map is made from.
  std::filesystem::path materials;
  /// The objects' collision geometry. The mesh by default: measured on ACRONYM's table example,
  /// the convex pieces bulge up to 12 mm past the mesh (docs/validation.md).
  AcronymCollision collision = AcronymCollision::kMesh;
  /// Convex decomposition (kPieces): at most this many pieces per object.
  int maxPieces = 64;
  /// Convex decomposition: a piece's hull may exceed its part's volume by this fraction.
  double concavity = 0.03;
  /// Called after each scene with its id (e.g. for progress); may be empty.
  std::function<void(const std::string& id)> onScene;
};

/// What `generateAcronymDatabase` made.
struct AcronymDatabaseReport {
  /// The scene ids, one per source in order.
  std::vector<std::string> scenes;
  /// Per scene, what the object generation did to the mesh (holes filled, pieces), prefixed with
  /// the scene id.
  std::vector<std::string> notes;
};

/// The object name a source gets in scene ids: the file name before the scale (ACRONYM names
/// its files `<Category>_<mesh id>_<scale>.h5`), lower case, characters other than letters and
/// digits as '_' (e.g. "table_99cf659ae2fe4b87b72437fd995483b").
std::string acronymObjectName(const std::string& file);

/// Makes a database of one scene per source in `out` (docs/database-format.md, "Scenes from
/// objects alone"): the object floating where its mesh frame says (the scaled mesh frame is the
/// world frame; no table), its mass, centre of mass and inertia from the source, its collision
/// geometry the mesh itself or its convex decomposition (options.collision), a material
/// of its own whose friction against the fingers is the source's; no images and no calibration
/// (index camera "none"). Scene ids are `plain/single/<name>/01`; each scene records its source
/// (<Source file>, with the world pose of the scaled mesh frame: identity). Deterministic. A
/// folder that already holds a database of the same sources is completed, not redone.
/// @throws std::invalid_argument for an empty list, two sources with one file name, a mass or
/// scale that is not finite and > 0, a friction < 0, an inertia that is not symmetric positive
/// definite; rw::common::LoadError naming the mesh for an unusable mesh; std::runtime_error
/// naming the file for files that cannot be written, or a folder holding another database.
AcronymDatabaseReport generateAcronymDatabase(const std::vector<AcronymObjectSource>& sources,
                                              const std::filesystem::path& out,
                                              const AcronymDatabaseOptions& options);

}  // namespace visgrab::generator
