#include "visgrab/database/database_writer.hpp"

#include <algorithm>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace visgrab::database {

namespace fs = std::filesystem;

DatabaseWriter::DatabaseWriter(fs::path dir, std::uint64_t seed, std::string generator,
                               const ObjectCatalog& catalog, std::string camera)
    : dir_(std::move(dir)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw std::runtime_error("cannot create " + dir_.string() + ": " + ec.message());
  const fs::path indexFile = dir_ / kIndexFileName;
  if (fs::exists(indexFile, ec)) {
    index_ = readIndex(indexFile);
    resumed_ = true;
    if (index_.formatVersion != kIndexFormatVersion) {
      throw std::runtime_error(
          indexFile.string() + ": the database was generated in index format " +
          std::to_string(index_.formatVersion) + ", which lacks files that format " +
          std::to_string(kIndexFormatVersion) + " has; generate into another folder");
    }
    if (index_.seed != seed) {
      throw std::runtime_error(indexFile.string() + ": the database was generated with seed " +
                               std::to_string(index_.seed) + ", not " + std::to_string(seed) +
                               "; use the same seed to resume, or another folder");
    }
    if (!camera.empty() && !index_.camera.empty() && index_.camera != camera) {
      throw std::runtime_error(indexFile.string() +
                               ": the database's images were made with the "
                               "camera profile \"" +
                               index_.camera + "\", not \"" + camera +
                               "\"; one database holds one profile's images: resume with "
                               "the same profile, or use another folder");
    }
    for (const SceneRecord& r : index_.scenes) {
      if (!validate(r.conditions, catalog).empty() || sceneIdOf(r.conditions, catalog) != r.id) {
        throw std::runtime_error(indexFile.string() + ": scene " + r.id +
                                 " is not one of the objects being generated; use another folder");
      }
    }
  }
  index_.catalog = catalog;
  index_.seed = seed;
  if (!generator.empty()) index_.generator = std::move(generator);
  if (!camera.empty()) index_.camera = std::move(camera);
}

DatabaseIndex DatabaseWriter::index() const {
  const std::lock_guard lock(mutex_);
  return index_;
}

bool DatabaseWriter::filesExist(const SceneFiles& files) const {
  for (const SceneFileField& field : sceneFileFields()) {
    const std::string& f = files.*field.member;
    if (f.empty() && fileMayBeAbsent(field, index_.camera)) continue;
    std::error_code ec;
    const fs::path p = dir_ / f;
    if (!fs::is_regular_file(p, ec) || fs::file_size(p, ec) == 0 || ec) return false;
  }
  return true;
}

bool DatabaseWriter::isComplete(std::string_view id) const {
  const std::lock_guard lock(mutex_);
  for (const SceneRecord& r : index_.scenes) {
    if (r.id == id) return filesExist(r.files);
  }
  return false;
}

std::vector<SceneConditions> DatabaseWriter::remaining(
    const std::vector<SceneConditions>& wanted) const {
  std::vector<SceneConditions> out;
  for (const SceneConditions& c : wanted) {
    if (!isComplete(sceneIdOf(c, index_.catalog))) out.push_back(c);
  }
  return out;
}

void DatabaseWriter::addScene(SceneRecord record) {
  const std::string expected = sceneIdOf(record.conditions, index_.catalog);
  if (record.id != expected) {
    throw std::invalid_argument("scene record \"" + record.id + "\" has the conditions of \"" +
                                expected + "\"");
  }
  for (const SceneFileField& field : sceneFileFields()) {
    const std::string& f = record.files.*field.member;
    if (f.empty() && fileMayBeAbsent(field, index_.camera)) continue;
    const std::string why = checkRelativePath(f);
    if (!why.empty()) {
      throw std::invalid_argument("scene " + record.id + ": file \"" + f + "\": " + why);
    }
    std::error_code ec;
    if (!fs::is_regular_file(dir_ / f, ec)) {
      throw std::runtime_error("scene " + record.id + ": " + (dir_ / f).string() +
                               " does not exist; write the scene's files before adding it");
    }
  }
  const std::lock_guard lock(mutex_);
  DatabaseIndex next = index_;
  const auto it = std::find_if(next.scenes.begin(), next.scenes.end(),
                               [&](const SceneRecord& r) { return r.id == record.id; });
  if (it != next.scenes.end()) {
    *it = std::move(record);
  } else {
    next.scenes.push_back(std::move(record));
  }
  std::stable_sort(
      next.scenes.begin(), next.scenes.end(), [&next](const SceneRecord& a, const SceneRecord& b) {
        return sceneIndex(a.conditions, next.catalog) < sceneIndex(b.conditions, next.catalog);
      });
  writeIndex(dir_ / kIndexFileName, next);  // throws before index_ changes
  index_ = std::move(next);
}

}  // namespace visgrab::database
