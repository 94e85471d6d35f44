#include "visgrab/objects/convex_hull.hpp"

#include <libqhull_r/libqhull_r.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "rw/common/memory_stream.hpp"

namespace visgrab::objects {

namespace {

using rw::math::Vector3D;

// Smallest singular value of the centred points: how far they are from lying on a plane.
double thickness(const std::vector<Vector3D>& points) {
  Vector3D mean = Vector3D::Zero();
  for (const Vector3D& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vector3D& p : points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const double largest = std::max(solver.eigenvalues()(2), 0.0);
  const double smallest = std::max(solver.eigenvalues()(0), 0.0);
  return largest > 0.0 ? std::sqrt(smallest / largest) : 0.0;
}

}  // namespace

rw::geometry::TriMesh convexHull(const std::vector<Vector3D>& input) {
  // Canonical input: sorted, exact duplicates removed, so that the hull does not depend on the
  // order the points came in.
  std::vector<Vector3D> points(input);
  for (Vector3D& p : points) p.array() += 0.0;  // -0.0 -> +0.0
  std::sort(points.begin(), points.end(), [](const Vector3D& a, const Vector3D& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 4 || thickness(points) < 1e-9) {
    throw std::invalid_argument("convexHull: the " + std::to_string(points.size()) +
                                " points do not span a volume");
  }
  std::vector<double> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Vector3D& p : points) coordinates.insert(coordinates.end(), p.data(), p.data() + 3);
  std::string options = "qhull Qt";  // merged facets, reported as triangles
  rw::common::MemoryStream errors;
  auto qh = std::make_unique<qhT>();
  qh_zero(qh.get(), errors.file());
  const int exitCode =
      qh_new_qhull(qh.get(), 3, static_cast<int>(points.size()), coordinates.data(), False,
                   options.data(), nullptr, errors.file());
  rw::geometry::TriMesh mesh;
  if (exitCode == qh_ERRnone) {
    std::map<int, std::uint32_t> index;  // Qhull point id -> mesh vertex
    for (facetT* f = qh->facet_list; f != nullptr && f->next != nullptr; f = f->next) {
      if (f->upperdelaunay || qh_setsize(qh.get(), f->vertices) != 3) continue;
      std::array<std::uint32_t, 3> tri{};
      int k = 0;
      vertexT** vertexp = reinterpret_cast<vertexT**>(&f->vertices->e[0].p);
      for (; *vertexp != nullptr && k < 3; ++vertexp, ++k) {
        const int id = qh_pointid(qh.get(), (*vertexp)->point);
        auto [it, inserted] = index.emplace(id, static_cast<std::uint32_t>(mesh.vertices.size()));
        if (inserted) mesh.vertices.push_back(points[static_cast<std::size_t>(id)]);
        tri[static_cast<std::size_t>(k)] = it->second;
      }
      const Vector3D& a = mesh.vertices[tri[0]];
      const Vector3D normal = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a);
      const Vector3D facetNormal(f->normal[0], f->normal[1], f->normal[2]);
      if (normal.dot(facetNormal) < 0.0) std::swap(tri[1], tri[2]);
      mesh.triangles.push_back(tri);
    }
  }
  const std::string message = exitCode == qh_ERRnone ? std::string() : errors.text();
  qh_freeqhull(qh.get(), !qh_ALL);
  int curLong = 0;
  int totLong = 0;
  qh_memfreeshort(qh.get(), &curLong, &totLong);
  if (exitCode == qh_ERRsingular) {
    // Flat within Qhull's round-off, though thicker than the check above.
    throw std::invalid_argument("convexHull: the " + std::to_string(points.size()) +
                                " points do not span a volume (Qhull: the initial simplex is "
                                "flat)");
  }
  if (exitCode != qh_ERRnone) {
    throw std::runtime_error("convexHull: Qhull failed (exit code " + std::to_string(exitCode) +
                             "): " + message);
  }
  return mesh;
}

double meshVolume(const rw::geometry::TriMesh& mesh) {
  double six = 0.0;
  for (const auto& t : mesh.triangles) {
    six += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return six / 6.0;
}

}  // namespace visgrab::objects
