#pragma once

#include <cstddef>
#include <string>
#include <vector>

/// How a benchmark run is cut into shards (`visgrab run --shard K --of N`, docs/cluster.md).
namespace visgrab::runner {

/// Shard `index` of `count` (1-based: 1 <= index <= count, as Slurm's `--array=1-N`).
struct ShardSpec {
  /// See ShardSpec.
  int index = 1;
  /// See ShardSpec.
  int count = 1;
};

/// The scenes [begin, end) of one shard, as positions in the run's scene list.
struct SceneBlock {
  /// See SceneBlock.
  std::size_t begin = 0;
  /// See SceneBlock.
  std::size_t end = 0;
};

/// Cuts the run's scenes (in database order; `graspsPerScene[i]` grasps in the i-th) into
/// `count` contiguous blocks balanced by grasp count: with T grasps in all and P grasps in the
/// scenes before scene i, scene i goes to block floor((P + graspsPerScene[i] / 2) * count / T)
/// (its grasps' midpoint; the last block for the end), so whole scenes stay together and block
/// k holds about T / count grasps. A scene without grasps goes to block floor(P * count / T)
/// (the last one at the end); T = 0 puts every scene in the first block. A block may be empty (a
/// scene with more grasps than T / count). Depends only on the counts, never on thread counts.
/// @throws std::invalid_argument if count < 1.
std::vector<SceneBlock> planShards(const std::vector<std::size_t>& graspsPerScene, int count);

/// Checks `shard` (1 <= index <= count). @throws std::invalid_argument saying what is wrong.
void checkShardSpec(const ShardSpec& shard);

/// "shard K of N".
std::string describe(const ShardSpec& shard);

}  // namespace visgrab::runner
