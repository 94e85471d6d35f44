#include "visgrab/render/camera.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace visgrab::render {

Eigen::Matrix3d PinholeCamera::K() const {
  Eigen::Matrix3d k;
  k << fx, skew, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return k;
}

Eigen::Vector2d PinholeCamera::project(const rw::math::Vector3D& p_W) const {
  const rw::math::Vector3D p_C = X_WC.inverse() * p_W;
  return {fx * p_C.x() / p_C.z() + skew * p_C.y() / p_C.z() + cx, fy * p_C.y() / p_C.z() + cy};
}

void PinholeCamera::validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("PinholeCamera: " + what);
  };
  if (width <= 0 || height <= 0) {
    fail("image size " + std::to_string(width) + "x" + std::to_string(height) +
         " must be positive");
  }
  for (double value : {fx, fy, cx, cy, skew, near, far}) {
    if (!std::isfinite(value)) fail("parameters must be finite");
  }
  if (fx <= 0.0 || fy <= 0.0) fail("focal lengths fx, fy must be positive");
  if (near <= 0.0 || far <= near) {
    fail("clipping distances need 0 < near < far (near " + std::to_string(near) + ", far " +
         std::to_string(far) + ")");
  }
  if (!X_WC.matrix().allFinite()) fail("pose X_WC must be finite");
}

Eigen::Matrix4d glProjection(const PinholeCamera& camera) {
  // Window x of pixel column j's centre is j + 0.5, so u maps to x_win = u + 0.5 and
  // x_ndc = 2 (u + 0.5) / W - 1. Window y runs upwards: image row i's centre is at
  // y_win = H - (v + 0.5), so y_ndc = 1 - 2 (v + 0.5) / H. Multiplying by w = z gives rows that
  // are linear in (x, y, z).
  const double w = camera.width;
  const double h = camera.height;
  const double n = camera.near;
  const double f = camera.far;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2.0 * camera.fx / w;
  P(0, 1) = 2.0 * camera.skew / w;
  P(0, 2) = 2.0 * (camera.cx + 0.5) / w - 1.0;
  P(1, 1) = -2.0 * camera.fy / h;
  P(1, 2) = 1.0 - 2.0 * (camera.cy + 0.5) / h;
  P(2, 2) = (f + n) / (f - n);
  P(2, 3) = -2.0 * f * n / (f - n);
  P(3, 2) = 1.0;
  return P;
}

}  // namespace visgrab::render
