#include "visgrab/database/database.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "rw/math/rpy.hpp"
#include "visgrab/database/original_manifest.hpp"

namespace visgrab::database {

namespace fs = std::filesystem;

namespace {

std::string unknownMessage(const std::string& id, const std::vector<std::string>& closest) {
  std::string message = "unknown scene id \"" + id + "\"";
  if (!closest.empty()) {
    message += "; closest known ids:";
    for (const std::string& c : closest) message += " " + c;
  }
  return message;
}

cv::Mat readImage(const fs::path& file, const std::string& what, const std::string& id, int flags) {
  const std::string prefix = file.string() + ": error: " + what + " of scene " + id + ": ";
  if (file.empty()) throw DatabaseError("scene " + id + ": no " + what + " is known");
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw DatabaseError(prefix + "no such file");
  std::ifstream in(file, std::ios::binary);
  // In one read of the file's size (not character by character: a stereo image is ~0.8 MB).
  const auto size = fs::file_size(file, ec);
  if (ec || !in) throw DatabaseError(prefix + "cannot read the file");
  std::vector<uchar> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (in.gcount() != static_cast<std::streamsize>(bytes.size())) {
    throw DatabaseError(prefix + "cannot read the file");
  }
  if (bytes.empty()) throw DatabaseError(prefix + "the file is empty");
  // OpenCV allocates the whole image from a PNG's header before it reads the pixels (found by
  // fuzzing: 57 bytes announcing 30000 x 30000 pixels took 2.7 GB), so the size is checked first.
  static constexpr std::array<uchar, 16> kPngStart = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n',
                                                      0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  static constexpr std::uint64_t kMaxPixels = std::uint64_t{1} << 26U;
  if (bytes.size() >= 24 && std::equal(kPngStart.begin(), kPngStart.end(), bytes.begin())) {
    std::uint64_t width = 0;
    std::uint64_t height = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      width = (width << 8U) | bytes[16 + i];
      height = (height << 8U) | bytes[20 + i];
    }
    if (width > kMaxPixels || height > kMaxPixels || width * height > kMaxPixels) {
      throw DatabaseError(prefix + "the PNG announces " + std::to_string(width) + " x " +
                          std::to_string(height) + " pixels, more than the " +
                          std::to_string(kMaxPixels) + " this reader accepts");
    }
  }
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, flags);
  } catch (const cv::Exception& e) {
    throw DatabaseError(prefix + "cannot decode the image: " + e.msg);
  }
  if (image.empty()) {
    throw DatabaseError(prefix + "cannot decode the image (corrupt, truncated or not an image)");
  }
  return image;
}

// A single-channel image of the given depth (CV_8U, CV_16U or CV_32F), read unchanged.
cv::Mat readSingleChannel(const fs::path& file, const std::string& what, const std::string& id,
                          std::initializer_list<int> depths, const std::string& expected) {
  cv::Mat image = readImage(file, what, id, cv::IMREAD_UNCHANGED);
  bool ok = image.channels() == 1;
  ok = ok && std::find(depths.begin(), depths.end(), image.depth()) != depths.end();
  if (!ok) {
    throw DatabaseError(file.string() + ": error: " + what + " of scene " + id + ": expected " +
                        expected + ", found " + std::to_string(image.channels()) +
                        " channel(s) of " +
                        (image.depth() == CV_8U    ? "8-bit"
                         : image.depth() == CV_16U ? "16-bit"
                                                   : "other") +
                        " values");
  }
  return image;
}

std::string fileLine(const char* label, const fs::path& file) {
  std::string line = std::string(label) + file.string();
  std::error_code ec;
  if (!file.empty() && !fs::exists(file, ec)) line += "  (missing)";
  return line + "\n";
}

}  // namespace

UnknownSceneError::UnknownSceneError(std::string id, std::vector<std::string> closest)
    : DatabaseError(unknownMessage(id, closest)),
      id_(std::move(id)),
      closest_(std::move(closest)) {}

