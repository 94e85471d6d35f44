#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rwsim/trial/grasp_outcome.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/results/trial_record.hpp"

/// The paper's five analyses (§2.4.2) of one or more runs, per condition group and method.
/// Definitions: docs/report.md.
namespace visgrab::analysis {

/// Number of grasp outcomes (rwsim::trial::kOutcomeTable order).
inline constexpr std::size_t kOutcomeCount = rwsim::trial::kOutcomeTable.size();

/// Settings of the analyses.
struct AnalysisOptions {
  /// Randomized trials for the success-vs-attempts curve (paper: 20).
  int randomTrials = 20;
  /// Seed of the randomized trials (fixed: the report is deterministic).
  std::uint64_t seed = 20120601;
  /// Attempts axis 1..maxAttempts; 0: the largest number of grasps of any scene and method.
  int maxAttempts = 0;
};

/// A set of scenes the analyses report on (a row of the paper's tables).
struct ConditionGroup {
  /// Key for files, e.g. "textured-single-standing", "overall".
  std::string key;
  /// Heading, e.g. "textured, single, standing".
  std::string name;
  /// Table only (nullopt: both tables, and scenes of unknown conditions).
  std::optional<database::Texture> texture;
  /// Single or double (nullopt: both).
  std::optional<database::SceneKind> kind;
  /// Standing/lying/apart/close (nullopt: all of the kind).
  std::optional<database::Arrangement> arrangement;
  /// True if a scene with these conditions belongs to the group.
  bool contains(const std::optional<database::SceneConditions>& conditions) const;
};

/// The 15 groups in report order: for the textured, then the plain table: single standing,
/// single lying, single all, double apart, double close, double all, all; then "overall".
std::vector<ConditionGroup> conditionGroups();

/// One compared column: a method of one run.
struct MethodColumn {
  /// Shown name: the method, prefixed by "<run label>: " when two runs have the same method.
  std::string label;
  /// Index of the run in analyze()'s input.
  std::size_t run = 0;
  /// The method's name in that run.
  std::string method;
  /// Grasps of this method rejected before simulation (malformed input).
  int rejected = 0;
  /// Trials of this method whose closing hit the closing cap (their detail says so: see
  /// rwsim::trial::closingHitCap); judged as they stood, they cost the cap's simulated time.
  int closingCapped = 0;
};

/// Analysis 1 (Figure 6): distribution of the outcomes. Every scene of the group has weight
/// 1/scenes: a scene without grasps adds it to noGraspShare, a scene with n grasps adds 1/n of
/// it to the share of each grasp's outcome. So noGraspShare is the proportion of scenes without a
/// suggested grasp and the other shares are the per-scene outcome distribution averaged over the
/// scenes; all shares add up to 1.
struct Distribution {
  /// Scenes in the group.
  int scenes = 0;
  /// Of those, scenes for which the method suggested no grasp.
  int scenesWithoutGrasps = 0;
  /// Grasps (trials) over all scenes.
  int grasps = 0;
  /// Grasps per outcome (plain counts).
  std::array<int, kOutcomeCount> counts{};
  /// Scene-weighted share per outcome (see above).
  std::array<double, kOutcomeCount> share{};
  /// Share of scenes without grasps.
  double noGraspShare = 0.0;
};

/// Analysis 2 (Table 1): mean qualities over all successful grasps (stable, slipped) of the group.
struct QualityMeans {
  /// Successful grasps.
  int successes = 0;
  /// Mean Q_lift (NaN without successes).
  double meanQLift = 0.0;
  /// Mean Q_GWS, the paper's definition (NaN without successes, or if one of them lacks it: a
  /// trial read from a version 1 trials.csv).
  double meanQGws = 0.0;
  /// Mean Q_GWS with unit normal forces (NaN without successes or if one of them lacks it).
  double meanQGwsUnit = 0.0;
};

/// Analysis 3 (Figure 7): success rate against the number of attempts n = 1..maxAttempts, the
/// mean over all scenes of the group (scenes without grasps count as never successful).
struct AttemptsCurve {
  /// Exact expectation: mean over scenes of successWithinAttempts(grasps, successes, n).
  std::vector<double> exact;
  /// The paper's estimate by randomized trials (randomizedAttempts()).
  std::vector<double> randomized;
};

/// Analysis 4 (Table 2): how often and how soon a success comes.
struct FirstSuccess {
  /// Scenes in the group.
  int scenes = 0;
  /// Scenes with at least one successful grasp.
  int scenesWithSuccess = 0;
  /// p = scenesWithSuccess / scenes (NaN for an empty group).
  double p = 0.0;
  /// ga: mean over the scenes with a success of the expected attempts to the first success when
  /// the grasps are tried in random order, (n + 1) / (k + 1) (NaN when no scene has a success).
  double ga = 0.0;
  /// The randomized trials' estimate of ga (mean first-success position).
  double gaRandomized = 0.0;
  /// ga when the grasps are tried in the order given (by rank).
  double gaGivenOrder = 0.0;
};

/// All analyses of one group and column.
struct GroupResult {
  /// Figure 6.
  Distribution distribution;
  /// Table 1.
  QualityMeans quality;
  /// Figure 7.
  AttemptsCurve attempts;
  /// Table 2.
  FirstSuccess firstSuccess;
};

/// Successful grasps among the grasps of some scenes.
struct SuccessCount {
  /// Grasps.
  int grasps = 0;
  /// Successful ones.
  int successes = 0;
  /// Successful ones that held the pair's first / second object (double scenes only).
  std::array<int, 2> byObject{};
  /// 100 * successes / grasps (NaN without grasps).
  double percent() const;
  /// 100 * byObject[i] / grasps (NaN without grasps).
  double percentOf(int i) const;
};

/// Analysis 5 (Tables 3 and 4) for one table (texture) and column: successful grasps out of all
/// grasps of the scenes, per object and arrangement.
struct ObjectTable {
  /// single[object - 1][0 standing, 1 lying].
  std::array<std::array<SuccessCount, 2>, database::kObjectCount> single{};
  /// pairs[pair index (a = 0)][0 far (apart), 1 close].
  std::array<std::array<SuccessCount, 2>, database::kPairCount> pairs{};
};

/// Everything the report shows.
struct Analysis {
  /// The settings used.
  AnalysisOptions options;
  /// Attempts axis length used.
  int maxAttempts = 1;
  /// Labels of the runs (RunResults::label, or "run N").
  std::vector<std::string> runLabels;
  /// The compared columns, run by run, methods in each run's order.
  std::vector<MethodColumn> columns;
  /// The groups (conditionGroups()).
  std::vector<ConditionGroup> groups;
  /// results[group][column].
  std::vector<std::vector<GroupResult>> results;
  /// objectTables[0 textured (Table 3), 1 plain (Table 4)][column].
  std::array<std::vector<ObjectTable>, 2> objectTables;
  /// Scenes of unknown conditions per run (only in "overall").
  std::vector<int> unknownScenes;
};

/// Runs the five analyses on `runs` (each run's methods become columns). Trials of a scene not in
/// the run's scene list are analysed with that scene added (conditions from the trial).
/// @throws std::invalid_argument for options out of range (randomTrials < 1, maxAttempts < 0).
Analysis analyze(const std::vector<results::RunResults>& runs, const AnalysisOptions& options = {});

}  // namespace visgrab::analysis
