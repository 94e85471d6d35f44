#include "visgrab/view/cameras.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace visgrab::view {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

constexpr std::array<std::pair<ViewPreset, std::string_view>, 4> kPresetNames{{
    {ViewPreset::kOblique, "oblique"},
    {ViewPreset::kFront, "front"},
    {ViewPreset::kSide, "side"},
    {ViewPreset::kTop, "top"},
}};

}  // namespace

std::string_view viewPresetName(ViewPreset preset) {
  for (const auto& [p, name] : kPresetNames) {
    if (p == preset) return name;
  }
  return "oblique";
}

std::optional<ViewPreset> viewPresetFromName(std::string_view name) {
  for (const auto& [p, n] : kPresetNames) {
    if (n == name) return p;
  }
  return std::nullopt;
}

Orbit presetOrbit(ViewPreset preset) {
  Orbit orbit;
  switch (preset) {
    case ViewPreset::kOblique:
      orbit.azimuthDeg = -125.0;
      orbit.elevationDeg = 35.0;
      break;
    case ViewPreset::kFront:
      orbit.azimuthDeg = -90.0;
      orbit.elevationDeg = 30.0;
      break;
    case ViewPreset::kSide:
      orbit.azimuthDeg = 0.0;
      orbit.elevationDeg = 25.0;
      break;
    case ViewPreset::kTop:
      orbit.azimuthDeg = -90.0;
      orbit.elevationDeg = 89.5;
      break;
  }
  return orbit;
}

render::PinholeCamera orbitCamera(const Orbit& orbit, int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("orbitCamera: the image size must be positive");
  }
  if (!(orbit.distance > 0.0) || !std::isfinite(orbit.distance)) {
    throw std::invalid_argument("orbitCamera: the distance must be positive and finite");
  }
  if (!(orbit.fovYDeg > 0.0 && orbit.fovYDeg < 180.0)) {
    throw std::invalid_argument("orbitCamera: the field of view must be in (0, 180) degrees");
  }
  const double az = orbit.azimuthDeg * kDegree;
  const double el = std::clamp(orbit.elevationDeg, -89.5, 89.5) * kDegree;
  const Eigen::Vector3d out(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const Eigen::Vector3d eye = orbit.target + orbit.distance * out;
  // OpenCV axes: z forward (towards the target), x right (horizontal), y down.
  const Eigen::Vector3d z = -out;
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  render::PinholeCamera camera;
  camera.width = width;
  camera.height = height;
  camera.fy = 0.5 * height / std::tan(0.5 * orbit.fovYDeg * kDegree);
  camera.fx = camera.fy;
  camera.cx = 0.5 * (width - 1);
  camera.cy = 0.5 * (height - 1);
  camera.near = std::max(1e-3, 0.02 * orbit.distance);
  camera.far = 20.0 * orbit.distance + 10.0;
  camera.X_WC = rw::math::Transform3D::Identity();
  camera.X_WC.linear() << x, y, z;
  camera.X_WC.translation() = eye;
  return camera;
}

Orbit framed(Orbit orbit, const Eigen::AlignedBox3d& box, int width, int height, double margin) {
  if (box.isEmpty()) return orbit;
  orbit.target = box.center();
  const double radius = std::max(0.5 * box.diagonal().norm(), 1e-3);
  const double halfY = 0.5 * orbit.fovYDeg * kDegree;
  const double halfX = std::atan(std::tan(halfY) * width / std::max(height, 1));
  orbit.distance = margin * radius / std::sin(std::min(halfX, halfY));
  return orbit;
}

render::Lighting studioLighting() {
  render::Lighting lighting;
  lighting.ambient = Eigen::Vector3f(0.28f, 0.28f, 0.30f);
  lighting.lights.clear();
  render::Light key;
  key.direction_W = Eigen::Vector3d(0.35, 0.55, -1.0);
  key.colour = Eigen::Vector3f(0.75f, 0.74f, 0.70f);
  key.castsShadows = true;
  render::Light fill;
  fill.direction_W = Eigen::Vector3d(-0.8, 0.3, -0.4);
  fill.colour = Eigen::Vector3f(0.22f, 0.23f, 0.26f);
  lighting.lights = {key, fill};
  lighting.shininess = 40.0f;
  return lighting;
}

Eigen::Vector3f studioBackground() { return Eigen::Vector3f(0.78f, 0.82f, 0.88f); }

}  // namespace visgrab::view
