#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#include "rw/loaders/workcell_loader.hpp"
#include "rw/proximity/collision_detector.hpp"
#include "rw/proximity/distance_calculator.hpp"

namespace {

// The project's SDH over a 6x6x10 cm box on a table (benchmarks/data/sdh_box.wc.xml), loaded
// once; the hand at the open cylinder pre-shape, its fingers a few centimetres from the box.
class SdhBoxFixture : public benchmark::Fixture {
 public:
  void SetUp(const benchmark::State&) override {
    if (wc_) return;
    wc_ = rw::loaders::loadWorkCell(std::filesystem::path(VISGRAB_SOURCE_DIR) /
                                    "benchmarks/data/sdh_box.wc.xml");
    detector_ = std::make_unique<rw::proximity::CollisionDetector>(*wc_);
    distances_ = std::make_unique<rw::proximity::DistanceCalculator>(*wc_);
    state_ = std::make_unique<rw::kinematics::State>(wc_->defaultState());
    const auto& hand = *wc_->findDevice("SchunkHand");
    rw::math::Q q(7);
    q << -1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174;  // SDH_CYL open (reference §7.1)
    hand.setQ(q, *state_);
  }

 protected:
  static std::unique_ptr<rw::models::WorkCell> wc_;
  static std::unique_ptr<rw::proximity::CollisionDetector> detector_;
  static std::unique_ptr<rw::proximity::DistanceCalculator> distances_;
  static std::unique_ptr<rw::kinematics::State> state_;
};

std::unique_ptr<rw::models::WorkCell> SdhBoxFixture::wc_;
std::unique_ptr<rw::proximity::CollisionDetector> SdhBoxFixture::detector_;
std::unique_ptr<rw::proximity::DistanceCalculator> SdhBoxFixture::distances_;
std::unique_ptr<rw::kinematics::State> SdhBoxFixture::state_;

// Is anything in collision? Nothing is, so every filtered frame pair is checked.
BENCHMARK_F(SdhBoxFixture, BM_Proximity_SdhVsBoxInCollision)(benchmark::State& st) {
  const rw::kinematics::FKTable fk(wc_->frames(), *state_);
  bool colliding = false;
  for (auto _ : st) {
    colliding = detector_->inCollision(fk);
    benchmark::DoNotOptimize(colliding);
  }
  st.counters["pairs"] = static_cast<double>(detector_->checkedPairs().size());
  st.counters["colliding"] = colliding ? 1 : 0;
}

// All colliding pairs, FK included (what an initial-collision check of a grasp costs).
BENCHMARK_F(SdhBoxFixture, BM_Proximity_SdhVsBoxCollidingPairs)(benchmark::State& st) {
  for (auto _ : st) benchmark::DoNotOptimize(detector_->collidingPairs(*state_));
}

// Distances of all filtered pairs.
BENCHMARK_F(SdhBoxFixture, BM_Proximity_SdhVsBoxDistances)(benchmark::State& st) {
  const rw::kinematics::FKTable fk(wc_->frames(), *state_);
  for (auto _ : st) benchmark::DoNotOptimize(distances_->distances(fk));
}

}  // namespace

BENCHMARK_MAIN();
