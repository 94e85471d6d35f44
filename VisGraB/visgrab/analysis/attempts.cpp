#include "visgrab/analysis/attempts.hpp"

#include "rw/common/strings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace visgrab::analysis {

namespace {

/// FNV-1a of `text`, mixed with `seed` and `trial` by SplitMix64.
std::uint64_t mixSeed(std::uint64_t seed, int trial, std::string_view text) {
  std::uint64_t z = rw::common::fnv1a(text) ^
                    (seed + 0x9e3779b97f4a7c15ULL * (static_cast<std::uint64_t>(trial) + 1));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// Uniform integer in [0, bound) by rejection (no modulo bias; same on every platform).
std::uint64_t boundedRandom(std::mt19937_64& rng, std::uint64_t bound) {
  const std::uint64_t limit =
      std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % bound;
  std::uint64_t x = rng();
  while (x >= limit) x = rng();
  return x % bound;
}

}  // namespace

double successWithinAttempts(int grasps, int successes, int attempts) {
  if (grasps <= 0 || successes <= 0) return 0.0;
  const int m = std::min(attempts, grasps);
  if (m <= 0) return 0.0;
  if (m > grasps - successes) return 1.0;
  // C(N-K, m) / C(N, m) = prod_{i=0}^{m-1} (N-K-i) / (N-i): the first m draws all fail.
  double allFail = 1.0;
  for (int i = 0; i < m; ++i) {
    allFail *= static_cast<double>(grasps - successes - i) / static_cast<double>(grasps - i);
  }
  return 1.0 - allFail;
}

double expectedAttemptsToFirstSuccess(int grasps, int successes) {
  return static_cast<double>(grasps + 1) / static_cast<double>(successes + 1);
}

RandomizedAttempts randomizedAttempts(const std::vector<SceneOutcomes>& scenes, int maxAttempts,
                                      int trials, std::uint64_t seed) {
  RandomizedAttempts out;
  const int n = std::max(maxAttempts, 0);
  std::vector<double> hits(static_cast<std::size_t>(n), 0.0);
  double firstSum = 0.0;
  long firstCount = 0;
  long pairs = 0;
  std::vector<std::size_t> order;
  for (int trial = 0; trial < trials; ++trial) {
    for (const SceneOutcomes& scene : scenes) {
      ++pairs;
      const std::size_t size = scene.success.size();
      order.resize(size);
      std::iota(order.begin(), order.end(), std::size_t{0});
      std::mt19937_64 rng(mixSeed(seed, trial, scene.key));
      for (std::size_t i = size; i > 1; --i) {
        std::swap(order[i - 1], order[boundedRandom(rng, i)]);
      }
      std::size_t first = 0;  // 1-based position of the first success, 0 if none
      for (std::size_t i = 0; i < size; ++i) {
        if (scene.success[order[i]]) {
          first = i + 1;
          break;
        }
      }
      if (first == 0) continue;
      firstSum += static_cast<double>(first);
      ++firstCount;
      for (std::size_t k = first; k <= static_cast<std::size_t>(n); ++k) hits[k - 1] += 1.0;
    }
  }
  out.rate.resize(hits.size(), 0.0);
  if (pairs > 0) {
    for (std::size_t k = 0; k < hits.size(); ++k)
      out.rate[k] = hits[k] / static_cast<double>(pairs);
  }
  out.meanFirstSuccess = firstCount > 0 ? firstSum / static_cast<double>(firstCount) : std::nan("");
  return out;
}

}  // namespace visgrab::analysis
