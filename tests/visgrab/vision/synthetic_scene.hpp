#pragma once
// Organized clouds ray-cast by hand: a camera where the database's rig has its left camera
// (eye (0, -0.5, 0.5) looking at the table frame's origin, fx = fy = 810 at 720x540), a table
// plane and axis-aligned boxes standing on it. Exact geometry, so that the vision's planes,
// clusters, patches and contacts can be checked against numbers worked out by hand.
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "visgrab/vision/stereo.hpp"

namespace visgrab::vision::test {

struct Box {
  Eigen::Vector3d lo, hi;
};

struct SyntheticScene {
  /// Table plane: normal . p = offset.
  Eigen::Vector3d tableNormal = Eigen::Vector3d::UnitZ();
  double tableOffset = 0.0;
  std::vector<Box> boxes;
  /// Standard deviation of Gaussian noise along each ray (m); 0: exact.
  double noise = 0.0;
};

struct Camera {
  Eigen::Vector3d eye{0.0, -0.5, 0.5};
  Eigen::Matrix3d R_TC;  // columns: camera x (right), y (down), z (forward) in the table frame
  double f = 810.0, cx = 359.5, cy = 269.5;
  int width = 720, height = 540;
  Camera() {
    const Eigen::Vector3d z = (Eigen::Vector3d::Zero() - eye).normalized();
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
    R_TC.col(0) = x;
    R_TC.col(1) = z.cross(x);
    R_TC.col(2) = z;
  }
};

inline double hitBox(const Box& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < b.lo[k] || o[k] > b.hi[k]) return std::numeric_limits<double>::infinity();
      continue;
    }
    double a = (b.lo[k] - o[k]) / d[k], c = (b.hi[k] - o[k]) / d[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
  }
  return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
}

/// The cloud the camera sees of `scene`, every `step` pixels, all cells textured.
inline OrganizedCloud rayCast(const SyntheticScene& scene, int step = 2,
                              const Camera& camera = Camera()) {
  OrganizedCloud cloud;
  cloud.step = step;
  cloud.width = (camera.width + step - 1) / step;
  cloud.height = (camera.height + step - 1) / step;
  cloud.viewpoint = camera.eye;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points.assign(static_cast<std::size_t>(cloud.size()), Eigen::Vector3f(nan, nan, nan));
  cloud.textured.assign(static_cast<std::size_t>(cloud.size()), 1);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int r = 0; r < cloud.height; ++r) {
    for (int c = 0; c < cloud.width; ++c) {
      const Eigen::Vector3d ray =
          (camera.R_TC * Eigen::Vector3d((c * step - camera.cx) / camera.f,
                                         (r * step - camera.cy) / camera.f, 1.0))
              .normalized();
      double t = std::numeric_limits<double>::infinity();
      const double denom = scene.tableNormal.dot(ray);
      if (denom < -1e-9) t = (scene.tableOffset - scene.tableNormal.dot(camera.eye)) / denom;
      for (const auto& b : scene.boxes) t = std::min(t, hitBox(b, camera.eye, ray));
      if (!std::isfinite(t) || t > 3.0) continue;
      if (scene.noise > 0.0) t += scene.noise * gauss(rng);
      cloud.points[static_cast<std::size_t>(r * cloud.width + c)] =
          (camera.eye + t * ray).cast<float>();
    }
  }
  return cloud;
}

}  // namespace visgrab::vision::test
