#include "visgrab/runner/shard_plan.hpp"

#include <algorithm>
#include <stdexcept>

namespace visgrab::runner {

std::vector<SceneBlock> planShards(const std::vector<std::size_t>& graspsPerScene, int count) {
  if (count < 1) {
    throw std::invalid_argument("the number of shards must be at least 1, not " +
                                std::to_string(count));
  }
  const auto n = static_cast<std::size_t>(count);
  std::size_t total = 0;
  for (const std::size_t g : graspsPerScene) total += g;
  std::vector<SceneBlock> blocks(n);
  // The block of each scene, from its grasps' midpoint 2P + g over 2T (integers: exact).
  std::vector<std::size_t> blockOf(graspsPerScene.size(), 0);
  std::size_t before = 0;
  for (std::size_t i = 0; i < graspsPerScene.size(); ++i) {
    if (total > 0) {
      const std::size_t midpoint2 = 2 * before + graspsPerScene[i];
      blockOf[i] = std::min(n - 1, midpoint2 * n / (2 * total));
    }
    before += graspsPerScene[i];
  }
  // The midpoints never decrease, so each block is a contiguous run of scenes.
  std::size_t next = 0;
  for (std::size_t k = 0; k < n; ++k) {
    blocks[k].begin = next;
    while (next < blockOf.size() && blockOf[next] == k) ++next;
    blocks[k].end = next;
  }
  return blocks;
}

void checkShardSpec(const ShardSpec& shard) {
  if (shard.count < 1) {
    throw std::invalid_argument("the number of shards (--of) must be at least 1, not " +
                                std::to_string(shard.count));
  }
  if (shard.index < 1 || shard.index > shard.count) {
    throw std::invalid_argument("the shard (--shard) must be between 1 and " +
                                std::to_string(shard.count) + " (--of), not " +
                                std::to_string(shard.index));
  }
}

std::string describe(const ShardSpec& shard) {
  return "shard " + std::to_string(shard.index) + " of " + std::to_string(shard.count);
}

}  // namespace visgrab::runner
