#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "visgrab/results/trial_record.hpp"

/// The files of a run's result folder (docs/report.md describes them):
///  - `trials.csv`: the line `# visgrab trials 2`, the column line
///    `scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,
///    simulated_time,detail` (one line), then one line per finished trial (detail always quoted,
///    see csvField; an empty q_gws or q_gws_unit is "not computed", NaN). Version 1 files (no
///    q_gws_unit) are still read: their q_gws was computed with unit normal forces, so it becomes
///    qGwsUnit and qGws is NaN (the paper's Q_GWS was not computed).
///  - `run.csv`: the line `# visgrab run <version>`, the column line
///    `record,id,texture,kind,arrangement,objects,pose,count`, then one `scene` record per scene
///    (conditions empty when unknown; objects separated by spaces), one `method` record per
///    method and one `rejected` record (count in the last column) per method with rejected grasps.
namespace visgrab::results {

/// Name of the trials file in a result folder.
inline constexpr std::string_view kTrialsFileName = "trials.csv";
/// Name of the run file in a result folder.
inline constexpr std::string_view kRunFileName = "run.csv";
/// Format version written in the first line of trials.csv (2: q_gws is the paper's Q_GWS and
/// q_gws_unit the unit-force one; 1: q_gws was the unit-force one, no q_gws_unit).
inline constexpr int kTrialsFormatVersion = 2;
/// Format version written in the first line of run.csv.
inline constexpr int kRunFormatVersion = 1;

/// The two header lines of trials.csv (each ending in '\n').
std::string trialsHeader();
/// One line of trials.csv for `trial`, ending in '\n'.
std::string formatTrialLine(const TrialRecord& trial);
/// The whole run.csv for `run`'s scenes, methods and rejected counts (its trials are ignored).
std::string formatRunFile(const RunResults& run);

/// What a trials.csv holds.
struct TrialsFile {
  /// The trials, in file order (conditions not set).
  std::vector<TrialRecord> trials;
  /// 1-based line of each trial.
  std::vector<int> lines;
  /// The file ended in a line without a line break (a write cut off by a kill): it was dropped.
  bool tornLastLine = false;
  /// Bytes up to and including the last complete line (where appending may continue); 0 when
  /// not even the header is complete.
  std::size_t completeBytes = 0;
  /// Format version of the file (kTrialsFormatVersion or 1; see above).
  int version = kTrialsFormatVersion;
};

/// Reads trials.csv text of version 2 or 1; `file` names it in errors. A last line without a
/// line break is torn (see TrialsFile) and dropped, whatever it holds. @throws
/// rw::common::LoadError with `file:line` for a wrong header or version, a malformed line, an
/// unknown outcome, a RobWork code that does not match the outcome, or a trial (scene, method,
/// grasp) given twice.
TrialsFile parseTrials(std::string_view text, const std::string& file);

/// Reads run.csv text (scenes, methods, rejected; no trials). @throws rw::common::LoadError with
/// `file:line` for a malformed file, unknown conditions or a scene given twice.
RunResults parseRunFile(std::string_view text, const std::string& file);

/// Puts trials in the canonical order: scene (position in `scenes`, unlisted scenes after them
/// by id), method (position in `methods`, unlisted after them by name), rank, grasp id.
void sortTrials(std::vector<TrialRecord>& trials, const std::vector<RunScene>& scenes,
                const std::vector<std::string>& methods);

/// Reads a result folder: run.csv (if present) and trials.csv. Trials get their scene's
/// conditions; scenes only in trials.csv are added (conditions from the id, warning when run.csv
/// exists), so are methods; trials are sorted with sortTrials; label is the folder's name.
/// A torn last line of trials.csv is dropped with a warning in `warnings` (if given).
/// @throws rw::common::LoadError (file:line) for corrupt files or a missing trials.csv.
RunResults readResults(const std::filesystem::path& dir,
                       std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// Writes `run` as a result folder (run.csv and trials.csv in canonical order), each file
/// atomically. @throws std::runtime_error if a file cannot be written.
void writeResults(const std::filesystem::path& dir, const RunResults& run);

}  // namespace visgrab::results
