#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rw/math/types.hpp"
#include "visgrab/database/scene_set.hpp"

namespace visgrab::database {

/// Version of the index format this code reads and writes (attribute formatVersion).
inline constexpr int kIndexFormatVersion = 1;
/// File name of the index inside a database folder.
inline constexpr std::string_view kIndexFileName = "index.xml";

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
};

/// The content of DIR/index.xml.
struct DatabaseIndex {
  /// Format version (kIndexFormatVersion when written by this code).
  int formatVersion = kIndexFormatVersion;
  /// Seed the generator used (placements, textures, noise).
  std::uint64_t seed = 0;
  /// Free text naming the generator (may be empty).
  std::string generator;
  /// Scenes in enumerateScenes() order.
  std::vector<SceneRecord> scenes;
};

/// The files a generated scene has by default: `scenes/<id>/left.png`, `right.png`,
/// `calibration.yml`, `scene.wc.xml`, `scene.dwc.xml`.
SceneFiles defaultSceneFiles(std::string_view id);

/// Reads and checks an index file (schema xml/database-index.xsd, then meaning: ids agree with
/// the conditions, no duplicates, objects agree with the scene, finite poses, relative paths).
/// @throws rw::common::LoadError with file:line diagnostics.
DatabaseIndex readIndex(const std::filesystem::path& file);

/// Same as readIndex, from text; `displayPath` names it in messages.
/// @throws rw::common::LoadError.
DatabaseIndex parseIndex(std::string_view text, const std::string& displayPath);

/// The index as XML text (numbers in shortest round-trip form, scenes in enumerateScenes()
/// order). @throws std::invalid_argument if a record is invalid (bad id, conditions, paths).
std::string indexToXml(const DatabaseIndex& index);

/// Writes the index atomically (temporary file, then rename). @throws std::invalid_argument for
/// an invalid record, std::runtime_error if the file cannot be written.
void writeIndex(const std::filesystem::path& file, const DatabaseIndex& index);

/// Why `path` cannot be a file path in an index (empty string if it can): empty, absolute,
/// containing "..", backslashes or control characters.
std::string checkRelativePath(std::string_view path);

}  // namespace visgrab::database
