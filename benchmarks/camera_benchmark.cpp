// The camera model's image steps per camera and scene (docs/database-format.md, "Camera
// profiles"): building the rig's maps (once per generation), the raw image from a render
// (blur, lens warp, vignetting, exposure, mosaic, noise) and the rectification (demosaic,
// undistort + rectify), for the shipped profiles; synthetic renders of the right size.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "visgrab/generator/camera_model.hpp"

namespace {

namespace gen = visgrab::generator;

gen::CameraProfile profile(const std::string& name) {
  return gen::loadCameraProfile(std::filesystem::path(VISGRAB_SOURCE_DIR) / "scenes/cameras" /
                                (name + ".xml"));
}

visgrab::visual::RgbImage syntheticRender(const visgrab::render::PinholeCamera& camera) {
  visgrab::visual::RgbImage image;
  image.width = camera.width;
  image.height = camera.height;
  gen::Random random(1);
  image.pixels.resize(static_cast<std::size_t>(image.width) *
                      static_cast<std::size_t>(image.height) * 3);
  for (auto& p : image.pixels) p = static_cast<std::uint8_t>(64 + random.next() % 128);
  return image;
}

void BM_Camera_RigMaps(benchmark::State& state) {
  const gen::CameraProfile p = profile("realistic");
  for (auto _ : state) {
    const gen::CameraRig rig(p);
    benchmark::DoNotOptimize(rig.calibration());
  }
}
BENCHMARK(BM_Camera_RigMaps)->Unit(benchmark::kMillisecond);

void BM_Camera_RawImage(benchmark::State& state, const std::string& name) {
  const gen::CameraRig rig(profile(name));
  const auto render = syntheticRender(rig.renderCamera(0));
  for (auto _ : state) {
    gen::Random noise(7, "raw");
    benchmark::DoNotOptimize(rig.rawImage(0, render, noise));
  }
}
BENCHMARK_CAPTURE(BM_Camera_RawImage, ideal, std::string("ideal"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Camera_RawImage, realistic, std::string("realistic"))
    ->Unit(benchmark::kMillisecond);

void BM_Camera_Rectify(benchmark::State& state, const std::string& name) {
  const gen::CameraRig rig(profile(name));
  gen::Random noise(7, "raw");
  const cv::Mat raw = rig.rawImage(0, syntheticRender(rig.renderCamera(0)), noise);
  for (auto _ : state) benchmark::DoNotOptimize(rig.rectify(0, raw));
}
BENCHMARK_CAPTURE(BM_Camera_Rectify, ideal, std::string("ideal"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Camera_Rectify, realistic, std::string("realistic"))
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
