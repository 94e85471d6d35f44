#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/math/types.hpp"
#include "visgrab/database/scene_set.hpp"

namespace visgrab::database {

/// Version of the index format this code writes (attribute formatVersion). Version 1 (the
/// five files left, right, calibration, workcell, dynamicWorkcell) is still read.
inline constexpr int kIndexFormatVersion = 2;
/// Oldest index format version this code reads.
inline constexpr int kOldestIndexFormatVersion = 1;
/// File name of the index inside a database folder.
inline constexpr std::string_view kIndexFileName = "index.xml";

/// Metres per unit of the database's depth.png (0.1 mm; Open3D's depth_scale 10000).
inline constexpr double kDepthUnit = 1e-4;
/// Disparity units per pixel in the database's disparity.png (KITTI's 256).
inline constexpr double kDisparityScale = 256.0;

/// Ground truth of one object in a scene.
struct ObjectPose {
  /// Object id, 1..18.
  int object = 0;
  /// Pose of the object's model frame in the table (world) frame; metres.
  rw::math::Transform3D X_WO = rw::math::Transform3D::Identity();
};

/// The files of one scene, relative to the database folder ('/'-separated, no "..").
struct SceneFiles {
  /// Rectified left image (PNG).
  std::string left;
  /// Rectified right image (PNG).
  std::string right;
  /// Stereo calibration (OpenCV YAML, see StereoCalibration).
  std::string calibration;
  /// Kinematic scene model (RobWork .wc.xml).
  std::string workcell;
  /// Dynamic scene model (RobWork .dwc.xml).
  std::string dynamicWorkcell;
  /// Raw left sensor image: distorted, unrectified, Bayer mosaic (8-bit PNG). Empty in
  /// databases made before format version 2.
  std::string rawLeft{};
  /// Raw right sensor image.
  std::string rawRight{};
  /// Disparity of the rectified pair from the documented matcher (16-bit PNG, KITTI scale).
  std::string disparity{};
  /// Point cloud reprojected from the disparity (binary PLY with colour).
  std::string pointCloud{};
  /// Ground-truth depth of the rectified left view (16-bit PNG).
  std::string depth{};
  /// Ground-truth instance mask of the rectified left view (8-bit PNG, object ids).
  std::string mask{};
  /// Ground-truth object poses (OpenCV FileStorage YAML).
  std::string poses{};
  /// Equal when all paths are equal.
  bool operator==(const SceneFiles& other) const = default;
};

/// One file of SceneFiles with its index attribute name.
struct SceneFileField {
  /// Attribute of <Files> in index.xml (and the key of `db show --json`'s files).
  const char* attribute;
  /// The member it is stored in.
  std::string SceneFiles::*member;
  /// True for the five files every index version has (never empty); false for the files of
  /// format version 2, empty when a scene has none.
  bool required;
};

/// Every file of a scene in index order: left, right, calibration, workcell, dynamicWorkcell,
/// rawLeft, rawRight, disparity, pointCloud, depth, mask, poses.
const std::vector<SceneFileField>& sceneFileFields();

/// The camera profile name of a database whose scenes have no images and no calibration (made
/// from objects alone, `visgrab db from-acronym`): `left`, `right` and `calibration` may then be
/// absent.
inline constexpr std::string_view kNoCamera = "none";

/// Where a scene was made from when it is not one of the generator's (`db from-acronym`): the
/// source file's name and the pose of its frame in the scene's world (for an ACRONYM file: the
/// frame of its scaled mesh, in which its grasps are given).
struct SceneSource {
  /// The file's name, without folders (e.g. "Table_99cf..._0.0097.h5").
  std::string file;
  /// Pose of the source's frame in the table (world) frame.
  rw::math::Transform3D X_W_source = rw::math::Transform3D::Identity();
};

/// True when a scene of a database made with camera profile `camera` may lack `field`'s file:
/// the files of format version 2, and in a database without images (kNoCamera) also the images
/// and the calibration (never the workcell and dynamic workcell).
bool fileMayBeAbsent(const SceneFileField& field, std::string_view camera);

/// One scene of a generated database.
struct SceneRecord {
  /// Scene id (sceneIdOf(conditions)).
  std::string id;
  /// The scene's conditions.
  SceneConditions conditions;
  /// Its files.
  SceneFiles files;
  /// Ground-truth poses, one per object, in the order of conditions.objects.
  std::vector<ObjectPose> objects;
  /// The file the scene was made from (<Source>), when not generated from a spec.
  std::optional<SceneSource> source{};
};

/// The content of DIR/index.xml.
struct DatabaseIndex {
  /// Format version (kIndexFormatVersion when written by this code).
  int formatVersion = kIndexFormatVersion;
  /// Seed the generator used (placements, textures, noise).
  std::uint64_t seed = 0;
  /// Free text naming the generator (may be empty).
  std::string generator;
  /// Name of the camera profile the images were made with (attribute camera; empty when the
  /// index does not say, e.g. format 1). One database holds one profile's images.
  std::string camera;
  /// Scenes in enumerateScenes(catalog) order.
  std::vector<SceneRecord> scenes;
  /// The objects the scenes are made of: the benchmark's, or (a database of your own objects)
  /// the ids and names its <Object> elements give and the pairs of its double scenes.
  ObjectCatalog catalog = ObjectCatalog::benchmark();
};

/// The files a generated scene has by default, all in `scenes/<id>/`: `raw_left.png`,
/// `raw_right.png`, `left.png`, `right.png`, `calibration.yml`, `disparity.png`, `cloud.ply`,
/// `depth.png`, `mask.png`, `poses.yml`, `scene.wc.xml`, `scene.dwc.xml`.
SceneFiles defaultSceneFiles(std::string_view id);

/// Reads and checks an index file of format version 1 or 2 (schema xml/database-index.xsd, then
/// meaning: ids agree with the conditions, no duplicates, objects agree with the scene, finite
/// poses, relative paths; the files of version 2 only in version 2, where an absent one is
/// empty). The result keeps the file's formatVersion.
/// @throws rw::common::LoadError with file:line diagnostics.
DatabaseIndex readIndex(const std::filesystem::path& file);

/// Same as readIndex, from text; `displayPath` names it in messages.
/// @throws rw::common::LoadError.
DatabaseIndex parseIndex(std::string_view text, const std::string& displayPath);

/// The index as XML text in format version kIndexFormatVersion (whatever index.formatVersion
/// says; empty optional files are left out; poses with 9 decimals, scenes in
/// enumerateScenes() order). @throws std::invalid_argument if a record is invalid (bad id,
/// conditions, paths).
std::string indexToXml(const DatabaseIndex& index);

/// Writes the index atomically (temporary file, then rename). @throws std::invalid_argument for
/// an invalid record, std::runtime_error if the file cannot be written.
void writeIndex(const std::filesystem::path& file, const DatabaseIndex& index);

/// Why `path` cannot be a file path in an index (empty string if it can): empty, absolute,
/// containing "..", backslashes or control characters.
std::string checkRelativePath(std::string_view path);

}  // namespace visgrab::database
