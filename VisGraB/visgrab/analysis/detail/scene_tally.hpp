#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "visgrab/analysis/analysis.hpp"
#include "visgrab/results/statistics.hpp"
#include "visgrab/results/trial_record.hpp"

/// What the analyses share between their source files: one scene's trials of one method, and the
/// interval computations over such scenes.
namespace visgrab::analysis::detail {

/// One grasp over its repeats (all trials of its scene, method and grasp id).
struct GraspRepeats {
  /// Trials (repeat 0 and the perturbed ones).
  int trials = 0;
  /// Of those, held (stable or slipped).
  int held = 0;
};

/// One scene's grasps of one method: the unperturbed trials (repeat 0) in rank order.
struct SceneTally {
  /// The scene id.
  std::string id;
  /// "<method>|<scene id>": the scene's random stream of the randomized trials.
  std::string key;
  /// The scene's conditions (nullopt: unknown).
  std::optional<database::SceneConditions> conditions;
  /// The repeat-0 trials, by rank.
  std::vector<const results::TrialRecord*> grasps;
  /// Per grasp (same order), its trials over all repeats.
  std::vector<GraspRepeats> repeats;
  /// Successful repeat-0 trials.
  int successes = 0;
};

/// The scenes of one run and method, in the run's scene order (scenes with trials but not in
/// the run's list appended). Only repeat-0 trials are grasps; every repeat counts in `repeats`.
std::vector<SceneTally> tallyScenes(const results::RunResults& run, const std::string& method);

/// The bootstrap settings of one estimate family: `options`' level, resamples and a seed derived
/// from options.bootstrapSeed and `key`; one thread (the analyses run families side by side).
results::BootstrapOptions bootstrapOptions(const AnalysisOptions& options, const std::string& key);

/// Fills the intervals of `result` (the *Ci fields: shares, success rate, qualities, exact curve,
/// p, ga) by the scene bootstrap over `scenes` (the group's scenes of one column).
void addGroupIntervals(const std::vector<const SceneTally*>& scenes, int maxAttempts,
                       const results::BootstrapOptions& options, GroupResult& result);

/// The scene-bootstrap interval of 100 * successes / grasps over `scenes` (the scenes of one
/// object or pair in one arrangement).
results::Interval percentInterval(const std::vector<const SceneTally*>& scenes,
                                  const results::BootstrapOptions& options);

/// The robust rate of a group and column over `scenes`; intervals when `options` is given.
RobustRate robustRate(const std::vector<const SceneTally*>& scenes,
                      const results::BootstrapOptions* options);

/// Fills `comparison` (all but its indices and runDifferences) from the scenes both columns
/// share: `a[i]` and `b[i]` are the same scene.
void compareColumns(const std::vector<const SceneTally*>& a,
                    const std::vector<const SceneTally*>& b, const AnalysisOptions& options,
                    const std::string& key, Comparison& comparison);

}  // namespace visgrab::analysis::detail
