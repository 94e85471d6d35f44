#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

/// Success against the number of attempts (paper Figure 7 and Table 2), exactly and by the
/// paper's randomized trials.
namespace visgrab::analysis {

/// Probability that at least one of `attempts` grasps drawn at random without replacement from a
/// scene's `grasps` grasps, `successes` of them successful, succeeds (hypergeometric):
/// 1 - C(grasps - successes, m) / C(grasps, m) with m = min(attempts, grasps); 0 when the scene
/// has no grasp or no success. Preconditions: 0 <= successes <= grasps, attempts >= 0.
double successWithinAttempts(int grasps, int successes, int attempts);

/// Expected position (1-based) of the first success when a scene's grasps are tried in uniformly
/// random order: (grasps + 1) / (successes + 1). Precondition: 1 <= successes <= grasps.
double expectedAttemptsToFirstSuccess(int grasps, int successes);

/// One scene's grasps for the randomized trials: which of them succeeded.
struct SceneOutcomes {
  /// A key that makes the scene's random orders independent of the other scenes and of how
  /// scenes are grouped (e.g. "<method>|<scene id>").
  std::string_view key;
  /// Success of each grasp, in any fixed order.
  std::vector<bool> success;
};

/// What the randomized trials measured over a set of scenes.
struct RandomizedAttempts {
  /// rate[n-1]: fraction of (scene, trial) pairs with a success within the first n attempts,
  /// n = 1..maxAttempts.
  std::vector<double> rate;
  /// Mean position of the first success over the (scene, trial) pairs that have one (NaN when
  /// none has).
  double meanFirstSuccess = 0.0;
};

/// The paper's estimator (§2.4.2): in each of `trials` randomized trials every scene's grasps are
/// put in a random order (Fisher-Yates with a 64-bit Mersenne Twister seeded from `seed`, the
/// trial and the scene's key, and unbiased bounded integers, so results are the same on every
/// platform); "success within n attempts" is averaged over scenes and trials. A scene without
/// grasps never succeeds.
RandomizedAttempts randomizedAttempts(const std::vector<SceneOutcomes>& scenes, int maxAttempts,
                                      int trials, std::uint64_t seed);

}  // namespace visgrab::analysis
