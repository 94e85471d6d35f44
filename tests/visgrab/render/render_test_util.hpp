#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "rw/math/types.hpp"
#include "visgrab/render/camera.hpp"
#include "visgrab/visual/visual_mesh.hpp"

/// Scenes and independent geometry for the renderer's tests (the tests' own arithmetic, not the
/// renderer's).
namespace visgrab::render::test {

/// A box centred at its frame's origin, 24 vertices with face normals, CCW from outside.
inline std::shared_ptr<visual::VisualMesh> makeBox(const Eigen::Vector3f& halfExtents) {
  auto mesh = std::make_shared<visual::VisualMesh>();
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      n[axis] = sign;
      // Two tangents with t1 x t2 = n, so the corners below run CCW seen from outside.
      const Eigen::Vector3f t1 = Eigen::Vector3f::Unit((axis + 1) % 3) * sign;
      const Eigen::Vector3f t2 = n.cross(t1);
      const auto base = static_cast<std::uint32_t>(mesh->positions.size());
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        const Eigen::Vector3f p = n + c[0] * t1 + c[1] * t2;
        mesh->positions.push_back(p.cwiseProduct(halfExtents));
        mesh->normals.push_back(n);
        mesh->uvs.emplace_back(0.5f * (c[0] + 1.0f), 0.5f * (1.0f - c[1]));
      }
      mesh->triangles.push_back({base, base + 1, base + 2});
      mesh->triangles.push_back({base, base + 2, base + 3});
    }
  }
  return mesh;
}

/// A square of side `side` in its frame's xy plane, normal +z, CCW seen from +z.
/// uv (0, 0) at (-h, +h), (1, 1) at (+h, -h): the texture's top row is at +y.
inline std::shared_ptr<visual::VisualMesh> makeSquare(float side) {
  auto mesh = std::make_shared<visual::VisualMesh>();
  const float h = side / 2.0f;
  mesh->positions = {{-h, -h, 0.0f}, {h, -h, 0.0f}, {h, h, 0.0f}, {-h, h, 0.0f}};
  mesh->normals.assign(4, Eigen::Vector3f::UnitZ());
  mesh->uvs = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

/// A disc of `radius` in its frame's xy plane, normal +z, a fan of `segments` triangles.
inline std::shared_ptr<visual::VisualMesh> makeDisc(float radius, int segments) {
  auto mesh = std::make_shared<visual::VisualMesh>();
  mesh->positions.emplace_back(0.0f, 0.0f, 0.0f);
  for (int i = 0; i < segments; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / segments;
    mesh->positions.emplace_back(static_cast<float>(radius * std::cos(a)),
                                 static_cast<float>(radius * std::sin(a)), 0.0f);
  }
  mesh->normals.assign(mesh->positions.size(), Eigen::Vector3f::UnitZ());
  for (int i = 0; i < segments; ++i) {
    mesh->triangles.push_back(
        {0, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % segments)});
  }
  return mesh;
}

/// A camera pose at `eye` looking at `target`, world z up: x right, y down, z forward.
inline rw::math::Transform3D lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  rw::math::Rotation3D R;
  R << x, y, z;
  return rw::math::makeTransform(R, eye);
}

/// An 800x600 camera with an off-centre principal point.
inline PinholeCamera testCamera() {
  PinholeCamera camera;
  camera.width = 800;
  camera.height = 600;
  camera.fx = 700.0;
  camera.fy = 690.0;
  camera.cx = 405.3;
  camera.cy = 297.8;
  camera.near = 0.05;
  camera.far = 20.0;
  camera.X_WC = lookAt({0.3, -1.8, 1.2}, {0.0, 0.0, 0.0});
  return camera;
}

/// OpenCV's projection, written out: u = fx x/z + s y/z + cx, v = fy y/z + cy.
inline Eigen::Vector2d projectOpenCv(const PinholeCamera& c, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d p = c.X_WC.inverse() * p_W;
  return {c.fx * p.x() / p.z() + c.skew * p.y() / p.z() + c.cx, c.fy * p.y() / p.z() + c.cy};
}

/// Convex hull (Andrew's monotone chain), counter-clockwise in (u, v).
inline std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

/// True if `p` is inside the counter-clockwise convex polygon.
inline bool insideConvex(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    if ((b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x()) < 0) return false;
  }
  return true;
}

/// The 8 corners of a box of `halfExtents` at pose X_WM, in the world.
inline std::vector<Eigen::Vector3d> boxCorners(const rw::math::Transform3D& X_WM,
                                               const Eigen::Vector3d& halfExtents) {
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d local((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    corners.push_back(X_WM * local.cwiseProduct(halfExtents));
  }
  return corners;
}

/// Camera z where the ray through pixel centre (u, v) = (col, row) first enters the box, or
/// +infinity if it misses (slab method in the box frame).
inline double rayBoxDepth(const PinholeCamera& c, int row, int col,
                          const rw::math::Transform3D& X_WM, const Eigen::Vector3d& halfExtents) {
  // Ray in camera frame: p(t) = t * d with d.z = 1, so the parameter t is the camera z.
  const double v = row;
  const double y = (v - c.cy) / c.fy;
  const Eigen::Vector3d d_C((col - c.cx - c.skew * y) / c.fx, y, 1.0);
  const rw::math::Transform3D X_MC = X_WM.inverse() * c.X_WC;
  const Eigen::Vector3d o = X_MC.translation();
  const Eigen::Vector3d d = X_MC.linear() * d_C;
  double enter = -std::numeric_limits<double>::infinity();
  double leave = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-15) {
      if (std::abs(o[k]) > halfExtents[k]) return std::numeric_limits<double>::infinity();
      continue;
    }
    double t1 = (-halfExtents[k] - o[k]) / d[k];
    double t2 = (halfExtents[k] - o[k]) / d[k];
    if (t1 > t2) std::swap(t1, t2);
    enter = std::max(enter, t1);
    leave = std::min(leave, t2);
  }
  if (enter > leave || enter <= 0.0) return std::numeric_limits<double>::infinity();
  return enter;
}

/// sRGB 8-bit value to linear [0, 1] (IEC 61966-2-1).
inline double srgbToLinear(std::uint8_t value) {
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// Linear [0, 1] to an sRGB 8-bit value.
inline int linearToSrgb(double c) {
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255.0 * std::clamp(s, 0.0, 1.0)));
}

/// The colour at image row `row`, column `col`.
inline Eigen::Vector3i pixel(const visual::RgbImage& image, int row, int col) {
  const std::size_t i = (static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width) +
                         static_cast<std::size_t>(col)) *
                        3;
  return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
}

}  // namespace visgrab::render::test
