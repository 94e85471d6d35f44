// What each file beside a generated scene's images costs to make (docs/database-format.md): the
// disparity (StereoSGBM with the default options) and its PNG, the point cloud, the depth and
// mask PNGs and the poses, on a plain and a textured scene ($VISGRAB_BENCH_DB, else generated
// at start-up). PNGs are encoded as writeImageAtomically does for them (disparity and mask
// PngCompression::kRle, depth kBest), without the disk.
#include <benchmark/benchmark.h>

#include <opencv2/imgcodecs.hpp>

#include "bench_database.hpp"
#include "visgrab/generator/scene_products.hpp"
#include "visgrab/vision/stereo.hpp"

namespace {

namespace db = visgrab::database;
namespace gen = visgrab::generator;

const std::vector<std::string> kScenes = {"plain/single/cocacola/01",
                                          "textured/double/burti_denkmit/05"};

visgrab::bench::BenchDatabase& benchDatabase() {
  static visgrab::bench::BenchDatabase database(kScenes);
  return database;
}

struct Scene {
  cv::Mat left, right, disparity;
  db::StereoCalibration calibration;
  visgrab::render::RenderResult truth;
  std::vector<gen::TruthObject> objects;
};

// The scene's images and calibration; the ground-truth render rebuilt from depth.png and
// mask.png (the encoders see the same values as in the generator).
const Scene& scene(std::size_t i) {
  static std::vector<Scene> scenes = [] {
    std::vector<Scene> out;
    const db::Database& database = benchDatabase().db();
    for (const auto& id : kScenes) {
      Scene s;
      s.left = database.leftImage(id);
      s.right = database.rightImage(id);
      s.calibration = database.calibration(id);
      s.disparity = visgrab::vision::computeDisparity(s.left, s.right, s.calibration,
                                                      visgrab::vision::StereoOptions{});
      const cv::Mat depth = database.depthImage(id);
      const cv::Mat mask = database.instanceMask(id);
      auto& t = s.truth;
      t.depth = {depth.cols, depth.rows, {}};
      t.instanceIds = {mask.cols, mask.rows, {}};
      for (int r = 0; r < depth.rows; ++r) {
        for (int c = 0; c < depth.cols; ++c) {
          const float z = depth.at<float>(r, c);
          t.depth.values.push_back(z > 0 ? z : std::numeric_limits<float>::infinity());
          const std::uint8_t m = mask.at<std::uint8_t>(r, c);
          t.instanceIds.values.push_back(m == 0 ? 0 : m == 255 ? 1 : 10 + m);
        }
      }
      for (const auto& o : database.groundTruth(id)) {
        s.objects.push_back({o.object, std::string(db::objectName(o.object)),
                             static_cast<std::uint16_t>(10 + o.object), o.X_WO});
      }
      out.push_back(std::move(s));
    }
    return out;
  }();
  return scenes.at(i);
}

std::size_t png(const cv::Mat& image, bool rle) {
  std::vector<uchar> bytes;
  std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, 9};
  if (rle) params.insert(params.end(), {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE});
  cv::imencode(".png", image, bytes, params);
  return bytes.size();
}

void BM_SceneProducts_Disparity(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(visgrab::vision::computeDisparity(s.left, s.right, s.calibration,
                                                               visgrab::vision::StereoOptions{}));
  }
}

void BM_SceneProducts_DisparityPng(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) bytes = png(gen::encodeDisparity(s.disparity), true);
  state.counters["bytes"] = static_cast<double>(bytes);
}

void BM_SceneProducts_PointCloud(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) {
    bytes = db::pointCloudToPly(gen::cloudFromDisparity(s.disparity, s.left, s.calibration)).size();
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}

void BM_SceneProducts_DepthPng(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) bytes = png(gen::encodeDepth(s.truth.depth), false);
  state.counters["bytes"] = static_cast<double>(bytes);
}

void BM_SceneProducts_MaskPng(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state)
    bytes = png(gen::encodeInstanceMask(s.truth.instanceIds, 1, s.objects), true);
  state.counters["bytes"] = static_cast<double>(bytes);
}

void BM_SceneProducts_Poses(benchmark::State& state) {
  const Scene& s = scene(static_cast<std::size_t>(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) bytes = gen::posesYaml(s.calibration, s.objects).size();
  state.counters["bytes"] = static_cast<double>(bytes);
}

// Argument 0: the plain scene, 1: the textured pair.
BENCHMARK(BM_SceneProducts_Disparity)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SceneProducts_DisparityPng)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SceneProducts_PointCloud)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SceneProducts_DepthPng)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SceneProducts_MaskPng)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SceneProducts_Poses)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