Database Database::open(const fs::path& dir) {
  const DatabaseIndex index = readIndex(dir / kIndexFileName);
  Database db;
  db.source_ = Source::kGenerated;
  db.root_ = dir;
  db.seed_ = index.seed;
  db.catalog_ = index.catalog;
  for (const SceneRecord& r : index.scenes) {
    SceneEntry e;
    e.id = r.id;
    e.conditions = r.conditions;
    // Your own objects have no scene in the original database's layout.
    e.originalId = index.catalog.isBenchmark() ? originalIdOf(r.conditions) : r.id;
    // Files a scene may lack (those of index format 2; the images and calibration of a
    // database without images): empty paths stay empty.
    const auto optional = [&](const std::string& relative) {
      return relative.empty() ? fs::path() : dir / relative;
    };
    e.leftImage = optional(r.files.left);
    e.rightImage = optional(r.files.right);
    e.calibration = optional(r.files.calibration);
    e.workcell = dir / r.files.workcell;
    e.dynamicWorkcell = dir / r.files.dynamicWorkcell;
    e.rawLeftImage = optional(r.files.rawLeft);
    e.rawRightImage = optional(r.files.rawRight);
    e.disparity = optional(r.files.disparity);
    e.pointCloud = optional(r.files.pointCloud);
    e.depth = optional(r.files.depth);
    e.mask = optional(r.files.mask);
    e.poses = optional(r.files.poses);
    e.groundTruth = r.objects;
    e.source = r.source;
    db.scenes_.push_back(std::move(e));
  }
  std::stable_sort(db.scenes_.begin(), db.scenes_.end(), [&index](const auto& a, const auto& b) {
    return sceneIndex(*a.conditions, index.catalog) < sceneIndex(*b.conditions, index.catalog);
  });
  db.buildLookup();
  return db;
}

Database Database::openOriginalManifestText(std::string_view text, const fs::path& manifest) {
  OriginalManifest m = parseOriginalManifest(text, manifest);
  Database db;
  db.source_ = Source::kOriginalManifest;
  db.root_ = m.directory;
  db.warnings_ = std::move(m.warnings);
  for (const OriginalScene& s : m.scenes) {
    if (m.find(s.id) != &s) continue;  // an earlier duplicate: the last one wins
    SceneEntry e;
    e.id = s.id;
    e.originalId = s.id;
    e.conditions = deriveConditions(s);
    e.leftImage = s.leftImage;
    e.rightImage = s.rightImage;
    e.workcell = s.workcell;
    e.dynamicWorkcell = s.dynamicWorkcell;
    e.disparity = s.disparity;
    e.pointCloud = s.pointCloud;
    e.collision = s.collision;
    db.scenes_.push_back(std::move(e));
  }
  db.buildLookup();
  return db;
}

Database Database::openOriginalManifest(const fs::path& manifest) {
  std::string text;
  const std::string why = rw::common::readTextFile(manifest, text);
  if (!why.empty()) {
    throw rw::common::LoadError({rw::common::Diagnostic{rw::common::Diagnostic::Severity::kError,
                                                        manifest.string(),
                                                        0,
                                                        0,
                                                        "cannot read the VisGraB manifest: " + why,
                                                        {}}});
  }
  return openOriginalManifestText(text, manifest);
}

Database Database::openAny(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return open(path);
  if (path.filename() == kIndexFileName) return open(path.parent_path());
  return openOriginalManifest(path);
}

void Database::buildLookup() {
  byId_.clear();
  byAlias_.clear();
  for (std::size_t i = 0; i < scenes_.size(); ++i) {
    byId_.emplace(scenes_[i].id, i);
  }
  for (std::size_t i = 0; i < scenes_.size(); ++i) {
    const SceneEntry& e = scenes_[i];
    std::string alias;
    if (source_ == Source::kGenerated) {
      alias = e.originalId;
    } else if (e.conditions) {
      alias = sceneIdOf(*e.conditions);
    }
    if (alias.empty() || byId_.count(alias) != 0) continue;
    const auto [it, inserted] = byAlias_.emplace(alias, i);
    if (!inserted) it->second = scenes_.size();  // ambiguous: two scenes map to it
  }
}

