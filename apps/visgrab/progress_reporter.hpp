#pragma once

#include <functional>
#include <mutex>
#include <ostream>
#include <string>
#include <string_view>

namespace visgrab::app {

/// The progress of one long job (scenes generated, trials run, pictures drawn) on a stream,
/// usually stderr. On a terminal: one live line redrawn in place (`\r`) with a bar, the rate and
/// the time left, ended by a line break when the job is done. Elsewhere (a log file, a pipe):
/// a plain line at most every `interval` seconds, plus the first and the last, so a log stays
/// readable. The library progress callbacks (generator, runner, baseline, report pictures) feed
/// it through update(); it may be called from several threads.
class ProgressReporter {
 public:
  /// Seconds since any fixed moment (tests inject their own).
  using Clock = std::function<double()>;

  /// How the progress is shown.
  struct Settings {
    /// True: a live line (a terminal); false: plain rate-limited lines.
    bool terminal = false;
    /// The least time in seconds between two plain lines.
    double interval = 5.0;
    /// The clock; empty: std::chrono::steady_clock.
    Clock clock;
  };

  /// Reports `label`'s progress (counted in `unit`, e.g. "scenes") on `out` (which must outlive
  /// this) as `settings` say.
  ProgressReporter(std::string label, std::string unit, std::ostream& out, Settings settings);

  /// Reports on stderr: live when stderr is a terminal, else a line every 5 seconds.
  ProgressReporter(std::string label, std::string unit);

  /// Ends an open live line.
  ~ProgressReporter();

  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  /// `done` of `total` units are done; `detail` (e.g. the last scene's id) goes at the end.
  void update(long done, long total, std::string_view detail = {});

  /// Ends an open live line with a line break (nothing in plain mode).
  void finish();

 private:
  std::string line(long done, long total, std::string_view detail, double elapsed) const;

  std::string label_;
  std::string unit_;
  std::ostream* out_;
  Settings settings_;
  std::mutex mutex_;
  double start_ = 0.0;
  // Plain mode: when the last line was written (negative: none yet).
  double lastLine_ = -1.0;
  // The last `done` written, so the final count is written once.
  long lastDone_ = -1;
  // Live mode: a line without its line break is on the terminal.
  bool open_ = false;
};

/// `seconds` as "4m05s", or "1h02m" from an hour on.
std::string durationText(double seconds);

}  // namespace visgrab::app
