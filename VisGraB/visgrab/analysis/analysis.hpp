#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rwsim/trial/grasp_outcome.hpp"
#include "visgrab/analysis/table.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/results/statistics.hpp"
#include "visgrab/results/trial_record.hpp"

/// The paper's five analyses (§2.4.2) of one or more runs, per condition group and method.
/// Definitions: docs/report.md.
namespace visgrab::analysis {

/// Number of grasp outcomes (rwsim::trial::kOutcomeTable order).
inline constexpr std::size_t kOutcomeCount = rwsim::trial::kOutcomeTable.size();

/// Fewest bootstrap resamples behind an interval (docs/report.md, "Error bars"): the ends of a
/// 95 % percentile interval are quantiles of the B resampled values, and with a handful of values
/// they are the extremes of a few draws, which need not even contain the estimate (B = 1 gives
/// [x, x] for one resample's x).
inline constexpr int kMinBootstrapResamples = 100;

/// Settings of the analyses.
struct AnalysisOptions {
  /// Randomized trials for the success-vs-attempts curve (paper: 20).
  int randomTrials = 20;
  /// Seed of the randomized trials (fixed: the report is deterministic).
  std::uint64_t seed = 20120601;
  /// Attempts axis 1..maxAttempts; 0: the largest number of grasps of any scene and method.
  int maxAttempts = 0;
  /// Confidence level of the intervals, in (0, 1).
  double ciLevel = 0.95;
  /// Resamples of the scene bootstrap behind every interval: 0 (no intervals, and with them no
  /// overall success rates and no comparisons: the report as it was before intervals existed)
  /// or at least kMinBootstrapResamples.
  int bootstrapResamples = 2000;
  /// Seed of the bootstrap and permutation streams (each estimate's stream is derived from it and
  /// the estimate's group, column and kind: docs/report.md, "Error bars").
  std::uint64_t bootstrapSeed = 20120601;
  /// Permutations of each paired permutation test (method against method).
  int permutations = 10000;
  /// Worker threads for the intervals; they do not depend on the count.
  int threads = 1;
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

/// `N` undefined intervals.
template <std::size_t N>
constexpr std::array<results::Interval, N> filledIntervals() {
  std::array<results::Interval, N> out{};
  for (results::Interval& i : out) i = kUndefinedInterval;
  return out;
}

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
  /// The scene-bootstrap interval of each share (undefined without intervals).
  std::array<results::Interval, kOutcomeCount> shareCi = filledIntervals<kOutcomeCount>();
  /// The interval of noGraspShare.
  results::Interval noGraspShareCi = kUndefinedInterval;
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
  /// The scene-bootstrap intervals of the three means (undefined without intervals).
  results::Interval meanQLiftCi = kUndefinedInterval;
  /// Of meanQGws.
  results::Interval meanQGwsCi = kUndefinedInterval;
  /// Of meanQGwsUnit.
  results::Interval meanQGwsUnitCi = kUndefinedInterval;
};

/// Analysis 3 (Figure 7): success rate against the number of attempts n = 1..maxAttempts, the
/// mean over all scenes of the group (scenes without grasps count as never successful).
struct AttemptsCurve {
  /// Exact expectation: mean over scenes of successWithinAttempts(grasps, successes, n).
  std::vector<double> exact;
  /// The paper's estimate by randomized trials (randomizedAttempts()).
  std::vector<double> randomized;
  /// The scene-bootstrap interval of each exact value (empty without intervals).
  std::vector<results::Interval> exactCi;
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
  /// The scene-bootstrap intervals (undefined without intervals): of p.
  results::Interval pCi = kUndefinedInterval;
  /// Of ga.
  results::Interval gaCi = kUndefinedInterval;
  /// Of gaGivenOrder.
  results::Interval gaGivenOrderCi = kUndefinedInterval;
};

/// The overall success rate: successful grasps among all grasps of the group, pooled.
struct SuccessRate {
  /// Grasps.
  int grasps = 0;
  /// Successful ones.
  int successes = 0;
  /// successes / grasps (NaN without grasps).
  double rate = 0.0;
  /// Its scene-bootstrap interval (undefined without intervals).
  results::Interval rateCi = kUndefinedInterval;
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
  /// The overall success rate.
  SuccessRate success;
};

/// Successful grasps among the grasps of some scenes.
struct SuccessCount {
  /// Grasps.
  int grasps = 0;
  /// Successful ones.
  int successes = 0;
  /// Successful ones that held the pair's first / second object (double scenes only).
  std::array<int, 2> byObject{};
  /// The scene-bootstrap interval of percent() (undefined without intervals).
  results::Interval percentCi = kUndefinedInterval;
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

/// One paired difference of two columns on their shared scenes: estimate A - B, its paired
/// scene-bootstrap interval and its two-sided paired permutation p-value.
struct PairedDifference {
  /// A's value.
  double a = 0.0;
  /// B's value.
  double b = 0.0;
  /// a - b.
  double difference = 0.0;
  /// Its paired bootstrap interval (results::pairedBootstrapInterval).
  results::Interval differenceCi = kUndefinedInterval;
  /// Its paired permutation p-value (results::pairedPermutationPValue).
  double pValue = 0.0;
};

/// Method against method: two columns compared on the scenes of a group that both were run on.
struct Comparison {
  /// Index into Analysis::groups.
  std::size_t group = 0;
  /// Index into Analysis::columns of A (the earlier column).
  std::size_t columnA = 0;
  /// Of B.
  std::size_t columnB = 0;
  /// Shared scenes of the group (the paired units).
  int scenes = 0;
  /// The pooled success rate (successes / grasps over the shared scenes).
  PairedDifference rate;
  /// p, the share of the shared scenes with a success.
  PairedDifference p;
  /// What differs between the two columns' runs (differingSources); empty within one run.
  std::vector<std::string> runDifferences;
};

/// The robust success of one column and group, from a run with repeats: each grasp's P(success)
/// = held trials / trials over its repeats (repeat 0 included, as grasps.csv counts them).
struct RobustRate {
  /// Index into Analysis::groups.
  std::size_t group = 0;
  /// Index into Analysis::columns.
  std::size_t column = 0;
  /// Grasps (each counted once).
  int grasps = 0;
  /// Trials over all their repeats.
  int trials = 0;
  /// Mean over the grasps of P(success) (NaN without grasps).
  double rate = 0.0;
  /// Its scene-bootstrap interval.
  results::Interval rateCi = kUndefinedInterval;
  /// Share of the grasps with 0 < P < 1 (NaN without grasps).
  double borderlineShare = 0.0;
  /// Its scene-bootstrap interval.
  results::Interval borderlineShareCi = kUndefinedInterval;
};

/// The run fields that differ between two runs: "hand", "engine", "engine settings",
/// "protocol" (its name or content hash), "database" (the database's index hash), in that order; an
/// unknown (empty) field differs from a known one. An empty engine counts as "ode" (runs older than
/// the record were ODE's).
std::vector<std::string> differingSources(const results::RunSources& a,
                                          const results::RunSources& b);

/// Everything the report shows.
struct Analysis {
  /// The settings used.
  AnalysisOptions options;
  /// Attempts axis length used.
  int maxAttempts = 1;
  /// Labels of the runs (RunResults::label, or "run N").
  std::vector<std::string> runLabels;
  /// Labels of the runs that had not finished (RunResults::finished false; analysed only when the
  /// user asked to): the reports say their figures cover part of the run.
  std::vector<std::string> unfinishedRuns;
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
  /// The intervals were computed (options.bootstrapResamples > 0).
  bool intervals = false;
  /// Every pair of columns with shared scenes, per group with shared scenes (group order, then
  /// column pairs in column order); empty without intervals.
  std::vector<Comparison> comparisons;
  /// Per group and column of a run with repeats (some trial's repeat > 0), group order then
  /// column order; empty when no run has repeats.
  std::vector<RobustRate> robust;
};

/// An option of analyze() out of range, named as each front end names it.
struct OptionProblem {
  /// The AnalysisOptions field, e.g. "ciLevel".
  std::string field;
  /// The `visgrab analyze` option ("--ci-level"; empty when the CLI has none).
  std::string cliOption;
  /// The Python visgrab.analyze argument ("ci_level"; empty when Python has none).
  std::string pythonArgument;
  /// What is wrong, after the name: e.g. "must be between 0 and 1 (exclusive), got 1.5" (the
  /// value as its shortest text).
  std::string problem;
};

/// The first option of `options` out of range (field order), nullopt when all are in range: the
/// one check behind analyze(), `visgrab analyze` and Python's visgrab.analyze.
std::optional<OptionProblem> checkOptions(const AnalysisOptions& options);

/// Runs the five analyses on `runs` (each run's methods become columns), with the overall
/// success rates, every estimate's scene-bootstrap interval and the comparisons of the columns
/// (unless options.bootstrapResamples is 0), and the robust rates of runs with repeats. The
/// paper's analyses read only the unperturbed trials (repeat 0). Trials of a scene not in the
/// run's scene list are analysed with that scene added (conditions from the trial).
/// @throws std::invalid_argument "FIELD PROBLEM" for options out of range (checkOptions:
/// randomTrials < 1, maxAttempts < 0, ciLevel outside (0, 1), bootstrapResamples neither 0 nor
/// at least kMinBootstrapResamples, permutations < 1, threads < 1), and for two runs of the same
/// label (RunResults::label; an empty one is "run N"): it names their columns and keys their
/// bootstrap streams (results::readResultFolders gives result folders distinct labels).
Analysis analyze(const std::vector<results::RunResults>& runs, const AnalysisOptions& options = {});

}  // namespace visgrab::analysis
