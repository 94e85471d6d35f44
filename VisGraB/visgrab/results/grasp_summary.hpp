#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rwsim/trial/grasp_outcome.hpp"
#include "visgrab/results/statistics.hpp"
#include "visgrab/results/trial_record.hpp"

/// grasps.csv: one line per grasp of a run with repeats (`visgrab run --repeats N`), its
/// probability of success over the repeats with a Wilson interval, and its outcome counts.
namespace visgrab::results {

/// Name of the per-grasp summary in a result folder (written only by a run with repeats).
inline constexpr std::string_view kGraspsFileName = "grasps.csv";

/// Confidence level of grasps.csv's Wilson intervals.
inline constexpr double kGraspIntervalLevel = 0.95;

/// One grasp over its repeats.
struct GraspSummary {
  /// Scene id.
  std::string sceneId;
  /// Method.
  std::string method;
  /// Grasp id.
  std::string graspId;
  /// Rank among the scene's grasps of the method.
  int rank = 0;
  /// Trials of the grasp (repeats run; fewer than the run's count when the adaptive rule
  /// stopped early).
  int repeats = 0;
  /// Of those, held ones (stable or slipped).
  int held = 0;
  /// The unperturbed trial's (repeat 0's) outcome.
  rwsim::trial::GraspOutcome unperturbed = rwsim::trial::GraspOutcome::kSimulationFailure;
  /// Trials per outcome (rwsim::trial::kOutcomeTable order).
  std::array<int, rwsim::trial::kOutcomeTable.size()> counts{};
  /// P(success) = held / repeats.
  double probability() const;
  /// Wilson interval of P at kGraspIntervalLevel.
  Interval interval() const;
};

/// The grasps of `trials` (any order), each with its repeats counted, in canonical order
/// (sortTrials with `scenes` and `methods`). @throws std::invalid_argument if a grasp lacks its
/// repeat 0.
std::vector<GraspSummary> summarizeGrasps(const std::vector<TrialRecord>& trials,
                                          const std::vector<RunScene>& scenes,
                                          const std::vector<std::string>& methods);

/// grasps.csv's text: the column line `scene,method,grasp,rank,repeats,held,p,p_ci_low,p_ci_high,
/// unperturbed,count_<outcome>...` and one record per grasp (RFC 4180, as trials.csv).
std::string formatGraspSummary(const std::vector<GraspSummary>& grasps);

/// Writes `dir`/grasps.csv for `run`'s trials atomically. @throws rw::common::WriteError.
void writeGraspSummary(const std::filesystem::path& dir, const RunResults& run);

}  // namespace visgrab::results
