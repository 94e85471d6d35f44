// Ferrari-Canny L1 epsilon (6-D Qhull hull). Synthetic: contacts on a 5 cm sphere pushing towards
// its centre, mu = 0.6, RobWork's 10 cone edges (30 and 100 points). Real: the contact sets after
// lifting of 18 SDH grasp trials on the simulator tests' box (tests/rwsim/simulator/data),
// recorded once at start-up (about 2 s), timed with both trial columns (Q_GWS, Q_GWS,unit) as a
// trial computes them, with whole hulls, and with the unit column alone as trials did before.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "rw/graspplanning/grasp_wrench_space.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_quality.hpp"
#include "rwsim/simulator/grasp_trial.hpp"

namespace {

using rw::graspplanning::Contact3D;
using rw::math::Q;
using rw::math::Vector3D;
namespace sim = rwsim::simulator;

constexpr double kRadius = 0.05;

Contact3D sphereContact(const Vector3D& direction) {
  Contact3D c;
  c.position = kRadius * direction.normalized();
  c.normal = -direction.normalized();
  c.mu = 0.6;
  return c;
}

std::vector<Contact3D> threeFingerGrasp() {
  std::vector<Contact3D> contacts;
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 3.0;
    contacts.push_back(sphereContact(Vector3D(std::cos(a), std::sin(a), 0.1)));
  }
  return contacts;
}

std::vector<Contact3D> randomGrasp(int count) {
  std::mt19937 rng(42);
  std::normal_distribution<double> gauss;
  std::vector<Contact3D> contacts;
  for (int i = 0; i < count; ++i) {
    contacts.push_back(sphereContact(Vector3D(gauss(rng), gauss(rng), gauss(rng))));
  }
  return contacts;
}

void runEpsilon(benchmark::State& state, const std::vector<Contact3D>& contacts,
                rw::graspplanning::GwsHull hull = rw::graspplanning::GwsHull::kLazy) {
  rw::graspplanning::GwsOptions options;
  options.hull = hull;
  int facets = 0;
  for (auto _ : state) {
    const auto result = rw::graspplanning::gwsEpsilon(contacts, Vector3D::Zero(), kRadius, options);
    benchmark::DoNotOptimize(result.epsilon);
    facets = result.facets;
  }
  state.counters["facets"] = facets;
}

void BM_Gws_Epsilon3Contacts(benchmark::State& state) { runEpsilon(state, threeFingerGrasp()); }
BENCHMARK(BM_Gws_Epsilon3Contacts)->Unit(benchmark::kMillisecond);

void BM_Gws_Epsilon10Contacts(benchmark::State& state) { runEpsilon(state, randomGrasp(10)); }
BENCHMARK(BM_Gws_Epsilon10Contacts)->Unit(benchmark::kMillisecond);

void BM_Gws_Epsilon10ContactsWholeHull(benchmark::State& state) {
  runEpsilon(state, randomGrasp(10), rw::graspplanning::GwsHull::kWhole);
}
BENCHMARK(BM_Gws_Epsilon10ContactsWholeHull)->Unit(benchmark::kMillisecond);

// ---- contact sets of real trials ----

struct HeldGrasp {
  std::vector<sim::TrialContact> contacts;
  Vector3D cog;
  double r = 0.0;
};

const rwsim::dynamics::DynamicWorkCell& boxScene() {
  static const auto dwc = rwsim::loaders::loadDynamicWorkCell(
      std::string(VISGRAB_SOURCE_DIR) + "/tests/rwsim/simulator/data/sdh_box.dwc.xml");
  return *dwc;
}

// The SDH pointing down at the box's top centre, turned by `yaw` about z and moved by dx along x.
sim::GraspParameters sdhGrasp(bool parallel, double dx, double yaw) {
  sim::GraspParameters g;
  g.X_W_tcp = rw::math::rpyTransform(Vector3D(yaw, std::numbers::pi, 0), Vector3D(dx, 0, 0.05));
  g.qOpen = Q(7);
  g.qClosed = Q(7);
  if (parallel) {  // SDH_PAR: two fingers facing each other
    g.qOpen << -1.571, -1.571, 1.571, -1.048, 0.174, -1.048, 0.174;
    g.qClosed << -1.571, -1.571, 1.571, 0.0, 0.419, 0.0, 0.419;
  } else {  // SDH_CYL
    g.qOpen << -1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174;
    g.qClosed << 0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349;
  }
  g.tauMax = Q(7);
  g.tauMax << 2.1, 1.4, 2.1, 1.05, 0.7, 1.05, 0.7;
  return g;
}

