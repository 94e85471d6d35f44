#pragma once

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/database/database_index.hpp"
#include "visgrab/database/scene_set.hpp"

namespace visgrab::database {

/// Builds a generated database folder one finished scene at a time, and resumes an interrupted
/// generation: a scene counts as done when the index lists it and all the files its record
/// names (the five required ones and the non-empty optional ones) exist and are not empty. Every
/// addScene() rewrites DIR/index.xml atomically, so an interruption never leaves a partial
/// index. Thread-safe: scenes may be added from several threads.
class DatabaseWriter {
 public:
  /// Opens `dir` for writing, creating it if needed. If DIR/index.xml exists it is read and
  /// kept (resume); its seed must equal `seed`, its format version kIndexFormatVersion and its
  /// objects `catalog`'s and, when both name one, its camera profile `camera`.
  /// @throws rw::common::LoadError for a corrupt index, std::runtime_error for a seed,
  /// version or camera mismatch, other objects, or a folder that cannot be created.
  DatabaseWriter(std::filesystem::path dir, std::uint64_t seed, std::string generator = {},
                 const ObjectCatalog& catalog = ObjectCatalog::benchmark(),
                 std::string camera = {});

  DatabaseWriter(const DatabaseWriter&) = delete;
  DatabaseWriter& operator=(const DatabaseWriter&) = delete;

  /// The database folder.
  const std::filesystem::path& directory() const { return dir_; }
  /// True if an existing index was read when opening.
  bool resumed() const { return resumed_; }
  /// A copy of the index as it is now.
  DatabaseIndex index() const;

  /// Where the files of scene `id` go by default (relative to directory()).
  SceneFiles filesFor(std::string_view id) const { return defaultSceneFiles(id); }
  /// `relative` made absolute against directory().
  std::filesystem::path path(std::string_view relative) const { return dir_ / relative; }

  /// True if the index lists scene `id` and every file its record names exists and is not
  /// empty.
  bool isComplete(std::string_view id) const;
  /// The scenes of `wanted` that are not complete, in the given order.
  std::vector<SceneConditions> remaining(const std::vector<SceneConditions>& wanted) const;

  /// Records a finished scene (replacing an earlier record with the same id) and rewrites the
  /// index atomically. Write the scene's files first (writeFileAtomically,
  /// writeImageAtomically, writeCalibration). @throws std::invalid_argument for an invalid
  /// record, std::runtime_error naming a missing file or a failed write.
  void addScene(SceneRecord record);

 private:
  bool filesExist(const SceneFiles& files) const;

  std::filesystem::path dir_;
  mutable std::mutex mutex_;
  DatabaseIndex index_;
  bool resumed_ = false;
};

}  // namespace visgrab::database
