// The project's SDH box trial against the same trial in MuJoCo 2.2.2 (docs/performance.md
// "MuJoCo comparison"): BM_Sim_SdhGraspTrial's scene (tests/rwsim/simulator/data/sdh_box.dwc.xml)
// and three cylinder grasps, run by rwsim::simulator::GraspTrial with and without Q_GWS, and by
// visgrab::mujoco::MujocoGraspTrial on the scene exported to MJCF. At the end the program prints
// the CPU-time ratios project / MuJoCo (medians over repetitions, if any) and fails if a trial on
// either side did not hold the box (outcome other than stable).
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "mujoco/mjcf_export.hpp"
#include "mujoco/mujoco_grasp_trial.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "sdh_box_trial.hpp"

namespace {

namespace sim = rwsim::simulator;

const char* const kProjectWithGws = "BM_Compare_ProjectTrial";
const char* const kProjectWithoutGws = "BM_Compare_ProjectTrialWithoutGws";
const char* const kMujoco = "BM_Compare_MujocoTrial";

sim::GraspTrialSetup trialSetup(bool computeGws) {
  sim::GraspTrialSetup setup;
  setup.hand = "SchunkHand";
  setup.tcpFrame = "SchunkHand.SDHTCP";
  setup.simulator = sim::optionsFromEngineProperties(visgrab::bench::sdhBoxScene());
  setup.computeGws = computeGws;
  return setup;
}

// Trials that did not hold the box, per benchmark ("name: outcome, detail").
std::vector<std::string>& failures() {
  static std::vector<std::string> list;
  return list;
}

void noteOutcome(const char* name, sim::GraspOutcome outcome, const std::string& detail) {
  if (outcome == sim::GraspOutcome::kStable) return;
  failures().push_back(std::string(name) + ": " + std::string(sim::outcomeName(outcome)) + ", " +
                       detail);
}

void projectTrials(benchmark::State& state, bool computeGws) {
  const auto& dwc = visgrab::bench::sdhBoxScene();
  const sim::GraspTrial trial(dwc, trialSetup(computeGws));
  const auto initial = dwc.workcell().defaultState();
  std::int64_t trials = 0;
  double simulated = 0.0;
  int stable = 0;
  for (auto _ : state) {
    const auto result = trial.run(
        visgrab::bench::sdhCylinderGrasp(0.002 * static_cast<double>(trials % 3)), initial);
    simulated += result.simulatedTime;
    stable += result.outcome == sim::GraspOutcome::kStable ? 1 : 0;
    noteOutcome(computeGws ? kProjectWithGws : kProjectWithoutGws, result.outcome, result.detail);
    ++trials;
  }
  state.counters["trials/s"] =
      benchmark::Counter(static_cast<double>(trials), benchmark::Counter::kIsRate);
  state.counters["sim s/trial"] = simulated / static_cast<double>(trials);
  state.counters["stable"] = static_cast<double>(stable) / static_cast<double>(trials);
}

void BM_Compare_ProjectTrial(benchmark::State& state) { projectTrials(state, true); }
void BM_Compare_ProjectTrialWithoutGws(benchmark::State& state) { projectTrials(state, false); }

void BM_Compare_MujocoTrial(benchmark::State& state) {
  const auto& dwc = visgrab::bench::sdhBoxScene();
  static const visgrab::mujoco::MjcfModel model = visgrab::mujoco::exportMjcf(dwc);
  visgrab::mujoco::MujocoGraspTrial trial(dwc, model, trialSetup(false));
  const auto initial = dwc.workcell().defaultState();
  std::int64_t trials = 0;
  double simulated = 0.0;
  int stable = 0;
  long steps = 0;
  long rows = 0;
  long iterations = 0;
  for (auto _ : state) {
    const auto result = trial.run(
        visgrab::bench::sdhCylinderGrasp(0.002 * static_cast<double>(trials % 3)), initial);
    simulated += result.simulatedTime;
    stable += result.outcome == sim::GraspOutcome::kStable ? 1 : 0;
    steps += result.steps;
    rows += result.constraintRows;
    iterations += result.solverIterations;
    noteOutcome(kMujoco, result.outcome, result.detail);
    ++trials;
  }
  state.counters["trials/s"] =
      benchmark::Counter(static_cast<double>(trials), benchmark::Counter::kIsRate);
  state.counters["sim s/trial"] = simulated / static_cast<double>(trials);
  state.counters["stable"] = static_cast<double>(stable) / static_cast<double>(trials);
  state.counters["rows/step"] = static_cast<double>(rows) / static_cast<double>(steps);
  state.counters["iters/step"] = static_cast<double>(iterations) / static_cast<double>(steps);
}

// The console output plus each benchmark's CPU time per trial: the "median" aggregate when there
// are repetitions, else the median of the runs seen.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const std::string& name = run.run_name.function_name;
      const bool aggregate = run.run_type == Run::RT_Aggregate;
      if (aggregate && run.aggregate_name == "median") medians_[name] = run.GetAdjustedCPUTime();
      if (!aggregate && !run.error_occurred) times_[name].push_back(run.GetAdjustedCPUTime());
      if (!aggregate || run.aggregate_name == "mean") {
        if (const auto it = run.counters.find("sim s/trial"); it != run.counters.end()) {
          simulated_[name] = it->second.value;
        }
      }
    }
  }

  // Simulated time per trial of a benchmark (its last run or the mean over repetitions), s; 0 if
  // unknown.
  double simulated(const std::string& name) const {
    const auto it = simulated_.find(name);
    return it == simulated_.end() ? 0.0 : it->second;
  }

  // CPU time per trial of a benchmark (in its time unit), or a negative value if it did not run.
  double time(const std::string& name) const {
    if (const auto it = medians_.find(name); it != medians_.end()) return it->second;
    const auto it = times_.find(name);
    if (it == times_.end() || it->second.empty()) return -1.0;
    std::vector<double> t = it->second;
    std::sort(t.begin(), t.end());
    const std::size_t n = t.size();
    return n % 2 == 1 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
  }

 private:
  std::map<std::string, double> medians_;
  std::map<std::string, std::vector<double>> times_;
  std::map<std::string, double> simulated_;
};

void printRatio(const RatioReporter& reporter, const char* label, const char* project) {
  const double p = reporter.time(project);
  const double m = reporter.time(kMujoco);
  if (p <= 0.0 || m <= 0.0) return;  // filtered out
  std::printf("ratio %s: %.3f (project %.2f ms / MuJoCo %.2f ms CPU per trial)\n", label, p / m, p,
              m);
  const double ps = reporter.simulated(project);
  const double ms = reporter.simulated(kMujoco);
  if (ps > 0.0 && ms > 0.0) {
    std::printf(
        "  per simulated second %s: %.3f (project %.2f s / MuJoCo %.2f s simulated per trial)\n",
        label, (p / ps) / (m / ms), ps, ms);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::RegisterBenchmark(kProjectWithGws, BM_Compare_ProjectTrial)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(kProjectWithoutGws, BM_Compare_ProjectTrialWithoutGws)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark(kMujoco, BM_Compare_MujocoTrial)->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  std::fflush(stdout);
  printRatio(reporter, "with Q_GWS", kProjectWithGws);
  printRatio(reporter, "without Q_GWS", kProjectWithoutGws);
  if (!failures().empty()) {
    std::printf("%zu trial(s) did not hold the box:\n", failures().size());
    for (const auto& f : failures()) std::printf("  %s\n", f.c_str());
    return 1;
  }
  return 0;
}
