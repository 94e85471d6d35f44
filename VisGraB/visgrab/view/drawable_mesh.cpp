#include "visgrab/view/drawable_mesh.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

namespace visgrab::view {

visual::VisualMesh shadedMesh(const rw::geometry::TriMesh& mesh, const Eigen::Vector3f& colour,
                              double creaseDegrees) {
  const std::size_t n = mesh.triangles.size();
  // Area-weighted face normals (|cross| = 2 * area) and unit ones.
  std::vector<Eigen::Vector3d> weighted(n), unit(n);
  std::vector<bool> valid(n, false);
  std::vector<std::vector<std::size_t>> around(mesh.vertices.size());
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d c = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]])
                                  .cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
    const double length = c.norm();
    if (!(length > 1e-18)) continue;
    weighted[t] = c;
    unit[t] = c / length;
    valid[t] = true;
    for (const std::uint32_t v : tri) around[v].push_back(t);
  }
  const double cosCrease = std::cos(creaseDegrees * std::numbers::pi / 180.0);
  visual::VisualMesh out;
  out.colour = colour;
  out.specular = 0.25f;
  for (std::size_t t = 0; t < n; ++t) {
    if (!valid[t]) continue;
    const auto& tri = mesh.triangles[t];
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    for (const std::uint32_t v : tri) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const std::size_t other : around[v]) {
        if (unit[other].dot(unit[t]) >= cosCrease) sum += weighted[other];
      }
      const Eigen::Vector3d normal = sum.norm() > 0.0 ? sum.normalized() : unit[t];
      out.positions.push_back(mesh.vertices[v].cast<float>());
      out.normals.push_back(normal.cast<float>());
    }
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

namespace {

/// A closed solid of revolution about z between the disk of radius `bottomRadius` at z = 0 and
/// the one of radius `topRadius` at z = 1 (0: a point), as a TriMesh.
rw::geometry::TriMesh solidOfRevolution(double bottomRadius, double topRadius, int segments) {
  rw::geometry::TriMesh mesh;
  const auto ring = [&](double radius, double z) {
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    for (int i = 0; i < segments; ++i) {
      const double a = 2.0 * std::numbers::pi * i / segments;
      mesh.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    }
    return first;
  };
  const auto s = static_cast<std::uint32_t>(segments);
  const std::uint32_t bottom = ring(bottomRadius, 0.0);
  const std::uint32_t top = ring(topRadius, 1.0);
  const auto bottomCentre = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, 0.0);
  const auto topCentre = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, 1.0);
  for (std::uint32_t i = 0; i < s; ++i) {
    const std::uint32_t j = (i + 1) % s;
    mesh.triangles.push_back({bottom + i, bottom + j, top + j});
    mesh.triangles.push_back({bottom + i, top + j, top + i});
    mesh.triangles.push_back({bottomCentre, bottom + j, bottom + i});
    mesh.triangles.push_back({topCentre, top + i, top + j});
  }
  return mesh;
}

}  // namespace

visual::VisualMesh unitShaft(int segments) {
  return shadedMesh(solidOfRevolution(1.0, 1.0, segments), Eigen::Vector3f(0.9f, 0.5f, 0.1f));
}

visual::VisualMesh unitHead(int segments) {
  // The apex ring has radius 0: its triangles are degenerate and dropped.
  return shadedMesh(solidOfRevolution(1.0, 0.0, segments), Eigen::Vector3f(0.9f, 0.5f, 0.1f));
}

}  // namespace visgrab::view
