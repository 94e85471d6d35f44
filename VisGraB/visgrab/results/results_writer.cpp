#include "visgrab/results/results_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "rw/common/write_error.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/results/results_file.hpp"

namespace visgrab::results {

namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

ResultsWriter::ResultsWriter(fs::path dir) : ResultsWriter(std::move(dir), Options{}) {}

ResultsWriter::ResultsWriter(fs::path dir, Options options)
    : dir_(std::move(dir)), options_(options) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw rw::common::WriteError(dir_, ec);
  const fs::path runPath = dir_ / kRunFileName;
  if (fs::exists(runPath)) {
    RunResults run = parseRunFile(readFile(runPath), runPath.string());
    scenes_ = std::move(run.scenes);
    methods_ = std::move(run.methods);
  }
  const fs::path trialsPath = dir_ / kTrialsFileName;
  std::size_t keep = 0;
  if (fs::exists(trialsPath)) {
    TrialsFile file = parseTrials(readFile(trialsPath), trialsPath.string());
    droppedTorn_ = file.tornLastLine;
    keep = file.completeBytes;
    resumed_ = file.trials.size();
    if (file.repeated != options_.repeated && !file.trials.empty()) {
      throw std::runtime_error(trialsPath.string() + " holds trials of a run " +
                               (file.repeated ? "with" : "without") + " repeats; this run is " +
                               (options_.repeated ? "" : "not ") +
                               "repeated: choose another folder");
    }
    if (file.repeated != options_.repeated) keep = 0;  // only a column line: write the right one
    if (file.version != kTrialsFormatVersion && file.completeBytes > 0) {
      // An older format: rewrite it in the current one before appending (its trials keep what
      // they had; see parseTrials), so the file never mixes formats.
      std::string text = trialsHeader(options_.repeated);
      for (const TrialRecord& t : file.trials) text += formatTrialLine(t, options_.repeated);
      database::writeFileAtomically(trialsPath, text);
      keep = text.size();
    }
    for (TrialRecord& t : file.trials) {
      keys_.emplace(Key(t.sceneId, t.method, t.graspId, t.repeat), t.outcome);
      trials_.push_back(std::move(t));
    }
  }
  fd_ = ::open(trialsPath.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) rw::common::throwWriteError(trialsPath);
  // Cut off a torn last record (or a torn header) so that appended records start on a fresh
  // line.
  if (::ftruncate(fd_, static_cast<off_t>(keep)) != 0 ||
      ::lseek(fd_, static_cast<off_t>(keep), SEEK_SET) < 0) {
    const int why = errno;
    ::close(fd_);
    fd_ = -1;
    throw rw::common::WriteError(trialsPath, std::error_code(why, std::generic_category()));
  }
  size_ = keep;
  if (keep == 0) writeAll(trialsHeader(options_.repeated));
}

ResultsWriter::~ResultsWriter() {
  if (fd_ >= 0) ::close(fd_);
}

bool ResultsWriter::contains(std::string_view scene, std::string_view method,
                             std::string_view graspId, int repeat) const {
  std::lock_guard lock(mutex_);
  return keys_.find(std::make_tuple(scene, method, graspId, repeat)) != keys_.end();
}

std::optional<rwsim::trial::GraspOutcome> ResultsWriter::outcomeOf(std::string_view scene,
                                                                   std::string_view method,
                                                                   std::string_view graspId,
                                                                   int repeat) const {
  std::lock_guard lock(mutex_);
  const auto it = keys_.find(std::make_tuple(scene, method, graspId, repeat));
  if (it == keys_.end()) return std::nullopt;
  return it->second;
}

std::vector<TrialRecord> ResultsWriter::trials() const {
  std::lock_guard lock(mutex_);
  return trials_;
}

void ResultsWriter::writeAll(std::string_view bytes) {
  const fs::path file = dir_ / kTrialsFileName;
  if (failure_) throw rw::common::WriteError(file, failure_);
  std::size_t written = 0;
  int why = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      why = errno;
      break;
    }
    written += static_cast<std::size_t>(n);
  }
  if (why == 0 && options_.syncEachTrial && ::fdatasync(fd_) != 0) why = errno;
  // A trials.csv whose folder was deleted takes every write and keeps nothing: stop at once.
  struct stat status {};
  if (why == 0 && ::fstat(fd_, &status) == 0 && status.st_nlink == 0) why = ENOENT;
  if (why != 0) {
    // Take back a part of the record (disk full in mid-record), so that the file ends in a
    // complete record; a resumed run finds a torn record anyway if even that fails. Nothing is
    // appended after a failure: a later record must never follow a torn one.
    if (written > 0 && ::ftruncate(fd_, static_cast<off_t>(size_)) == 0) {
      ::lseek(fd_, static_cast<off_t>(size_), SEEK_SET);
    }
    failure_ = std::error_code(why, std::generic_category());
    throw rw::common::WriteError(file, failure_);
  }
  size_ += bytes.size();
}

void ResultsWriter::append(const TrialRecord& trial) {
  const std::string line = formatTrialLine(trial, options_.repeated);
  std::lock_guard lock(mutex_);
  if (fd_ < 0) throw std::logic_error("ResultsWriter::append after finalize()");
  if (trial.repeat != 0 && !options_.repeated) {
    throw std::logic_error("ResultsWriter::append: a repeat in a run without repeats");
  }
  Key key(trial.sceneId, trial.method, trial.graspId, trial.repeat);
  if (keys_.count(key) != 0) {
    throw std::logic_error("trial (" + trial.sceneId + ", " + trial.method + ", " + trial.graspId +
                           ", repeat " + std::to_string(trial.repeat) +
                           ") is already in the results");
  }
  writeAll(line);
  keys_.emplace(std::move(key), trial.outcome);
  trials_.push_back(trial);
}

void ResultsWriter::writeRun(const RunResults& run) {
  const std::string text = formatRunFile(run);
  std::lock_guard lock(mutex_);
  database::writeFileAtomically(dir_ / kRunFileName, text);
  scenes_ = run.scenes;
  methods_ = run.methods;
}

void ResultsWriter::finalize() {
  std::lock_guard lock(mutex_);
  if (fd_ < 0) return;
  std::vector<TrialRecord> sorted = trials_;
  sortTrials(sorted, scenes_, methods_);
  std::string text = trialsHeader(options_.repeated);
  for (const TrialRecord& t : sorted) text += formatTrialLine(t, options_.repeated);
  database::writeFileAtomically(dir_ / kTrialsFileName, text);
  ::close(fd_);
  fd_ = -1;
}

}  // namespace visgrab::results
