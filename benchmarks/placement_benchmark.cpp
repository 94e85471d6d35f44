// The collision-aware placement of contact grasps (visgrab/grasp/placement.hpp) on the simulator
// tests' scene (tests/rwsim/simulator/data/sdh_box.dwc.xml: the SDH over a 6 x 6 x 10 cm box on
// a table): a grasp whose IK placement is free (one scene test), one the search moves, and one
// without a free placement (every candidate tested: the worst case for three contacts).
#include <benchmark/benchmark.h>

#include <memory>
#include <optional>
#include <stdexcept>

#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"

namespace {

using rw::math::Vector3D;
using visgrab::grasp::DesiredContact;
namespace sim = rwsim::simulator;

struct Fixture {
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc;
  std::unique_ptr<visgrab::grasp::HandGraspSetup> hand;
  std::unique_ptr<sim::GraspTrial> trial;
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture out;
    out.dwc = rwsim::loaders::loadDynamicWorkCell(std::string(VISGRAB_SOURCE_DIR) +
                                                  "/tests/rwsim/simulator/data/sdh_box.dwc.xml");
    out.hand = visgrab::grasp::loadHandGraspSetup(std::string(VISGRAB_SOURCE_DIR) +
                                                  "/scenes/hands/sdh/sdh.grasp.xml");
    sim::GraspTrialSetup setup;
    setup.hand = out.hand->deviceName();
    setup.controller = out.hand->controllerName();
    setup.tcpFrame = out.hand->tcpFrameName();
    setup.simulator = sim::optionsFromEngineProperties(*out.dwc);
    out.trial = std::make_unique<sim::GraspTrial>(*out.dwc, setup);
    return out;
  }();
  return f;
}

visgrab::grasp::GraspRequest request(std::vector<DesiredContact> contacts) {
  visgrab::grasp::GraspRequest r;
  r.id = "bench";
  r.kind = visgrab::grasp::GraspKind::kContacts;
  r.contacts = std::move(contacts);
  r.approach = -Vector3D::UnitZ();
  return r;
}

void place(benchmark::State& state, const visgrab::grasp::GraspRequest& r,
           std::optional<visgrab::grasp::ResolveStatus> expected) {
  const Fixture& f = fixture();
  const auto initial = f.dwc->workcell().defaultState();
  const visgrab::grasp::PlacementTest test = [&](const sim::GraspParameters& g) {
    return f.trial->checkPlacement(g, initial);
  };
  int tests = 0;
  for (auto _ : state) {
    const auto resolved = visgrab::grasp::resolve(r, *f.hand, test);
    if (expected && resolved.status != *expected) throw std::logic_error(resolved.message);
    tests = resolved.placement->tests;
    benchmark::DoNotOptimize(resolved.parameters);
  }
  state.counters["scene_tests"] = tests;
}

// Two fingers on the box's sides near its top: the IK's own placement is free.
void BM_Grasp_PlaceFree(benchmark::State& state) {
  place(state,
        request({DesiredContact{{-0.03, 0, 0.09}, {1, 0, 0}},
                 DesiredContact{{0.03, 0, 0.09}, {-1, 0, 0}}}),
        visgrab::grasp::ResolveStatus::kOk);
}
BENCHMARK(BM_Grasp_PlaceFree)->Unit(benchmark::kMillisecond);

// Three fingers at mid-height: the thumb's link touches the box; the search opens it.
void BM_Grasp_PlaceMoved(benchmark::State& state) {
  place(state,
        request({DesiredContact{{-0.03, 0.02, 0.05}, {1, 0, 0}},
                 DesiredContact{{0.03, 0.0, 0.05}, {-1, 0, 0}},
                 DesiredContact{{-0.03, -0.02, 0.05}, {1, 0, 0}}}),
        visgrab::grasp::ResolveStatus::kOk);
}
BENCHMARK(BM_Grasp_PlaceMoved)->Unit(benchmark::kMillisecond);

// The same three contacts through the contact IK alone (no scene): what the placement adds.
void BM_Grasp_IkOnlyMoved(benchmark::State& state) {
  const Fixture& f = fixture();
  const auto r = request({DesiredContact{{-0.03, 0.02, 0.05}, {1, 0, 0}},
                          DesiredContact{{0.03, 0.0, 0.05}, {-1, 0, 0}},
                          DesiredContact{{-0.03, -0.02, 0.05}, {1, 0, 0}}});
  for (auto _ : state) benchmark::DoNotOptimize(visgrab::grasp::resolve(r, *f.hand).parameters);
}
BENCHMARK(BM_Grasp_IkOnlyMoved)->Unit(benchmark::kMillisecond);

// Three fingers 2 cm above the table: no free placement, every candidate is tested.
void BM_Grasp_PlaceNoneFree(benchmark::State& state) {
  place(state,
        request({DesiredContact{{-0.03, 0.02, 0.02}, {1, 0, 0}},
                 DesiredContact{{0.03, 0.0, 0.02}, {-1, 0, 0}},
                 DesiredContact{{-0.03, -0.02, 0.02}, {1, 0, 0}}}),
        visgrab::grasp::ResolveStatus::kInCollision);
}
BENCHMARK(BM_Grasp_PlaceNoneFree)->Unit(benchmark::kMillisecond);

// Two fingers from above on the box 2 cm over the table, the far finger's contact 2 cm inside
// the box (a pinch that guessed a thin wall): many two-contact candidates are tested.
void BM_Grasp_PlacePinchInside(benchmark::State& state) {
  place(state,
        request({DesiredContact{{-0.03, 0, 0.02}, {1, 0, 0}},
                 DesiredContact{{-0.01, 0, 0.02}, {-1, 0, 0}}}),
        std::nullopt);
}
BENCHMARK(BM_Grasp_PlacePinchInside)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
