#pragma once

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"
#include "rwsim/contacts/contact_detector.hpp"
#include "support/test_support.hpp"

/// Helpers for the contact tests: poses, meshes built in code, and a one-call collide().
namespace rwsim::contacts::test {

using rw::geometry::Geometry;
using rw::geometry::TriMesh;
using rw::math::Transform3D;
using rw::math::Vector3D;

/// Penetration used by the resting-contact tests (m).
inline constexpr double kPen = 1e-4;

/// pi.
inline constexpr double kPi = std::numbers::pi;

/// Expects every point's normal to be `n` (within 1e-9).
inline void expectAllNormals(const std::vector<ContactPoint>& points, const Vector3D& n) {
  for (const ContactPoint& c : points) EXPECT_VECTOR_NEAR(c.normal, n, 1e-9);
}

/// A pose: translation p, then rotation by `angle` about `axis`.
inline Transform3D pose(const Vector3D& p, double angle = 0.0,
                        const Vector3D& axis = Vector3D::UnitZ()) {
  Transform3D X = Transform3D::Identity();
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  X.translation() = p;
  return X;
}

/// Contacts of two geometries (shapes built for the call).
inline std::vector<ContactPoint> contacts(const Geometry& a, const Transform3D& X_W_a,
                                          const Geometry& b, const Transform3D& X_W_b,
                                          const ContactOptions& options = {}) {
  std::vector<ContactPoint> out;
  collide(*ContactShape::build(a), X_W_a, *ContactShape::build(b), X_W_b, options, out);
  return out;
}

/// A geometry from a mesh.
inline std::shared_ptr<const Geometry> meshGeometry(TriMesh mesh) {
  return Geometry::mesh(std::make_shared<const TriMesh>(std::move(mesh)), "test");
}

/// The closed prism over a counter-clockwise polygon (in xy), from z0 to z1.
inline TriMesh prism(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1) {
  TriMesh m;
  const auto n = static_cast<std::uint32_t>(polygon.size());
  for (const double z : {z0, z1}) {
    for (const auto& p : polygon) m.vertices.emplace_back(p.x(), p.y(), z);
  }
  // Caps as fans from the polygon's first vertex work for the L below only when star-shaped
  // from it; callers pass polygons that are.
  for (std::uint32_t k = 1; k + 1 < n; ++k) {
    m.triangles.push_back({0, k + 1, k});
    m.triangles.push_back({n, n + k, n + k + 1});
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t k1 = (k + 1) % n;
    m.triangles.push_back({k, k1, n + k1});
    m.triangles.push_back({k, n + k1, n + k});
  }
  return m;
}

/// A UV sphere of `radius` with `slices` longitudes and `stacks` latitude bands.
inline TriMesh uvSphere(double radius, std::uint32_t slices, std::uint32_t stacks) {
  TriMesh m;
  m.vertices.emplace_back(0, 0, radius);
  for (std::uint32_t k = 1; k < stacks; ++k) {
    const double polar = std::numbers::pi * k / stacks;
    for (std::uint32_t i = 0; i < slices; ++i) {
      const double a = 2.0 * std::numbers::pi * i / slices;
      m.vertices.emplace_back(radius * std::sin(polar) * std::cos(a),
                              radius * std::sin(polar) * std::sin(a), radius * std::cos(polar));
    }
  }
  m.vertices.emplace_back(0, 0, -radius);
  const auto ring = [&](std::uint32_t k, std::uint32_t i) { return 1 + k * slices + i % slices; };
  const auto south = static_cast<std::uint32_t>(m.vertices.size() - 1);
  for (std::uint32_t i = 0; i < slices; ++i) {
    m.triangles.push_back({0, ring(0, i), ring(0, i + 1)});
    for (std::uint32_t k = 0; k + 2 < stacks; ++k) {
      m.triangles.push_back({ring(k, i), ring(k + 1, i), ring(k + 1, i + 1)});
      m.triangles.push_back({ring(k, i), ring(k + 1, i + 1), ring(k, i + 1)});
    }
    m.triangles.push_back({south, ring(stacks - 2, i + 1), ring(stacks - 2, i)});
  }
  return m;
}

/// A closed cylinder mesh along z with `segments` sides (caps as fans from their centres).
inline TriMesh fineCylinder(double radius, double height, std::uint32_t segments) {
  TriMesh m;
  for (const double z : {-height / 2, height / 2}) {
    for (std::uint32_t i = 0; i < segments; ++i) {
      const double a = 2.0 * std::numbers::pi * i / segments;
      m.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    }
  }
  const auto bottom = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(0, 0, -height / 2);
  m.vertices.emplace_back(0, 0, height / 2);
  const std::uint32_t top = bottom + 1;
  for (std::uint32_t i = 0; i < segments; ++i) {
    const std::uint32_t j = (i + 1) % segments;
    m.triangles.push_back({i, j, segments + j});
    m.triangles.push_back({i, segments + j, segments + i});
    m.triangles.push_back({bottom, j, i});
    m.triangles.push_back({top, segments + i, segments + j});
  }
  return m;
}

/// A square patch of two triangles in z = 0 (like RobWork's objects/plane_5x5.stl), normal +z.
inline TriMesh floorPatch(double half) {
  TriMesh m;
  m.vertices = {Vector3D(-half, -half, 0), Vector3D(half, -half, 0), Vector3D(half, half, 0),
                Vector3D(-half, half, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

/// Area of the convex hull of planar points (gift wrapping; fine for a handful of points).
inline double hullArea(const std::vector<Eigen::Vector2d>& p) {
  if (p.size() < 3) return 0.0;
  std::size_t start = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (p[i].x() < p[start].x() || (p[i].x() == p[start].x() && p[i].y() < p[start].y())) {
      start = i;
    }
  }
  double area = 0.0;
  std::size_t current = start;
  std::size_t steps = 0;
  do {
    std::size_t next = (current + 1) % p.size();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Eigen::Vector2d a = p[next] - p[current];
      const Eigen::Vector2d b = p[i] - p[current];
      if (a.x() * b.y() - a.y() * b.x() < 0.0) next = i;
    }
    area += 0.5 * (p[current].x() * p[next].y() - p[next].x() * p[current].y());
    current = next;
  } while (current != start && ++steps <= p.size());
  return area;
}

/// The xy coordinates of contact positions.
inline std::vector<Eigen::Vector2d> xy(const std::vector<ContactPoint>& points) {
  std::vector<Eigen::Vector2d> out;
  for (const ContactPoint& c : points) out.emplace_back(c.position.x(), c.position.y());
  return out;
}

}  // namespace rwsim::contacts::test
