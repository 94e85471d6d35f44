#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "visgrab/results/trial_record.hpp"

/// The files of a run's result folder (docs/report.md describes them). Both are RFC 4180 CSV
/// (csv.hpp), so `pandas.read_csv(path)` and Python's csv module read them with no options:
/// the first line is the column line, fields holding a comma, a double quote or a line break
/// (or beginning or ending with a space) are quoted with quotes doubled, line breaks stay literal
/// inside quotes (a record may then span lines), nothing is escaped with backslashes.
///  - `trials.csv` (version 4): the column line `scene,method,grasp,rank,outcome,robwork_code,
///    q_lift,q_gws,q_gws_unit,object,simulated_time,closing_capped,detail` (one line; the columns
///    are trial_columns.hpp's table), then one record per finished trial (detail always quoted;
///    an empty q_gws or q_gws_unit is "not computed", NaN; closing_capped is 0 or 1). A run with
///    repeats (`--repeats N`, N > 1) writes `repeat,seed` after `rank`.
///  - `run.csv` (version 2): the column line `record,id,texture,kind,arrangement,objects,pose,
///    count`, then one `scene` record per scene (conditions empty when unknown; objects separated
///    by spaces), one `method` record per method, one `rejected` record (count in the last
///    column) per method with rejected grasps, and `database`, `grasps`, `hand` records naming
///    the run's inputs, and `engine` and `engine_settings` records naming the physics engine and
///    its settings (absent in older files, whose runs were ODE's); a run with a trial protocol
///    other than the lift adds `protocol`, `protocol_hash` and `protocol_file` (the file it was
///    given; absent in older files), a run with repeats `repeats`, `noise` and `adaptive`.
/// The column line identifies the format: a later version that changes what a column means
/// changes the column line. Older files are still read: they start with a comment line
/// `# visgrab trials 1|2` or `# visgrab run 1` before the column line, hold one record per line
/// and escape `\`, line feed and carriage return inside quotes as `\\`, `\n`, `\r`. trials.csv
/// version 1 has no q_gws_unit: its q_gws was computed with unit normal forces, so it becomes
/// qGwsUnit and qGws is NaN (the paper's Q_GWS was not computed); version 2 has the columns of 3.
/// Version 3 (RFC 4180 like 4) has no closing_capped column: it is read from the detail text,
/// where the trial noted it (rwsim::trial::closingHitCap).
namespace visgrab::results {

/// Name of the trials file in a result folder.
inline constexpr std::string_view kTrialsFileName = "trials.csv";
/// Name of the run file in a result folder.
inline constexpr std::string_view kRunFileName = "run.csv";
/// Name of the file `visgrab run` keeps in a result folder while its run has not finished: it is
/// written before the first trial runs and removed once trials.csv is in its canonical order and
/// grasps.csv is written. A folder holding it is a run that was stopped, killed or failed, or one
/// still running: its trials are only part of the run, and an analysis of them would not say so.
/// (Folders written before the file existed never hold it.)
inline constexpr std::string_view kUnfinishedFileName = "unfinished.txt";
/// Format version of the trials.csv written (4: RFC 4180, no comment line, with closing_capped;
/// 3: the same without closing_capped; 2: the columns of 3 after `# visgrab trials 2`, backslash
/// escapes; 1: no q_gws_unit, q_gws was the unit-force one).
inline constexpr int kTrialsFormatVersion = 4;
/// Format version of the run.csv written (2: RFC 4180, no comment line; 1: `# visgrab run 1`
/// first, backslash escapes).
inline constexpr int kRunFormatVersion = 2;

/// The column line of trials.csv (ending in '\n'): what an empty result folder's file holds;
/// with the repeat and seed columns when `repeated` (a run with repeats).
std::string trialsHeader(bool repeated = false);
/// The record of trials.csv for `trial`, ending in '\n' (it spans lines when a field holds a
/// line break); with its repeat and seed when `repeated`.
std::string formatTrialLine(const TrialRecord& trial, bool repeated = false);
/// The whole run.csv for `run`'s scenes, methods and rejected counts (its trials are ignored).
std::string formatRunFile(const RunResults& run);

/// What a trials.csv holds.
struct TrialsFile {
  /// The trials, in file order (conditions not set).
  std::vector<TrialRecord> trials;
  /// 1-based line where each trial's record starts.
  std::vector<int> lines;
  /// The file ended in a record without its line break (a write cut off by a kill, possibly
  /// inside a quoted field): it was dropped.
  bool tornLastLine = false;
  /// 1-based line where the dropped record starts (0 when none was dropped).
  int tornLine = 0;
  /// Bytes up to and including the line break of the last complete record (where appending may
  /// continue); 0 when not even the column line (or an older file's two header lines) is
  /// complete.
  std::size_t completeBytes = 0;
  /// Format version of the file (kTrialsFormatVersion, 3, 2 or 1; see above).
  int version = kTrialsFormatVersion;
  /// The file has the repeat and seed columns (version 4 of a run with repeats).
  bool repeated = false;
};

/// Reads trials.csv text of version 4, 3, 2 or 1; `file` names it in errors. A last record without
/// its line break is torn (see TrialsFile) and dropped, whatever it holds. @throws
/// rw::common::LoadError with `file:line` (the line where the record starts; the message gives
/// the column) for a wrong column line or version, a malformed record, a number that is not
/// finite (`nan`, `inf`: only an empty q_gws or q_gws_unit stands for NaN), an unknown outcome, a
/// RobWork code that does not match the outcome, or a trial (scene, method, grasp, repeat) given
/// twice.
TrialsFile parseTrials(std::string_view text, const std::string& file);

/// Reads run.csv text of version 2 or 1 (scenes, methods, rejected, inputs; no trials).
/// @throws rw::common::LoadError with `file:line` for a malformed or cut-off file, unknown
/// conditions or a scene given twice.
RunResults parseRunFile(std::string_view text, const std::string& file);

/// Puts trials in the canonical order: scene (position in `scenes`, unlisted scenes after them
/// by id), method (position in `methods`, unlisted after them by name), rank, grasp id,
/// repeat.
void sortTrials(std::vector<TrialRecord>& trials, const std::vector<RunScene>& scenes,
                const std::vector<std::string>& methods);

/// Reads a result folder: run.csv (if present) and trials.csv. Trials get their scene's
/// conditions; scenes only in trials.csv are added (conditions from the id, warning when run.csv
/// exists), so are methods; trials are sorted with sortTrials; label is the folder's name.
/// A torn last record of trials.csv is dropped with a warning in `warnings` (if given).
/// RunResults::finished is false when the folder holds kUnfinishedFileName (with a warning naming
/// it and the trials read).
/// @throws rw::common::LoadError (file:line) for a folder that does not exist or is a file, a
/// missing trials.csv, one without its column line (empty, or cut off in it), or corrupt files.
RunResults readResults(const std::filesystem::path& dir,
                       std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// Writes `dir`'s unfinished.txt (atomically; a sentence for whoever opens the folder).
/// @throws rw::common::WriteError if it cannot be written.
void markUnfinished(const std::filesystem::path& dir);
/// Removes `dir`'s unfinished.txt if it is there. @throws rw::common::WriteError if it cannot be
/// removed.
void markFinished(const std::filesystem::path& dir);
/// Throws std::runtime_error naming `dir` when `run` (read from `dir`) has not finished
/// (RunResults::finished): figures over part of a run would pass for the run's. `allow` is how the
/// caller's user asks to use its trials anyway (e.g. "--allow-unfinished"), named in the message.
void requireFinished(const RunResults& run, const std::filesystem::path& dir,
                     std::string_view allow);

/// Reads the result folders `dirs` (readResults each, in order) to be compared side by side and
/// labels each run so the labels tell them apart: the folder's name (as readResults), and for
/// folders whose names are the same, the shortest trailing part of their absolute paths that
/// differs from every other folder's (`benchA/results`, `benchB/results`).
/// @throws rw::common::LoadError as readResults; std::invalid_argument when one folder is given
/// twice (also under two paths to it).
std::vector<RunResults> readResultFolders(const std::vector<std::filesystem::path>& dirs,
                                          std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// The labels readResultFolders gives folders `dirs` (no check that they exist or differ).
std::vector<std::string> distinctLabels(const std::vector<std::filesystem::path>& dirs);

/// Writes `run` as a result folder (run.csv and trials.csv in canonical order, with the repeat
/// columns when run.repeats.repeated()), each file atomically. @throws std::runtime_error if a file
/// cannot be written.
void writeResults(const std::filesystem::path& dir, const RunResults& run);

}  // namespace visgrab::results
