#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <opencv2/core/mat.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "visgrab/database/database_index.hpp"
#include "visgrab/database/point_cloud.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/database/stereo_calibration.hpp"

namespace visgrab::database {

/// A scene's data that cannot be read (missing or corrupt image, no calibration, ...).
class DatabaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A scene id that the database does not have; what() suggests the closest known ids.
class UnknownSceneError : public DatabaseError {
 public:
  /// Makes the error for `id` with the closest known ids.
  UnknownSceneError(std::string id, std::vector<std::string> closest);
  /// The id asked for.
  const std::string& id() const { return id_; }
  /// The closest known ids (by edit distance), best first.
  const std::vector<std::string>& closest() const { return closest_; }

 private:
  std::string id_;
  std::vector<std::string> closest_;
};

/// One scene as the Database presents it (generated or original).
struct SceneEntry {
  /// The id used to select it: ours for a generated database, the manifest's for the original.
  std::string id;
  /// Its conditions; nullopt for an original scene whose conditions could not be derived.
  std::optional<SceneConditions> conditions;
  /// The id in the original layout (originalIdOf) for a generated scene; the manifest id for an
  /// original one.
  std::string originalId;
  /// Left image (absolute or relative to the working folder, as the database was opened).
  std::filesystem::path leftImage;
  /// Right image.
  std::filesystem::path rightImage;
  /// Stereo calibration; empty for original scenes (the manifest names none).
  std::filesystem::path calibration;
  /// Scene workcell (.wc.xml).
  std::filesystem::path workcell;
  /// Scene dynamic workcell (.dwc.xml).
  std::filesystem::path dynamicWorkcell;
  /// Ground-truth object poses (generated scenes only).
  std::vector<ObjectPose> groundTruth;
  /// Disparity image (generated: 16-bit PNG, disparity x 256; original: the manifest's disp).
  /// Empty when the scene has none (generated databases before index format 2).
  std::filesystem::path disparity;
  /// Point cloud (generated: binary PLY, see readPointCloud; original: the manifest's
  /// pointCloud). Empty when the scene has none.
  std::filesystem::path pointCloud;
  /// Original only: collision mesh (may be empty).
  std::filesystem::path collision;
  /// Generated only (index format 2): raw left sensor image (Bayer mosaic, distorted,
  /// unrectified); empty when the scene has none.
  std::filesystem::path rawLeftImage;
  /// Raw right sensor image; as rawLeftImage.
  std::filesystem::path rawRightImage;
  /// Generated only (index format 2): ground-truth depth of the rectified left view (16-bit
  /// PNG, 0.1 mm units).
  std::filesystem::path depth;
  /// Generated only (index format 2): ground-truth instance mask of the rectified left view.
  std::filesystem::path mask;
  /// Generated only (index format 2): ground-truth poses (OpenCV YAML).
  std::filesystem::path poses;
  /// Generated only: the file the scene was made from (`db from-acronym`), else nullopt.
  std::optional<SceneSource> source{};
};

/// A scene database opened for reading: a generated folder (DIR/index.xml) or an original
/// VisGraB benchmark manifest. Immutable after opening; safe to share between threads.
class Database {
 public:
  /// Where the scenes came from.
  enum class Source { kGenerated, kOriginalManifest };

  /// Opens a generated database folder (reads DIR/index.xml; images are read on demand).
  /// @throws rw::common::LoadError if the index is missing or corrupt.
  static Database open(const std::filesystem::path& dir);
  /// Opens an original VisGraB manifest (see readOriginalManifest).
  /// @throws rw::common::LoadError.
  static Database openOriginalManifest(const std::filesystem::path& manifest);
  /// Same, from manifest text; `manifest` names it and gives the folder paths are relative to.
  /// @throws rw::common::LoadError.
  static Database openOriginalManifestText(std::string_view text,
                                           const std::filesystem::path& manifest);
  /// Opens what `path` is: a folder or an `index.xml` file → generated; another file → an
  /// original manifest. @throws rw::common::LoadError.
  static Database openAny(const std::filesystem::path& path);

  /// Generated or original.
  Source source() const { return source_; }
  /// The database folder (generated) or the manifest's folder (original).
  const std::filesystem::path& root() const { return root_; }
  /// Generator seed (0 for an original manifest).
  std::uint64_t seed() const { return seed_; }
  /// Warnings found while opening (original manifests: ignored elements, duplicate ids).
  const std::vector<rw::common::Diagnostic>& warnings() const { return warnings_; }

