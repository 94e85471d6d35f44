#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

/// Joins the result folders of a run's shards into the run's result folder (`visgrab merge`).
namespace visgrab::runner {

/// What a merge wrote.
struct MergeSummary {
  /// Shards merged (N).
  int shards = 0;
  /// Scenes, methods and trials of the merged run.
  int scenes = 0;
  /// See scenes.
  int methods = 0;
  /// See scenes.
  std::size_t trials = 0;
};

/// Checks that `shardDirs` are the finished shards 1..N of one run, each given once, and
/// writes `out`/run.csv and `out`/trials.csv (results::writeResults) with the bytes a
/// one-machine `visgrab run` of the same work writes: the shards' scenes in shard order, the
/// methods, rejected counts summed per method, the sources, every trial in canonical order.
/// Shards of one run agree on N, the input fingerprint (shard.txt) and run.csv's methods and
/// sources.
/// @throws std::runtime_error naming the shard folder and what is wrong: no shard.txt, a shard
/// still running or killed, a trials.csv ending in a torn line or changed since the shard
/// finished, shards of different runs (naming the inputs that differ), a shard given twice or
/// missing, shards whose run.csv records other engines or engine settings (naming both), `out`
/// being one of the shards or holding results already (trials.csv, run.csv or grasps.csv: as
/// `visgrab run`, the merge never writes over results); rw::common::LoadError (file:line) for a
/// corrupt file; rw::common::WriteError if `out` cannot be written.
MergeSummary mergeShards(const std::vector<std::filesystem::path>& shardDirs,
                         const std::filesystem::path& out);

}  // namespace visgrab::runner
