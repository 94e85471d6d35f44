// The SDH box trial on the ODE engine (the project's default) against the same trial on the
// optional MuJoCo engine (rwsim_mujoco; docs/performance.md "MuJoCo comparison"): BM_Sim_
// SdhGraspTrial's scene (tests/rwsim/simulator/data/sdh_box.dwc.xml) and three cylinder grasps,
// all run by the one protocol, rwsim::simulator::GraspTrial, with and without Q_GWS; only the
// engine factory differs (odeEngineFactory, the default, or rwsim::mujoco::mujocoEngineFactory).
// At the end the program prints the CPU-time ratios ODE / MuJoCo (medians over repetitions, if
// any) and fails if a trial on either engine did not hold the box (outcome other than stable or
// slipped).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rwsim/mujoco/mujoco_engine.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "sdh_box_trial.hpp"

namespace {

namespace sim = rwsim::simulator;

const char* const kOdeWithGws = "BM_Compare_OdeTrial";
const char* const kOdeWithoutGws = "BM_Compare_OdeTrialWithoutGws";
const char* const kMujocoWithGws = "BM_Compare_MujocoTrial";
const char* const kMujocoWithoutGws = "BM_Compare_MujocoTrialWithoutGws";

sim::GraspTrialSetup trialSetup(bool computeGws) {
  sim::GraspTrialSetup setup;
  setup.hand = "SchunkHand";
  setup.tcpFrame = "SchunkHand.SDHTCP";
  setup.simulator = sim::optionsFromEngineProperties(visgrab::bench::sdhBoxScene());
  setup.computeGws = computeGws;
  return setup;
}

// The MuJoCo engines of the scene (the MJCF exported and compiled once).
std::shared_ptr<const rwsim::trial::EngineFactory> mujocoEngines() {
  static const auto factory = rwsim::mujoco::mujocoEngineFactory(visgrab::bench::sdhBoxScene());
  return factory;
}

// Trials that did not hold the box, per benchmark ("name: outcome, detail").
std::vector<std::string>& failures() {
  static std::vector<std::string> list;
  return list;
}

void noteOutcome(const char* name, sim::GraspOutcome outcome, const std::string& detail) {
  if (outcome == sim::GraspOutcome::kStable || outcome == sim::GraspOutcome::kSlipped) return;
  failures().push_back(std::string(name) + ": " + std::string(sim::outcomeName(outcome)) + ", " +
                       detail);
}

void trials(benchmark::State& state, const char* name, bool computeGws,
            std::shared_ptr<const rwsim::trial::EngineFactory> engine) {
  const auto& dwc = visgrab::bench::sdhBoxScene();
  const sim::GraspTrial trial(dwc, trialSetup(computeGws), std::move(engine));
  const auto initial = dwc.workcell().defaultState();
  std::int64_t count = 0;
  double simulated = 0.0;
  int stable = 0;
  for (auto _ : state) {
    const auto result = trial.run(
        visgrab::bench::sdhCylinderGrasp(0.002 * static_cast<double>(count % 3)), initial);
    simulated += result.simulatedTime;
    stable += result.outcome == sim::GraspOutcome::kStable ? 1 : 0;
    noteOutcome(name, result.outcome, result.detail);
    ++count;
  }
  state.counters["trials/s"] =
      benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsRate);
  state.counters["sim s/trial"] = simulated / static_cast<double>(count);
  state.counters["stable"] = static_cast<double>(stable) / static_cast<double>(count);
}

void BM_Compare_OdeTrial(benchmark::State& state) { trials(state, kOdeWithGws, true, nullptr); }
void BM_Compare_OdeTrialWithoutGws(benchmark::State& state) {
  trials(state, kOdeWithoutGws, false, nullptr);
}
void BM_Compare_MujocoTrial(benchmark::State& state) {
  trials(state, kMujocoWithGws, true, mujocoEngines());
}
void BM_Compare_MujocoTrialWithoutGws(benchmark::State& state) {
  trials(state, kMujocoWithoutGws, false, mujocoEngines());
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

void printRatio(const RatioReporter& reporter, const char* label, const char* ode,
                const char* mujoco) {
  const double p = reporter.time(ode);
  const double m = reporter.time(mujoco);
  if (p <= 0.0 || m <= 0.0) return;  // filtered out
  std::printf("ratio %s: %.3f (ODE %.2f ms / MuJoCo %.2f ms CPU per trial)\n", label, p / m, p, m);
  const double ps = reporter.simulated(ode);
  const double ms = reporter.simulated(mujoco);
  if (ps > 0.0 && ms > 0.0) {
    std::printf(
        "  per simulated second %s: %.3f (ODE %.3f s / MuJoCo %.3f s simulated per trial)\n", label,
        (p / ps) / (m / ms), ps, ms);
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (const char* name : {kOdeWithGws, kOdeWithoutGws, kMujocoWithGws, kMujocoWithoutGws}) {
    const auto function = name == kOdeWithGws      ? BM_Compare_OdeTrial
                          : name == kOdeWithoutGws ? BM_Compare_OdeTrialWithoutGws
                          : name == kMujocoWithGws ? BM_Compare_MujocoTrial
                                                   : BM_Compare_MujocoTrialWithoutGws;
    benchmark::RegisterBenchmark(name, function)->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  std::printf("MuJoCo engine: %s\n", mujocoEngines()->settings().c_str());
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  std::fflush(stdout);
  printRatio(reporter, "with Q_GWS", kOdeWithGws, kMujocoWithGws);
  printRatio(reporter, "without Q_GWS", kOdeWithoutGws, kMujocoWithoutGws);
  if (!failures().empty()) {
    std::printf("%zu trial(s) did not hold the box:\n", failures().size());
    for (const auto& f : failures()) std::printf("  %s\n", f.c_str());
    return 1;
  }
  return 0;
}
