#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <vector>

#include "visgrab/results/trial_record.hpp"

namespace visgrab::results {

/// Writes a run's result folder as the run goes (see results_file.hpp for the formats): every
/// finished trial is appended to trials.csv as one record (several lines when a field holds a
/// line break) and handed to the operating system at once (one write() per record, no buffer in
/// the process), so a killed run loses nothing but the trial being written. A failed write (disk
/// full, the folder deleted) takes back the part of the record it wrote, if it can, and ends
/// appending: the file never holds a record after a torn one. Opening a folder that has a
/// trials.csv reads it back for resume (contains()); a torn last record (cut anywhere, inside
/// quotes too) is dropped and cut off. A trials.csv of an older format version (1 or 2) is
/// rewritten in the current one first (atomically); its trials keep the values they had
/// (version 1: q_gws not computed, see parseTrials).
/// append(), contains(), trials() and writeRun() may be called from several threads.
class ResultsWriter {
 public:
  /// How durable each append is.
  struct Options {
    /// fdatasync after every trial (survives a power cut, not only a killed process; slower).
    bool syncEachTrial = false;
    /// The run repeats its grasps: trials.csv has the repeat and seed columns. Opening a file
    /// holding trials of the other kind is an error.
    bool repeated = false;
  };

  /// Opens (creating) `dir` and its trials.csv; reads back existing trials and run.csv.
  /// @throws rw::common::LoadError (file:line) if an existing file is corrupt, std::runtime_error
  /// if it holds trials with repeats and options.repeated is false or the other way round,
  /// rw::common::WriteError if the folder or file cannot be created or written.
  explicit ResultsWriter(std::filesystem::path dir);
  /// See ResultsWriter(dir).
  ResultsWriter(std::filesystem::path dir, Options options);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// The result folder.
  const std::filesystem::path& dir() const { return dir_; }
  /// Number of trials read back when the writer was opened.
  std::size_t resumedCount() const { return resumed_; }
  /// True if the file ended in a torn record when opened (it was dropped).
  bool droppedTornLine() const { return droppedTorn_; }
  /// True if trial (scene, method, graspId, repeat) is in the file (read back or appended).
  bool contains(std::string_view scene, std::string_view method, std::string_view graspId,
                int repeat = 0) const;
  /// The outcome of trial (scene, method, graspId, repeat) if it is in the file.
  std::optional<rwsim::trial::GraspOutcome> outcomeOf(std::string_view scene,
                                                      std::string_view method,
                                                      std::string_view graspId,
                                                      int repeat = 0) const;
  /// All trials so far: read back ones first, then appended ones in append order.
  std::vector<TrialRecord> trials() const;
  /// Appends one finished trial and hands it to the OS (fdatasync too if syncEachTrial).
  /// @throws std::logic_error if the trial is already there or after finalize(),
  /// rw::common::WriteError (file and reason) if the write fails, or failed before, or the file
  /// was deleted.
  void append(const TrialRecord& trial);
  /// Writes run.csv atomically (temporary file, then rename) with the run's scenes (database
  /// order), methods and rejected counts; `run.trials` is ignored. Also the order finalize() uses.
  /// @throws rw::common::WriteError if it cannot be written.
  void writeRun(const RunResults& run);
  /// Rewrites trials.csv atomically in the canonical order (sortTrials with the scenes and
  /// methods of the last writeRun(), or of run.csv when opened), so that the bytes do not depend
  /// on the order trials finished in. Closes the writer: append() throws afterwards.
  /// @throws rw::common::WriteError if it cannot be written.
  void finalize();

 private:
  using Key = std::tuple<std::string, std::string, std::string, int>;
  void writeAll(std::string_view bytes);

  std::filesystem::path dir_;
  Options options_;
  mutable std::mutex mutex_;
  int fd_ = -1;
  /// Bytes of trials.csv up to its last complete record.
  std::size_t size_ = 0;
  /// Why the last write failed (appends throw from then on).
  std::error_code failure_;
  std::size_t resumed_ = 0;
  bool droppedTorn_ = false;
  std::map<Key, rwsim::trial::GraspOutcome, std::less<>> keys_;
  std::vector<TrialRecord> trials_;
  std::vector<RunScene> scenes_;
  std::vector<std::string> methods_;
};

}  // namespace visgrab::results
