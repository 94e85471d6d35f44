// Ferrari-Canny L1 epsilon (6-D Qhull hull) for typical contact counts. Contacts lie on a 5 cm
// sphere and push towards its centre, mu = 0.6, RobWork's 10 cone edges: 30 and 100 points.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "rw/graspplanning/grasp_wrench_space.hpp"

namespace {

using rw::graspplanning::Contact3D;
using rw::math::Vector3D;

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

void runEpsilon(benchmark::State& state, const std::vector<Contact3D>& contacts) {
  int facets = 0;
  for (auto _ : state) {
    const auto result = rw::graspplanning::gwsEpsilon(contacts, Vector3D::Zero(), kRadius);
    benchmark::DoNotOptimize(result.epsilon);
    facets = result.facets;
  }
  state.counters["facets"] = facets;
}

void BM_Gws_Epsilon3Contacts(benchmark::State& state) { runEpsilon(state, threeFingerGrasp()); }
BENCHMARK(BM_Gws_Epsilon3Contacts)->Unit(benchmark::kMillisecond);

void BM_Gws_Epsilon10Contacts(benchmark::State& state) { runEpsilon(state, randomGrasp(10)); }
BENCHMARK(BM_Gws_Epsilon10Contacts)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