// Held grasps' contacts of 18 trials (two pre-shapes, three offsets, three turns), recorded once.
const std::vector<HeldGrasp>& heldGrasps() {
  static const std::vector<HeldGrasp> held = [] {
    const auto& dwc = boxScene();
    sim::GraspTrialSetup setup;
    setup.hand = "SchunkHand";
    setup.tcpFrame = "SchunkHand.SDHTCP";
    setup.simulator = sim::optionsFromEngineProperties(dwc);
    setup.computeGws = false;
    const sim::GraspTrial trial(dwc, setup);
    const auto initial = dwc.workcell().defaultState();
    std::vector<HeldGrasp> out;
    for (const bool parallel : {false, true}) {
      for (const double dx : {0.0, 0.004, 0.008}) {
        for (const double yaw : {0.0, 0.5, 1.0}) {
          const auto r = trial.run(sdhGrasp(parallel, dx, yaw), initial);
          if (r.outcome != sim::GraspOutcome::kStable && r.outcome != sim::GraspOutcome::kSlipped) {
            continue;
          }
          const auto& body = dwc.body(r.object);
          // The box is 6 x 6 x 10 cm around its centre of mass.
          out.push_back(
              HeldGrasp{r.contacts, body.mass.cog, std::sqrt(0.03 * 0.03 * 2 + 0.05 * 0.05)});
        }
      }
    }
    return out;
  }();
  return held;
}

// Relative change |lazy - whole| / whole of both columns over the held grasps' contacts
// (0/0 counts as 0): {median, max}.
std::pair<double, double> lazyVsWhole() {
  std::vector<double> changes;
  sim::GwsQualityOptions whole;
  whole.hull = rw::graspplanning::GwsHull::kWhole;
  for (const HeldGrasp& g : heldGrasps()) {
    const auto a = sim::gwsQualities(g.contacts, g.cog, g.r);
    const auto b = sim::gwsQualities(g.contacts, g.cog, g.r, whole);
    for (const auto& [x, y] : {std::pair{a.qGws, b.qGws}, std::pair{a.qGwsUnit, b.qGwsUnit}}) {
      changes.push_back(y != 0.0 ? std::abs(x - y) / y : std::abs(x));
    }
  }
  if (changes.empty()) return {0.0, 0.0};
  std::sort(changes.begin(), changes.end());
  return {changes[changes.size() / 2], changes.back()};
}

// One held grasp's quality per iteration, round robin over the recorded sets.
template <typename Quality>
void runHeld(benchmark::State& state, Quality quality) {
  const auto& held = heldGrasps();
  std::size_t next = 0;
  double contacts = 0.0;
  std::int64_t sets = 0;
  for (auto _ : state) {
    const HeldGrasp& g = held[next];
    next = (next + 1) % held.size();
    benchmark::DoNotOptimize(quality(g));
    contacts += static_cast<double>(g.contacts.size());
    ++sets;
  }
  state.counters["contacts"] = contacts / static_cast<double>(std::max<std::int64_t>(sets, 1));
  state.counters["sets"] = static_cast<double>(held.size());
}

// What a trial computes now: both columns, lazy hulls.
void BM_Gws_TrialQualities(benchmark::State& state) {
  runHeld(state, [](const HeldGrasp& g) { return sim::gwsQualities(g.contacts, g.cog, g.r).qGws; });
  const auto [median, max] = lazyVsWhole();
  state.counters["rel change median"] = median;
  state.counters["rel change max"] = max;
}
BENCHMARK(BM_Gws_TrialQualities)->Unit(benchmark::kMillisecond);

// Both columns with whole hulls (the lazy hull's reference).
void BM_Gws_TrialQualitiesWholeHull(benchmark::State& state) {
  sim::GwsQualityOptions whole;
  whole.hull = rw::graspplanning::GwsHull::kWhole;
  runHeld(state, [&whole](const HeldGrasp& g) {
    return sim::gwsQualities(g.contacts, g.cog, g.r, whole).qGws;
  });
}
BENCHMARK(BM_Gws_TrialQualitiesWholeHull)->Unit(benchmark::kMillisecond);

// What a trial computed before the paper's column: unit forces only, whole hull.
void BM_Gws_TrialUnitOnlyWholeHull(benchmark::State& state) {
  runHeld(state, [](const HeldGrasp& g) {
    const std::vector<Contact3D> c3 = rwsim::simulator::toContacts3D(g.contacts);
    rw::graspplanning::GwsOptions options;
    options.hull = rw::graspplanning::GwsHull::kWhole;
    return rw::graspplanning::gwsEpsilon(c3, g.cog, g.r, options).epsilon;
  });
}
BENCHMARK(BM_Gws_TrialUnitOnlyWholeHull)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
