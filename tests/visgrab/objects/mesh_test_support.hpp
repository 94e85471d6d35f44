#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "support/test_support.hpp"
#include "visgrab/objects/object_model.hpp"

/// Closed meshes built in code for the mesh-object tests, and an OBJ writer for them.
namespace visgrab::test::objects {

/// A box [x0, x0 + a] x [y0, y0 + b] x [z0, z0 + c], wound outwards.
inline rw::geometry::TriMesh boxMesh(const Eigen::Vector3d& corner, const Eigen::Vector3d& size) {
  rw::geometry::TriMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.push_back(corner + Eigen::Vector3d((i & 1) ? size.x() : 0.0,
                                                  (i & 2) ? size.y() : 0.0,
                                                  (i & 4) ? size.z() : 0.0));
  }
  // Each face as a quad, counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    const auto v = [&q](int k) { return static_cast<std::uint32_t>(q[k]); };
    m.triangles.push_back({v(0), v(1), v(2)});
    m.triangles.push_back({v(0), v(2), v(3)});
  }
  return m;
}

/// A prism over a polygon given counter-clockwise seen from above (star-shaped about its first
/// vertex), from z = 0 to z = h.
inline rw::geometry::TriMesh prismMesh(const std::vector<Eigen::Vector2d>& polygon, double h) {
  rw::geometry::TriMesh m;
  const auto n = static_cast<std::uint32_t>(polygon.size());
  for (const double z : {0.0, h}) {
    for (const auto& p : polygon) m.vertices.emplace_back(p.x(), p.y(), z);
  }
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    m.triangles.push_back({0, i + 1, i});          // bottom, seen from below
    m.triangles.push_back({n, n + i, n + i + 1});  // top
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
  }
  return m;
}

/// A regular polygon of `sides` vertices on a circle of radius r about the origin.
inline std::vector<Eigen::Vector2d> circle(double r, int sides) {
  std::vector<Eigen::Vector2d> out;
  for (int i = 0; i < sides; ++i) {
    const double a = 2.0 * std::numbers::pi * i / sides;
    out.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return out;
}

/// Writes a mesh as OBJ text (full double precision) and returns the path.
inline std::filesystem::path writeObj(const std::filesystem::path& file,
                                      const rw::geometry::TriMesh& mesh) {
  std::string text;
  char line[128];
  for (const auto& v : mesh.vertices) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", v.x(), v.y(), v.z());
    text += line;
  }
  for (const auto& t : mesh.triangles) {
    text += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
            std::to_string(t[2] + 1) + "\n";
  }
  return writeFile(file, text);
}

/// The visual parts of a model as one mesh, vertices joined by exact position.
inline rw::geometry::TriMesh weldedVisual(const visgrab::objects::ObjectModel& model) {
  rw::geometry::TriMesh m;
  std::map<std::tuple<float, float, float>, std::uint32_t> index;
  for (const auto& part : model.visual) {
    for (const auto& t : part.mesh.triangles) {
      std::array<std::uint32_t, 3> tri{};
      for (std::size_t k = 0; k < 3; ++k) {
        const Eigen::Vector3f& p = part.mesh.positions[t[k]];
        const auto [it, inserted] = index.emplace(std::make_tuple(p.x(), p.y(), p.z()),
                                                  static_cast<std::uint32_t>(m.vertices.size()));
        if (inserted) m.vertices.push_back(p.cast<double>());
        tri[k] = it->second;
      }
      m.triangles.push_back(tri);
    }
  }
  return m;
}

/// Largest distance of a mesh vertex in front of one of the mesh's triangle planes (0 for a
/// convex mesh wound outwards), relative to the mesh's size.
inline double convexityViolation(const rw::geometry::TriMesh& m) {
  rw::geometry::Aabb box;
  for (const auto& v : m.vertices) box.extend(v);
  const double size = (box.max - box.min).norm();
  double worst = 0.0;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d& a = m.vertices[t[0]];
    const Eigen::Vector3d n = (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a);
    if (n.norm() < 1e-14 * size * size) continue;
    for (const auto& v : m.vertices) worst = std::max(worst, n.normalized().dot(v - a));
  }
  return worst / size;
}

}  // namespace visgrab::test::objects
