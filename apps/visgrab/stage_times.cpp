#include "stage_times.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <stdexcept>
#include <utility>

#include "visgrab/results/csv.hpp"

namespace visgrab::app {

namespace {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The total of every stage, named "total".
StageTimes::Stage total(const std::vector<StageTimes::Stage>& stages) {
  StageTimes::Stage sum{"total", 0.0, 0.0, {}};
  for (const auto& s : stages) {
    sum.wall += s.wall;
    sum.cpu += s.cpu;
  }
  return sum;
}

}  // namespace

StageTimes::StageTimes() : StageTimes(steadySeconds, processCpuSeconds) {}

StageTimes::StageTimes(Clock wall, Clock cpu) : wall_(std::move(wall)), cpu_(std::move(cpu)) {}

void StageTimes::start(std::string name) {
  if (running_) throw std::logic_error("StageTimes::start: stage " + stages_.back().name + " runs");
  stages_.push_back({std::move(name), 0.0, 0.0, {}});
  running_ = true;
  wallStart_ = wall_();
  cpuStart_ = cpu_();
}

void StageTimes::stop(std::string note) {
  if (!running_) throw std::logic_error("StageTimes::stop: no stage runs");
  Stage& s = stages_.back();
  s.wall = wall_() - wallStart_;
  s.cpu = cpu_() - cpuStart_;
  s.note = std::move(note);
  running_ = false;
}

std::string StageTimes::table() const {
  std::string text = "stage times (wall, process CPU):\n";
  std::vector<Stage> rows = stages_;
  rows.push_back(total(stages_));
  for (const auto& s : rows) {
    char line[96];
    std::snprintf(line, sizeof line, "  %-9s %9.1f s %9.1f s", s.name.c_str(), s.wall, s.cpu);
    text += line;
    if (!s.note.empty()) text += "  " + s.note;
    text += "\n";
  }
  return text;
}

std::string StageTimes::csv() const {
  std::string text = "stage,wall_s,cpu_s,note\n";
  std::vector<Stage> rows = stages_;
  rows.push_back(total(stages_));
  for (const auto& s : rows) {
    char numbers[64];
    std::snprintf(numbers, sizeof numbers, ",%.3f,%.3f,", s.wall, s.cpu);
    text += results::csvField(s.name) + numbers + results::csvField(s.note) + "\n";
  }
  return text;
}

}  // namespace visgrab::app
