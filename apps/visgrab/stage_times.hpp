#pragma once

#include <functional>
#include <string>
#include <vector>

namespace visgrab::app {

/// How long each stage of a long command took (`visgrab benchmark`: database, baseline, trials,
/// report), in wall time and in the process's CPU time (all its threads), so that a run's stage
/// times can be read off its output instead of a stopwatch.
class StageTimes {
 public:
  /// Seconds since any fixed moment.
  using Clock = std::function<double()>;

  /// One finished stage.
  struct Stage {
    /// The stage's name, e.g. "database".
    std::string name;
    /// Wall time, s.
    double wall = 0.0;
    /// The process's CPU time (user + system, every thread), s.
    double cpu = 0.0;
    /// What the stage did, e.g. "432 scenes generated" (may be empty).
    std::string note;
  };

  /// Times with the steady clock and the process CPU clock.
  StageTimes();
  /// Times with the given clocks (tests inject their own).
  StageTimes(Clock wall, Clock cpu);

  /// Starts the stage `name`. @pre no stage is running.
  void start(std::string name);
  /// Ends the running stage with `note`. @pre a stage is running.
  void stop(std::string note = {});

  /// The finished stages in the order they ran.
  const std::vector<Stage>& stages() const { return stages_; }
  /// The stages and their total as aligned text lines under a heading, e.g.
  /// `  database      81.3 s    160.2 s  432 scenes generated`.
  std::string table() const;
  /// The stages and their total as CSV: `stage,wall_s,cpu_s,note`, one line each.
  std::string csv() const;

 private:
  Clock wall_;
  Clock cpu_;
  std::vector<Stage> stages_;
  bool running_ = false;
  double wallStart_ = 0.0;
  double cpuStart_ = 0.0;
};

}  // namespace visgrab::app
