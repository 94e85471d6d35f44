// `visgrab render`'s pictures of a scene with the SDH placed at a grasp around the can of
// plain/single/cocacola/01 (Mesa llvmpipe through EGL, 4x MSAA, shadows): one 800 x 600 picture
// (the budget: 0.5 s on 2 cores), the three 480 x 360 panels of a trial strip without and
// with the trial's replay, and uploading a scene's meshes. The scene comes from $VISGRAB_BENCH_DB
// or is generated at start-up (bench_database.hpp).
#include <benchmark/benchmark.h>

#include <numbers>

#include "bench_database.hpp"
#include "rw/math/rpy.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/render/offscreen_renderer.hpp"
#include "visgrab/view/grasp_pictures.hpp"

namespace {

constexpr const char* kScene = "plain/single/cocacola/01";

struct Fixture {
  visgrab::bench::BenchDatabase database{{kScene}};
  std::unique_ptr<visgrab::grasp::HandGraspSetup> hand = visgrab::grasp::loadHandGraspSetup(
      std::filesystem::path(VISGRAB_SOURCE_DIR) / "scenes/hands/sdh/sdh.grasp.xml");
  visgrab::session::SceneSession session{visgrab::session::SceneLoader(database.db(), *hand),
                                         database.db().scene(kScene)};
  visgrab::session::SceneGrasp grasp;

  Fixture() {
    // SDH_CYL pointing down, its TCP 6 cm above the can's base (a stable grasp).
    const auto base = database.db().groundTruth(kScene).front().X_WO.translation();
    grasp.request.sceneId = kScene;
    grasp.request.id = "bench";
    grasp.request.method = "bench";
    grasp.request.kind = visgrab::grasp::GraspKind::kPreshape;
    grasp.request.preshape = "SDH_CYL";
    grasp.request.X_W_tcp = rw::math::rpyTransform(rw::math::Vector3D(0.0, std::numbers::pi, 0.0),
                                                   base + rw::math::Vector3D(0, 0, 0.06));
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_Picture_Scene800x600(benchmark::State& state) {
  Fixture& f = fixture();
  visgrab::render::OffscreenRenderer offscreen;
  const visgrab::view::WorkcellDrawing drawing(f.session.workcell(), offscreen.renderer(),
                                               f.hand->deviceName());
  const auto resolved = f.session.resolve(f.grasp.request);
  const auto placed = f.session.trial().placedState(resolved.parameters, f.session.initialState());
  visgrab::view::PictureOptions options;
  options.width = 800;
  options.height = 600;
  Eigen::AlignedBox3d box = visgrab::view::objectsBox(f.session, drawing, placed);
  box.extend(drawing.bounds(placed, drawing.handFrames()));
  const auto orbit = visgrab::view::framed(visgrab::view::presetOrbit(options.view), box, 800, 600);
  for (auto _ : state) {
    const auto image =
        visgrab::view::renderState(offscreen.renderer(), drawing, placed, {}, {}, orbit, options);
    benchmark::DoNotOptimize(image.pixels.data());
  }
}
BENCHMARK(BM_Picture_Scene800x600)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Picture_Strip(benchmark::State& state) {
  Fixture& f = fixture();
  visgrab::render::OffscreenRenderer offscreen;
  const visgrab::view::WorkcellDrawing drawing(f.session.workcell(), offscreen.renderer(),
                                               f.hand->deviceName());
  const auto resolved = f.session.resolve(f.grasp.request);
  const auto replay =
      visgrab::view::replayTrial(f.session.trial(), resolved.parameters, f.session.initialState());
  visgrab::view::PictureOptions options;
  options.width = 480;
  options.height = 360;
  for (auto _ : state) {
    const auto image =
        visgrab::view::graspStrip(offscreen.renderer(), drawing, f.session, replay, "x", options);
    benchmark::DoNotOptimize(image.pixels.data());
  }
}
BENCHMARK(BM_Picture_Strip)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Picture_StripWithReplay(benchmark::State& state) {
  Fixture& f = fixture();
  visgrab::render::OffscreenRenderer offscreen;
  const visgrab::view::WorkcellDrawing drawing(f.session.workcell(), offscreen.renderer(),
                                               f.hand->deviceName());
  visgrab::view::PictureOptions options;
  options.width = 480;
  options.height = 360;
  for (auto _ : state) {
    const auto picture =
        visgrab::view::trialStrip(offscreen.renderer(), drawing, f.session, f.grasp, options);
    benchmark::DoNotOptimize(picture.image.pixels.data());
  }
}
BENCHMARK(BM_Picture_StripWithReplay)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Picture_UploadScene(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    visgrab::render::OffscreenRenderer offscreen;
    const visgrab::view::WorkcellDrawing drawing(f.session.workcell(), offscreen.renderer(),
                                                 f.hand->deviceName());
    benchmark::DoNotOptimize(&drawing);
  }
}
BENCHMARK(BM_Picture_UploadScene)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