const SceneEntry* Database::find(std::string_view id) const {
  if (const auto it = byId_.find(id); it != byId_.end()) return &scenes_[it->second];
  if (const auto it = byAlias_.find(id); it != byAlias_.end() && it->second < scenes_.size()) {
    return &scenes_[it->second];
  }
  return nullptr;
}

std::vector<const SceneEntry*> Database::filter(const SceneFilter& f) const {
  std::vector<const SceneEntry*> out;
  for (const SceneEntry& e : scenes_) {
    if (f.matches(e.id, e.conditions ? &*e.conditions : nullptr)) out.push_back(&e);
  }
  return out;
}

std::vector<std::string> Database::closestIds(std::string_view id, std::size_t count) const {
  std::vector<std::pair<std::size_t, std::size_t>> ranked;  // (distance, index)
  for (std::size_t i = 0; i < scenes_.size(); ++i) {
    ranked.emplace_back(rw::common::editDistance(id, scenes_[i].id), i);
  }
  const std::size_t n = std::min(count, ranked.size());
  std::partial_sort(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(n), ranked.end());
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back(scenes_[ranked[i].second].id);
  return out;
}

const SceneEntry& Database::scene(std::string_view id) const {
  if (const SceneEntry* e = find(id)) return *e;
  throw UnknownSceneError(std::string(id), closestIds(id));
}

cv::Mat Database::leftImage(std::string_view id, int flags) const {
  const SceneEntry& e = scene(id);
  return readImage(e.leftImage, "left image", e.id, flags);
}

cv::Mat Database::rightImage(std::string_view id, int flags) const {
  const SceneEntry& e = scene(id);
  return readImage(e.rightImage, "right image", e.id, flags);
}

StereoCalibration Database::calibration(std::string_view id) const {
  const SceneEntry& e = scene(id);
  if (e.calibration.empty()) {
    throw DatabaseError("scene " + e.id +
                        ": no calibration file is known (the original manifest names none)");
  }
  return readCalibration(e.calibration);
}

cv::Mat Database::disparityImage(std::string_view id) const {
  const SceneEntry& e = scene(id);
  cv::Mat stored = readSingleChannel(e.disparity, "disparity image", e.id, {CV_8U, CV_16U, CV_32F},
                                     "a single-channel 8-bit, 16-bit or float image");
  if (stored.depth() == CV_32F) return stored;
  cv::Mat disparity;
  stored.convertTo(disparity, CV_32F, stored.depth() == CV_16U ? 1.0 / kDisparityScale : 1.0);
  disparity.setTo(-1.0f, stored == 0);
  return disparity;
}

cv::Mat Database::depthImage(std::string_view id) const {
  const SceneEntry& e = scene(id);
  const cv::Mat stored = readSingleChannel(e.depth, "depth image", e.id, {CV_16U},
                                           "a single-channel 16-bit PNG (0.1 mm units)");
  cv::Mat depth;
  stored.convertTo(depth, CV_32F, kDepthUnit);
  return depth;
}

cv::Mat Database::instanceMask(std::string_view id) const {
  const SceneEntry& e = scene(id);
  return readSingleChannel(e.mask, "instance mask", e.id, {CV_8U},
                           "a single-channel 8-bit PNG (object ids)");
}

PointCloud Database::pointCloud(std::string_view id) const {
  const SceneEntry& e = scene(id);
  if (e.pointCloud.empty()) throw DatabaseError("scene " + e.id + ": no point cloud is known");
  try {
    return readPointCloud(e.pointCloud);
  } catch (const PointCloudError& error) {
    throw DatabaseError(std::string(error.what()) + " (point cloud of scene " + e.id + ")");
  }
}

