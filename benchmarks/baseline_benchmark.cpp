// The baseline grasp generator's steps on one plain and one textured scene (argument 0 and 1):
// dense stereo and reprojection, segmentation, grasp synthesis, and the whole scene (images read
// from disk, analysis, grasps). The scenes come from the database in $VISGRAB_BENCH_DB when it
// holds them, else from a two-scene database generated into a temporary folder at start-up.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_database.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/vision/baseline.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::database::Database;
using visgrab::vision::BaselineOptions;

// Argument 0: the plain table, 1: the textured one; the same object and pose on both (both are
// in the shared test database too: VISGRAB_BENCH_DB=build/tests/test-database).
constexpr std::array<const char*, 2> kSceneIds = {"plain/single/cocacola/01",
                                                  "textured/single/cocacola/01"};

const Database& benchDatabase() {
  static const visgrab::bench::BenchDatabase database({kSceneIds[0], kSceneIds[1]});
  return database.db();
}

// One scene's inputs and intermediate results, made once.
struct SceneData {
  const visgrab::database::SceneEntry* entry = nullptr;
  cv::Mat left, right;
  visgrab::database::StereoCalibration calibration;
  visgrab::vision::SceneSegmentation segmentation;
};

const SceneData& sceneData(int which) {
  static const std::array<SceneData, 2> data = [] {
    std::array<SceneData, 2> out;
    const BaselineOptions options;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Database& db = benchDatabase();
      out[i].entry = &db.scene(kSceneIds[i]);
      out[i].left = db.leftImage(kSceneIds[i]);
      out[i].right = db.rightImage(kSceneIds[i]);
      out[i].calibration = db.calibration(kSceneIds[i]);
      out[i].segmentation = visgrab::vision::analyzeScene(db, *out[i].entry, options);
    }
    return out;
  }();
  return data[static_cast<std::size_t>(which)];
}

void label(benchmark::State& state, const SceneData& scene) { state.SetLabel(scene.entry->id); }

void BM_Baseline_StereoCloud(benchmark::State& state) {
  const SceneData& scene = sceneData(static_cast<int>(state.range(0)));
  const BaselineOptions options;
  const auto range = visgrab::vision::stereoDisparityRange(scene.calibration, options.stereo);
  int valid = 0;
  for (auto _ : state) {
    const auto cloud =
        visgrab::vision::stereoCloud(scene.left, scene.right, scene.calibration, options.stereo);
    valid = 0;
    for (int i = 0; i < cloud.size(); ++i) valid += cloud.valid(i) ? 1 : 0;
    benchmark::DoNotOptimize(valid);
  }
  label(state, scene);
  state.counters["minDisparity"] = range.minDisparity;
  state.counters["numDisparities"] = range.numDisparities;
  state.counters["points"] = valid;
}

void BM_Baseline_SegmentScene(benchmark::State& state) {
  const SceneData& scene = sceneData(static_cast<int>(state.range(0)));
  const BaselineOptions options;
  for (auto _ : state) {
    state.PauseTiming();
    visgrab::vision::OrganizedCloud cloud = scene.segmentation.cloud;
    state.ResumeTiming();
    const auto s = visgrab::vision::segmentScene(std::move(cloud), options.segmentation);
    benchmark::DoNotOptimize(s.patches.data());
  }
  label(state, scene);
  state.counters["clusters"] = static_cast<double>(scene.segmentation.clusters.size());
  state.counters["patches"] = static_cast<double>(scene.segmentation.patches.size());
}

void BM_Baseline_GenerateGrasps(benchmark::State& state) {
  const SceneData& scene = sceneData(static_cast<int>(state.range(0)));
  const BaselineOptions options;
  std::size_t grasps = 0;
  for (auto _ : state) {
    const auto g = visgrab::vision::generateGrasps(scene.segmentation, options.grasps);
    grasps = g.size();
    benchmark::DoNotOptimize(g.data());
  }
  label(state, scene);
  state.counters["grasps"] = static_cast<double>(grasps);
}

// What `visgrab baseline` does per scene: read the images and calibration, analyse, make grasps.
void BM_Baseline_Scene(benchmark::State& state) {
  const SceneData& scene = sceneData(static_cast<int>(state.range(0)));
  const Database& db = benchDatabase();
  const BaselineOptions options;
  for (auto _ : state) {
    const auto s = visgrab::vision::analyzeScene(db, *scene.entry, options);
    const auto g = visgrab::vision::generateGrasps(s, options.grasps);
    benchmark::DoNotOptimize(g.data());
  }
  label(state, scene);
}

// Process CPU time: OpenCV's SGBM runs in its own worker threads.
BENCHMARK(BM_Baseline_StereoCloud)
    ->Arg(0)
    ->Arg(1)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Baseline_SegmentScene)
    ->Arg(0)
    ->Arg(1)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Baseline_GenerateGrasps)
    ->Arg(0)
    ->Arg(1)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Baseline_Scene)
    ->Arg(0)
    ->Arg(1)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
