#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/runner/shard_plan.hpp"

/// The record a shard's result folder holds besides trials.csv and run.csv (docs/cluster.md):
/// which shard of which run it is and whether it finished.
namespace visgrab::runner {

/// Name of the shard record in a shard's result folder.
inline constexpr std::string_view kShardRecordFileName = "shard.txt";

/// What makes the shards of one run one run: hashes (64-bit FNV-1a, hex) of the inputs' contents
/// and the settings. Every shard of a run computes the same values, whatever its thread count.
struct RunFingerprint {
  /// The database's index.xml (a generated folder) or manifest file.
  std::string database;
  /// The grasp files in the order the run reads them (a folder's files by name): names and bytes.
  std::string grasps;
  /// The hand: its grasp description (name and bytes), or every file of its folder when the
  /// hand is given as a folder.
  std::string hand;
  /// The scene filter (--scenes), as given; empty: all scenes.
  std::string scenes;

  /// See RunFingerprint.
  bool operator==(const RunFingerprint&) const = default;
};

/// A shard's record (kShardRecordFileName): written "running" (atomically) when the shard starts
/// and "finished", with the hashes of its finished files, when it ends.
struct ShardRecord {
  /// See ShardSpec.
  ShardSpec shard;
  /// False while the shard runs, or after it was killed or stopped.
  bool finished = false;
  /// The run's inputs.
  RunFingerprint inputs;
  /// Trials in trials.csv (finished records only).
  std::size_t trials = 0;
  /// Hash of trials.csv's bytes when the shard finished (empty while running).
  std::string trialsHash;
  /// Hash of run.csv's bytes when the shard finished (empty while running).
  std::string runHash;
};

/// 64-bit FNV-1a of `bytes`, as 16 lower-case hex digits.
std::string contentHash(std::string_view bytes);

/// The fingerprint of a run over `database`, the grasp sources `grasps` (files or folders, as
/// taskio::readGraspSources reads them), the hand description or folder `hand` and the scene
/// filter `scenes`. @throws rw::common::LoadError naming a file that cannot be read.
RunFingerprint fingerprintRun(const std::filesystem::path& database,
                              const std::vector<std::filesystem::path>& grasps,
                              const std::filesystem::path& hand, const std::string& scenes);

/// The text of `record` (lines `key value`; the first line `visgrab shard 1`).
std::string formatShardRecord(const ShardRecord& record);

/// Reads a shard record's text; `file` names it in errors. @throws rw::common::LoadError with
/// file:line for a wrong first line, an unknown or repeated key, a malformed value or a missing
/// key.
ShardRecord parseShardRecord(std::string_view text, const std::string& file);

/// Reads dir/shard.txt. @throws rw::common::LoadError (file:line) if it is missing or malformed.
ShardRecord readShardRecord(const std::filesystem::path& dir);

/// Writes dir/shard.txt atomically. @throws rw::common::WriteError if it cannot be written.
void writeShardRecord(const std::filesystem::path& dir, const ShardRecord& record);

/// Names the inputs in which `a` and `b` differ ("the grasp files, the hand"); empty if none.
std::string describeDifference(const RunFingerprint& a, const RunFingerprint& b);

}  // namespace visgrab::runner