const std::vector<ObjectPose>& Database::groundTruth(std::string_view id) const {
  return scene(id).groundTruth;
}

std::string Database::summaryLine(const SceneEntry& s, const ObjectCatalog& catalog) {
  std::ostringstream out;
  out << std::left << std::setw(44) << s.id << "  ";
  out << (s.conditions ? describe(*s.conditions, catalog) : std::string("(conditions unknown)"));
  return out.str();
}

std::string Database::details(const SceneEntry& s, const ObjectCatalog& catalog) {
  std::string out = "id:               " + s.id + "\n";
  if (s.originalId != s.id) out += "original id:      " + s.originalId + "\n";
  if (s.conditions) {
    out += "canonical id:     " + sceneIdOf(*s.conditions, catalog) + "\n";
    out += "conditions:       " + describe(*s.conditions, catalog) + "\n";
  } else {
    out += "conditions:       unknown (not derivable from the manifest)\n";
  }
  if (s.leftImage.empty() && s.rightImage.empty() && s.calibration.empty() && s.source) {
    out += "images:           none (a scene made from " + s.source->file + ")\n";
  } else {
    out += fileLine("left image:       ", s.leftImage);
    out += fileLine("right image:      ", s.rightImage);
  }
  if (!s.calibration.empty()) out += fileLine("calibration:      ", s.calibration);
  out += fileLine("workcell:         ", s.workcell);
  out += fileLine("dynamic workcell: ", s.dynamicWorkcell);
  if (!s.rawLeftImage.empty()) out += fileLine("raw left image:   ", s.rawLeftImage);
  if (!s.rawRightImage.empty()) out += fileLine("raw right image:  ", s.rawRightImage);
  if (!s.disparity.empty()) out += fileLine("disparity:        ", s.disparity);
  if (!s.pointCloud.empty()) out += fileLine("point cloud:      ", s.pointCloud);
  if (!s.depth.empty()) out += fileLine("depth (truth):    ", s.depth);
  if (!s.mask.empty()) out += fileLine("mask (truth):     ", s.mask);
  if (!s.poses.empty()) out += fileLine("poses (truth):    ", s.poses);
  if (!s.collision.empty()) out += fileLine("collision mesh:   ", s.collision);
  for (const ObjectPose& o : s.groundTruth) {
    const Eigen::Vector3d p = o.X_WO.translation();
    const Eigen::Vector3d rpy = rw::math::rotationToRpy(o.X_WO.linear()) * rw::math::kRad2Deg;
    std::ostringstream line;
    line << std::fixed << std::setprecision(4) << "object " << o.object << " "
         << catalog.name(o.object) << ": position " << p.x() << " " << p.y() << " " << p.z()
         << " m, RPY " << std::setprecision(2) << rpy.x() << " " << rpy.y() << " " << rpy.z()
         << " deg (table frame)\n";
    out += line.str();
  }
  return out;
}

std::string indexHash(const fs::path& database) {
  std::error_code ec;
  const fs::path index = fs::is_directory(database, ec) ? database / "index.xml" : database;
  return rw::common::hex64(rw::common::fnv1a(rw::common::readTextFileOrThrow(index)));
}

std::string recordedDatabaseProblem(const fs::path& database, const std::string& recordedHash) {
  std::string hash;
  try {
    hash = indexHash(database);
  } catch (const std::exception& e) {
    return "the database " + database.string() +
           " cannot be read (moved or deleted since the run?): " + e.what();
  }
  if (!recordedHash.empty() && hash != recordedHash) {
    return "the database at " + database.string() +
           " is not the one the run used: its index hash is " + hash + ", the run recorded " +
           recordedHash + " (generated again or replaced since the run?)";
  }
  return {};
}

void requireRecordedDatabase(const fs::path& database, const std::string& recordedHash) {
  if (recordedHash.empty()) return;
  if (std::string problem = recordedDatabaseProblem(database, recordedHash); !problem.empty()) {
    throw std::runtime_error(problem);
  }
}

}  // namespace visgrab::database
