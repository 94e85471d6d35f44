#pragma once

#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "rwsim/trial/trial_types.hpp"
#include "visgrab/results/trial_record.hpp"

/// The per-trial record's single definition: one entry per trials.csv column. The column line,
/// the writer (formatTrialLine), the reader (parseTrials), the Python TrialResult's properties
/// and their docs all follow this table, so adding a per-trial metric is a field of TrialRecord,
/// its computation (results::recordResult) and one entry here, plus its line in docs/report.md.
namespace visgrab::results {

/// A field's value as a binding sees it: text, an integer, a real or a flag.
using TrialValue = std::variant<std::string, long long, double, bool>;

/// One column of trials.csv.
struct TrialColumn {
  /// Its name in the column line.
  std::string_view name;
  /// The Python TrialResult property that holds it (the name unless the binding's older
  /// spelling differs, e.g. "id" for "grasp").
  std::string_view property;
  /// One sentence: what it holds (the Python docstring).
  std::string_view doc;
  /// The field as written, quoting included (without the separating comma).
  std::string (*format)(const TrialRecord& trial);
  /// Reads the field (quoting undone) into `trial`; fields to its left are already read.
  /// @throws std::invalid_argument saying what is wrong with it.
  void (*parse)(const std::string& field, TrialRecord& trial);
  /// The value as a binding returns it.
  TrialValue (*value)(const TrialRecord& trial);
  /// Written only by a repeated run (`visgrab run --repeats N`, N > 1): repeat and seed. A run
  /// without repeats writes the column line without them, as before repeats existed.
  bool repeatedOnly = false;
};

/// The columns of trials.csv (the current format version), in order, the repeated-only ones
/// included.
std::span<const TrialColumn> trialColumns();

/// The column line of the current version: the names joined by commas (no line break); the
/// repeated-only columns only when `repeated`.
std::string trialColumnLine(bool repeated = false);

/// Records what a trial measured: the simulation-dependent fields of `record` (outcome, Q_lift,
/// Q_GWS, ..., closing_capped, detail) from `result`; `objectId` is the database id (1..18, 0 for
/// none) of the object the trial grasped. The identity fields (scene, method, grasp, rank,
/// conditions) are the caller's.
void recordResult(const rwsim::trial::GraspTrialResult& result, int objectId, TrialRecord& record);

}  // namespace visgrab::results
