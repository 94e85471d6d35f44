#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"

namespace {

// The project's SDH, loaded once.
class SdhFixture : public benchmark::Fixture {
 public:
  void SetUp(const benchmark::State&) override {
    if (!wc_) {
      wc_ = rw::loaders::loadWorkCell(std::filesystem::path(VISGRAB_SOURCE_DIR) /
                                      "scenes/hands/sdh/sdh.wc.xml");
    }
  }

 protected:
  static std::unique_ptr<rw::models::WorkCell> wc_;
};

std::unique_ptr<rw::models::WorkCell> SdhFixture::wc_;

// All frame poses of the SDH for a new configuration (what a simulator step needs).
BENCHMARK_F(SdhFixture, BM_Kinematics_SdhFkTable)(benchmark::State& st) {
  const auto& device = *wc_->devices().front();
  rw::kinematics::State state = wc_->defaultState();
  rw::math::Q q = rw::math::Q::Zero(device.dof());
  double t = 0;
  for (auto _ : st) {
    t += 1e-3;
    q.setConstant(0.5 * std::sin(t));
    device.setQ(q, state);
    const rw::kinematics::FKTable fk(wc_->frames(), state);
    benchmark::DoNotOptimize(fk.worldTransform(device.ends().back()));
  }
}

// One fingertip pose by walking up the tree.
BENCHMARK_F(SdhFixture, BM_Kinematics_SdhFingertip)(benchmark::State& st) {
  const auto& device = *wc_->devices().front();
  rw::kinematics::State state = wc_->defaultState();
  device.setQ(rw::math::Q::Constant(device.dof(), 0.3), state);
  const auto tip = device.ends().back();
  for (auto _ : st) {
    benchmark::DoNotOptimize(rw::kinematics::worldTransform(wc_->frames(), state, tip));
  }
}

}  // namespace

BENCHMARK_MAIN();
