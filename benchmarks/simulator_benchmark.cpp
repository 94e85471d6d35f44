// The ODE simulator on the project's SDH over a 6 x 6 x 10 cm box (the simulator tests' scene,
// tests/rwsim/simulator/data/sdh_box.dwc.xml): one physics step while the hand closes on the box,
// and whole grasp trials (VisGraB's SDH_CYL pre-shape, hand pointing down at the box centre).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>

#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/control/pd_controller.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "sdh_box_trial.hpp"

namespace {

using rw::math::Transform3D;
namespace sim = rwsim::simulator;

// The scene's state with the hand at qOpen and its SDHTCP at the grasp pose.
rw::kinematics::State placedHand(const sim::GraspParameters& g) {
  const auto& dwc = visgrab::bench::sdhBoxScene();
  const auto& tree = dwc.workcell().frames();
  const auto& hand = *dwc.device(dwc.findDevice("SchunkHand")).device;
  rw::kinematics::State state = dwc.workcell().defaultState();
  hand.setQ(g.qOpen, state);
  const auto base = hand.base();
  const Transform3D X_W_base =
      g.X_W_tcp * rw::kinematics::relativeTransform(
                      tree, state, dwc.workcell().findFrame("SchunkHand.SDHTCP"), base);
  const Transform3D X_W_parent = rw::kinematics::worldTransform(tree, state, state.parentOf(base));
  tree.frame(base).setMovableTransform(state, X_W_parent.inverse() * X_W_base);
  return state;
}

void BM_Sim_SdhStep(benchmark::State& state) {
  const auto& dwc = visgrab::bench::sdhBoxScene();
  const auto hand = dwc.findDevice("SchunkHand");
  const auto g = visgrab::bench::sdhCylinderGrasp(0.0);
  const auto start = placedHand(g);
  sim::Simulator simulator(dwc, sim::optionsFromEngineProperties(dwc));
  const auto* pdParams = dwc.findController("GraspController");
  rwsim::control::PDController pd(pdParams->p, pdParams->d);
  const auto restart = [&] {
    simulator.reset(start);
    simulator.setMotorForceLimits(hand, g.tauMax);
    pd.reset(g.qOpen);
    pd.setTarget(g.qClosed);
  };
  restart();
  std::size_t contacts = 0;
  std::int64_t steps = 0;
  for (auto _ : state) {
    if (simulator.time() > 0.8) {  // closed and pressing for a while: start over
      state.PauseTiming();
      restart();
      state.ResumeTiming();
    }
    const double dt = simulator.options().timeStep;
    simulator.setMotorVelocityTargets(hand, pd.update(simulator.jointPositions(hand), dt));
    benchmark::DoNotOptimize(simulator.step());
    for (const auto& bc : simulator.contacts()) contacts += bc.points.size();
    ++steps;
  }
  state.counters["contacts/step"] = static_cast<double>(contacts) / static_cast<double>(steps);
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Sim_SdhStep)->Unit(benchmark::kMicrosecond);

void runTrials(benchmark::State& state, bool computeGws) {
  const auto& dwc = visgrab::bench::sdhBoxScene();
  sim::GraspTrialSetup setup;
  setup.hand = "SchunkHand";
  setup.tcpFrame = "SchunkHand.SDHTCP";
  setup.simulator = sim::optionsFromEngineProperties(dwc);
  setup.computeGws = computeGws;
  // Per step: the solver's constraint rows and the contact points on the hand and elsewhere.
  double rows = 0.0;
  double handPoints = 0.0;
  double otherPoints = 0.0;
  double separated = 0.0;
  std::int64_t steps = 0;
  const sim::GraspTrial* running = nullptr;
  setup.observer = [&](const rwsim::trial::PhysicsEngine& engine, std::string_view) {
    const auto& s = dynamic_cast<const sim::Simulator&>(engine);
    rows += static_cast<double>(s.lastStepRows());
    for (const auto& bc : s.contacts()) {
      const bool hand = running->isHandBody(bc.bodyA) || running->isHandBody(bc.bodyB);
      (hand ? handPoints : otherPoints) += static_cast<double>(bc.points.size());
      for (const auto& p : bc.points) separated += p.point.depth < 0.0 ? 1.0 : 0.0;
    }
    ++steps;
  };
  const sim::GraspTrial trial(dwc, setup);
  running = &trial;
  const auto initial = dwc.workcell().defaultState();
  std::int64_t trials = 0;
  double simulated = 0.0;
  int stable = 0;
  for (auto _ : state) {
    // Three poses a few millimetres apart so the runs are not all the same.
    const auto result = trial.run(
        visgrab::bench::sdhCylinderGrasp(0.002 * static_cast<double>(trials % 3)), initial);
    simulated += result.simulatedTime;
    stable += result.outcome == sim::GraspOutcome::kStable ? 1 : 0;
    ++trials;
  }
  state.counters["trials/s"] =
      benchmark::Counter(static_cast<double>(trials), benchmark::Counter::kIsRate);
  state.counters["sim s/trial"] = simulated / static_cast<double>(trials);
  state.counters["stable"] = static_cast<double>(stable) / static_cast<double>(trials);
  const double perStep = 1.0 / static_cast<double>(std::max<std::int64_t>(steps, 1));
  state.counters["rows/step"] = rows * perStep;
  state.counters["hand pts/step"] = handPoints * perStep;
  state.counters["other pts/step"] = otherPoints * perStep;
  state.counters["separated pts/step"] = separated * perStep;
}

void BM_Sim_SdhGraspTrial(benchmark::State& state) { runTrials(state, true); }
BENCHMARK(BM_Sim_SdhGraspTrial)->Unit(benchmark::kMillisecond);

void BM_Sim_SdhGraspTrialWithoutGws(benchmark::State& state) { runTrials(state, false); }
BENCHMARK(BM_Sim_SdhGraspTrialWithoutGws)->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