  /// All scenes (generated: enumerateScenes() order; original: document order, one per id).
  const std::vector<SceneEntry>& list() const { return scenes_; }
  /// The scenes that `filter` selects, in list() order.
  std::vector<const SceneEntry*> filter(const SceneFilter& filter) const;
  /// True if scene(id) would find a scene.
  bool contains(std::string_view id) const { return find(id) != nullptr; }
  /// The scene with `id`. Also accepts the other spelling: an original id
  /// (`textured/cocacola/img_03`) in a generated database, our id in an original one whose
  /// conditions were derived. @throws UnknownSceneError naming the id and the closest ids.
  const SceneEntry& scene(std::string_view id) const;
  /// The closest known ids to `id` (edit distance), at most `count`, best first.
  std::vector<std::string> closestIds(std::string_view id, std::size_t count = 3) const;

  /// The left image, decoded with cv::imread `flags`. @throws UnknownSceneError, DatabaseError
  /// naming the file when it is missing or cannot be decoded (corrupt, truncated).
  cv::Mat leftImage(std::string_view id, int flags = cv::IMREAD_COLOR) const;
  /// The right image; as leftImage.
  cv::Mat rightImage(std::string_view id, int flags = cv::IMREAD_COLOR) const;
  /// The scene's stereo calibration. @throws UnknownSceneError, DatabaseError (none known),
  /// CalibrationError (file missing or invalid, naming file and node).
  StereoCalibration calibration(std::string_view id) const;
  /// The disparity of the rectified pair: CV_32F pixels, disparity in pixels, negative (-1)
  /// where there is none. A 16-bit PNG is read as value / 256 (0: none, the database's and
  /// KITTI's convention), an 8-bit image as its value (0: none), a float image as it is.
  /// @throws UnknownSceneError, DatabaseError naming the file (none known, missing, corrupt,
  /// not single-channel).
  cv::Mat disparityImage(std::string_view id) const;
  /// The ground-truth depth of the rectified left view: CV_32F camera z in metres, 0 where
  /// nothing was drawn. @throws UnknownSceneError, DatabaseError naming the file (none known,
  /// missing, corrupt, not a 16-bit single-channel image).
  cv::Mat depthImage(std::string_view id) const;
  /// The ground-truth instance mask of the rectified left view: CV_8U, 0 background, 255
  /// table, the object id on object pixels. @throws UnknownSceneError, DatabaseError naming
  /// the file (none known, missing, corrupt, not an 8-bit single-channel image).
  cv::Mat instanceMask(std::string_view id) const;
  /// The scene's point cloud (readPointCloud). @throws UnknownSceneError, DatabaseError naming
  /// the file (none known, missing, not the database's PLY layout, truncated).
  PointCloud pointCloud(std::string_view id) const;
  /// The ground-truth object poses (empty for original scenes). @throws UnknownSceneError.
  const std::vector<ObjectPose>& groundTruth(std::string_view id) const;

  /// The objects of the scenes: the benchmark's, or a database of your own objects' (its index).
  const ObjectCatalog& catalog() const { return catalog_; }

  /// One line for `visgrab db list`: id and conditions (object names from `catalog`).
  static std::string summaryLine(const SceneEntry& scene,
                                 const ObjectCatalog& catalog = ObjectCatalog::benchmark());
  /// Several lines for `visgrab db show`: ids, conditions, files (marked when missing),
  /// ground truth (object names from `catalog`).
  static std::string details(const SceneEntry& scene,
                             const ObjectCatalog& catalog = ObjectCatalog::benchmark());

 private:
  Database() = default;
  const SceneEntry* find(std::string_view id) const;
  void buildLookup();

  Source source_ = Source::kGenerated;
  std::filesystem::path root_;
  std::uint64_t seed_ = 0;
  ObjectCatalog catalog_ = ObjectCatalog::benchmark();
  std::vector<SceneEntry> scenes_;
  std::map<std::string, std::size_t, std::less<>> byId_;
  std::map<std::string, std::size_t, std::less<>> byAlias_;
  std::vector<rw::common::Diagnostic> warnings_;
};

/// 64-bit FNV-1a of the database's index file, as 16 lower-case hex digits: DIR/index.xml of a
/// generated folder (or the index.xml given), or the original manifest file. The index holds the
/// generator's seed and every object's pose, so a database generated again differently, or
/// replaced, has another hash. @throws rw::common::LoadError naming the file it cannot read.
std::string indexHash(const std::filesystem::path& database);

/// Whether `database` is still the database a run recorded (its path and, when recorded,
/// `recordedHash` of indexHash): empty if so, else why not, naming the path (it cannot be read:
/// moved or deleted; or its index changed: generated again or replaced).
std::string recordedDatabaseProblem(const std::filesystem::path& database,
                                    const std::string& recordedHash);

/// recordedDatabaseProblem as an exception, for a run that recorded a hash (nothing is checked
/// when `recordedHash` is empty: the opening of the database reports a missing one).
/// @throws std::runtime_error with recordedDatabaseProblem's text.
void requireRecordedDatabase(const std::filesystem::path& database,
                             const std::string& recordedHash);

}  // namespace visgrab::database
