#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include "visgrab/render/offscreen_renderer.hpp"

namespace {

using visgrab::render::GlRenderer;
using visgrab::render::Light;
using visgrab::render::MeshHandle;
using visgrab::render::OffscreenRenderer;
using visgrab::render::PinholeCamera;
using visgrab::render::RenderOptions;
using visgrab::render::Scene;
using visgrab::visual::RgbImage;
using visgrab::visual::VisualMesh;

/// A procedural texture: stripes and a checker, different per seed.
std::shared_ptr<const RgbImage> makeTexture(int size, int seed) {
  auto image = std::make_shared<RgbImage>();
  image->width = size;
  image->height = size;
  image->pixels.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * 3);
  std::size_t i = 0;
  for (int row = 0; row < size; ++row) {
    for (int col = 0; col < size; ++col) {
      const bool check = ((row / 32) + (col / 32) + seed) % 2 == 0;
      image->pixels[i++] = static_cast<std::uint8_t>(check ? 200 : 40 + 20 * seed);
      image->pixels[i++] = static_cast<std::uint8_t>((row * 3 + seed * 50) % 256);
      image->pixels[i++] = static_cast<std::uint8_t>((col * 5 + seed * 30) % 256);
    }
  }
  return image;
}

/// A textured capsule-like body of revolution (radius r, height h) with about 2 * rings *
/// segments triangles, standing on z = 0.
std::shared_ptr<VisualMesh> makeBody(double r, double h, int rings, int segments, int seed) {
  auto mesh = std::make_shared<VisualMesh>();
  for (int i = 0; i <= rings; ++i) {
    const double t = static_cast<double>(i) / rings;
    const double phi = std::numbers::pi * (t - 0.5);  // -pi/2 .. pi/2 along the profile
    const double ringRadius = r * std::cos(phi);
    const double z = h * t;
    for (int j = 0; j <= segments; ++j) {
      const double a = 2.0 * std::numbers::pi * j / segments;
      mesh->positions.emplace_back(static_cast<float>(ringRadius * std::cos(a)),
                                   static_cast<float>(ringRadius * std::sin(a)),
                                   static_cast<float>(z));
      const Eigen::Vector3d n(std::cos(phi) * std::cos(a), std::cos(phi) * std::sin(a),
                              std::sin(phi));
      mesh->normals.push_back(n.normalized().cast<float>());
      mesh->uvs.emplace_back(static_cast<float>(j) / static_cast<float>(segments),
                             static_cast<float>(1.0 - t));
    }
  }
  const auto stride = static_cast<std::uint32_t>(segments + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(rings); ++i) {
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(segments); ++j) {
      const std::uint32_t a = i * stride + j;
      const std::uint32_t b = a + stride;
      mesh->triangles.push_back({a, a + 1, b + 1});
      mesh->triangles.push_back({a, b + 1, b});
    }
  }
  mesh->colour = Eigen::Vector3f::Ones();
  mesh->specular = 0.3f;
  mesh->texture = makeTexture(512, seed);
  return mesh;
}

std::shared_ptr<VisualMesh> makeTable() {
  auto mesh = std::make_shared<VisualMesh>();
  const float h = 0.6f;
  mesh->positions = {{-h, -h, 0.0f}, {h, -h, 0.0f}, {h, h, 0.0f}, {-h, h, 0.0f}};
  mesh->normals.assign(4, Eigen::Vector3f::UnitZ());
  mesh->uvs = {{0.0f, 4.0f}, {4.0f, 4.0f}, {4.0f, 0.0f}, {0.0f, 0.0f}};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh->texture = makeTexture(1024, 7);
  mesh->specular = 0.05f;
  return mesh;
}

constexpr int kObjects = 10;

/// Ten ~5000-triangle textured objects (50 rings x 50 segments) and a table.
std::vector<std::shared_ptr<VisualMesh>> makeMeshes() {
  std::vector<std::shared_ptr<VisualMesh>> meshes;
  for (int i = 0; i < kObjects; ++i) meshes.push_back(makeBody(0.04, 0.12, 50, 50, i));
  meshes.push_back(makeTable());
  return meshes;
}

/// The database's view: an 800x600 camera 0.9 m from the table, looking down at 50 degrees.
PinholeCamera makeCamera() {
  PinholeCamera camera;
  camera.width = 800;
  camera.height = 600;
  camera.fx = camera.fy = 900.0;
  camera.cx = 399.5;
  camera.cy = 299.5;
  const Eigen::Vector3d eye(0.0, -0.6, 0.7);
  const Eigen::Vector3d z = (-eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R;
  R << x, y, z;
  camera.X_WC = rw::math::makeTransform(R, eye);
  return camera;
}

void BM_Render_Scene800x600(benchmark::State& state) {
  OffscreenRenderer renderer;
  const auto meshes = makeMeshes();
  Scene scene;
  for (int i = 0; i < kObjects; ++i) {
    const MeshHandle handle = renderer.add(meshes[static_cast<std::size_t>(i)]);
    const double x = -0.32 + 0.16 * (i % 5);
    const double y = i < 5 ? -0.1 : 0.12;
    scene.items.push_back(
        {handle, rw::math::makeTranslation({x, y, 0.0}), static_cast<std::uint16_t>(i + 1)});
  }
  scene.items.push_back({renderer.add(meshes.back()), rw::math::Transform3D::Identity(), 0});
  scene.lighting.lights[0].direction_W = {0.3, 0.4, -1.0};
  scene.lighting.lights[0].castsShadows = state.range(0) != 0;
  Light fill;
  fill.type = Light::Type::kPoint;
  fill.position_W = {-1.0, -1.0, 1.5};
  fill.colour = {0.2f, 0.2f, 0.25f};
  scene.lighting.lights.push_back(fill);
  const PinholeCamera camera = makeCamera();
  // shadows:1 draws the shadow map in every render: the light turns by a hair each time (the
  // renderer keeps the map while scene and light stay the same). shadows:2 renders the same
  // scene again and reuses it, as the second image of a stereo pair does.
  const bool turnLight = state.range(0) == 1;
  int frame = 0;
  for (auto _ : state) {
    if (turnLight) scene.lighting.lights[0].direction_W.z() = -1.0 - 1e-9 * (frame++ % 2);
    auto result = renderer.render(scene, camera, RenderOptions{});
    benchmark::DoNotOptimize(result.colour.pixels.data());
  }
  state.counters["triangles"] = kObjects * 5000 + 2;
}
BENCHMARK(BM_Render_Scene800x600)
    ->ArgName("shadows")
    ->Arg(1)
    ->Arg(2)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_Render_Upload(benchmark::State& state) {
  OffscreenRenderer context;
  const auto meshes = makeMeshes();
  for (auto _ : state) {
    state.PauseTiming();
    auto renderer = std::make_unique<GlRenderer>();
    state.ResumeTiming();
    for (const auto& mesh : meshes) benchmark::DoNotOptimize(renderer->add(mesh));
    state.PauseTiming();
    renderer.reset();
    state.ResumeTiming();
  }
  state.counters["meshes"] = static_cast<double>(meshes.size());
}
BENCHMARK(BM_Render_Upload)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
