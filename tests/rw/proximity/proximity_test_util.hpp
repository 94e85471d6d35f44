#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/rpy.hpp"
#include "rw/math/types.hpp"
#include "rw/proximity/triangle_queries.hpp"

/// Helpers shared by the proximity tests: shapes built in code and surface checks.
namespace rw::proximity::test {

using rw::math::Transform3D;
using rw::math::Vector3D;

/// Pose from a position and RPY angles in degrees.
inline Transform3D pose(const Vector3D& p, double rollDeg = 0, double pitchDeg = 0,
                        double yawDeg = 0) {
  return rw::math::rpyTransform(Vector3D(rollDeg, pitchDeg, yawDeg) * rw::math::kDeg2Rad, p);
}

/// Distance of world point `p` from the surface of a box (half extents `h`) placed at X.
inline double boxSurfaceDistance(const Vector3D& p, const Transform3D& X, const Vector3D& h) {
  const Vector3D local = X.inverse() * p;
  const Vector3D outside = (local.cwiseAbs() - h).cwiseMax(0.0);
  if (outside.squaredNorm() > 0.0) return outside.norm();
  return (h - local.cwiseAbs()).minCoeff();
}

/// Distance of world point `p` from the surface of a sphere of radius r centred at c.
inline double sphereSurfaceDistance(const Vector3D& p, const Vector3D& c, double r) {
  return std::abs((p - c).norm() - r);
}

/// Distance of world point `p` from the triangles of `mesh` placed at X.
inline double meshSurfaceDistance(const Vector3D& p, const Transform3D& X,
                                  const rw::geometry::TriMesh& mesh) {
  const Vector3D local = X.inverse() * p;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    const Triangle tri{{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]}};
    best = std::min(best, (closestPointOnTriangle(local, tri) - local).norm());
  }
  return best;
}

/// A closed prism: the counter-clockwise polygon `outline` (x, y) triangulated by `fan`
/// (index triples into outline, counter-clockwise), extruded from z0 to z1.
inline std::shared_ptr<const rw::geometry::TriMesh> prism(
    const std::vector<Eigen::Vector2d>& outline, const std::vector<std::array<int, 3>>& fan,
    double z0, double z1) {
  auto mesh = std::make_shared<rw::geometry::TriMesh>();
  const auto n = static_cast<std::uint32_t>(outline.size());
  for (const auto& q : outline) mesh->vertices.emplace_back(q.x(), q.y(), z0);
  for (const auto& q : outline) mesh->vertices.emplace_back(q.x(), q.y(), z1);
  for (const auto& f : fan) {
    const auto a = static_cast<std::uint32_t>(f[0]);
    const auto b = static_cast<std::uint32_t>(f[1]);
    const auto c = static_cast<std::uint32_t>(f[2]);
    mesh->triangles.push_back({n + a, n + b, n + c});  // top, seen from +z
    mesh->triangles.push_back({a, c, b});              // bottom, seen from -z
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    mesh->triangles.push_back({i, j, n + j});
    mesh->triangles.push_back({i, n + j, n + i});
  }
  return mesh;
}

/// An L-shaped block: [0,2]x[0,1] united with [0,1]x[0,2] in x-y, z from 0 to 1 (non-convex).
inline std::shared_ptr<const rw::geometry::Geometry> lShape() {
  const std::vector<Eigen::Vector2d> outline{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<std::array<int, 3>> fan{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  return rw::geometry::Geometry::mesh(prism(outline, fan, 0.0, 1.0), "L-shape (test)");
}

/// The tetrahedron with corners o, o + a, o + b, o + c (a, b, c right-handed).
inline std::shared_ptr<const rw::geometry::Geometry> tetrahedron(const Vector3D& o,
                                                                 const Vector3D& a,
                                                                 const Vector3D& b,
                                                                 const Vector3D& c) {
  auto mesh = std::make_shared<rw::geometry::TriMesh>();
  mesh->vertices = {o, o + a, o + b, o + c};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return rw::geometry::Geometry::mesh(mesh, "tetrahedron (test)");
}

}  // namespace rw::proximity::test
