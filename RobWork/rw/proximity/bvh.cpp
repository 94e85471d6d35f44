#include "rw/proximity/bvh.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace rw::proximity {

using rw::math::Rotation3D;
using rw::math::Vector3D;

namespace {

// Padding against rounding in the separating-axis tests of near-parallel edges.
constexpr double kAxisEpsilon = 1e-12;

Obb boxAlong(std::span<const Vector3D> points, const Rotation3D& axes) {
  Vector3D lo = Vector3D::Constant(std::numeric_limits<double>::infinity());
  Vector3D hi = -lo;
  for (const Vector3D& p : points) {
    const Vector3D local = axes.transpose() * p;
    lo = lo.cwiseMin(local);
    hi = hi.cwiseMax(local);
  }
  Obb box;
  box.axes = axes;
  box.center = axes * (0.5 * (lo + hi));
  box.halfExtents = 0.5 * (hi - lo);
  return box;
}

// Volume with a small floor per extent, so flat boxes still compare sensibly.
double paddedVolume(const Vector3D& halfExtents) {
  const double floor = 1e-9 * halfExtents.maxCoeff() + 1e-15;
  return (halfExtents.array() + floor).prod();
}

}  // namespace

Obb fitObb(std::span<const Vector3D> points) {
  const Obb aligned = boxAlong(points, Rotation3D::Identity());
  if (points.size() < 3) return aligned;
  Vector3D mean = Vector3D::Zero();
  for (const Vector3D& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vector3D& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  if (solver.info() != Eigen::Success) return aligned;
  Rotation3D axes = solver.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  const Obb principal = boxAlong(points, axes);
  return paddedVolume(principal.halfExtents) < paddedVolume(aligned.halfExtents) * (1.0 - 1e-9)
             ? principal
             : aligned;
}

bool obbDisjoint(const Obb& a, const Obb& b, const Rotation3D& R_ab, const Vector3D& t_ab,
                 double tolerance) {
  const Rotation3D R = a.axes.transpose() * (R_ab * b.axes);
  const Vector3D T = a.axes.transpose() * (R_ab * b.center + t_ab - a.center);
  const Eigen::Matrix3d absR = R.cwiseAbs().array() + kAxisEpsilon;
  const Vector3D& ea = a.halfExtents;
  const Vector3D& eb = b.halfExtents;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(T[i]) > ea[i] + eb.dot(absR.row(i)) + tolerance) return true;
  }
  for (int j = 0; j < 3; ++j) {
    if (std::abs(T.dot(R.col(j))) > ea.dot(absR.col(j)) + eb[j] + tolerance) return true;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const double ra = ea[i1] * absR(i2, j) + ea[i2] * absR(i1, j);
      const double rb = eb[j1] * absR(i, j2) + eb[j2] * absR(i, j1);
      if (std::abs(T[i2] * R(i1, j) - T[i1] * R(i2, j)) > ra + rb + tolerance) return true;
    }
  }
  return false;
}

double obbDistanceLowerBound(const Obb& a, const Obb& b, const Rotation3D& R_ab,
                             const Vector3D& t_ab) {
  const Rotation3D R = a.axes.transpose() * (R_ab * b.axes);
  const Vector3D T = a.axes.transpose() * (R_ab * b.center + t_ab - a.center);
  const Eigen::Matrix3d absR = R.cwiseAbs().array() + kAxisEpsilon;
  const Vector3D& ea = a.halfExtents;
  const Vector3D& eb = b.halfExtents;
  double gap = 0.0;
  // The line through the centres: the best axis for boxes far apart relative to their size.
  const double centreDistance = T.norm();
  if (centreDistance > 0.0) {
    const Vector3D u = T / centreDistance;
    gap = std::max(0.0,
                   centreDistance - ea.dot(u.cwiseAbs()) - eb.dot((R.transpose() * u).cwiseAbs()));
  }
  for (int i = 0; i < 3; ++i) {
    gap = std::max(gap, std::abs(T[i]) - ea[i] - eb.dot(absR.row(i)));
    gap = std::max(gap, std::abs(T.dot(R.col(i))) - ea.dot(absR.col(i)) - eb[i]);
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const double ra = ea[i1] * absR(i2, j) + ea[i2] * absR(i1, j);
      const double rb = eb[j1] * absR(i, j2) + eb[j2] * absR(i, j1);
      const double raw = std::abs(T[i2] * R(i1, j) - T[i1] * R(i2, j)) - ra - rb;
      const double axisSquared = 1.0 - R(i, j) * R(i, j);
      if (raw > 0.0 && axisSquared > 1e-12) {
        gap = std::max(gap, raw / std::sqrt(axisSquared));
      }
    }
  }
  return gap;
}

namespace {

// Top-down construction: split at the mean centroid along the box's longest axis, or at the
// median when the mean leaves one side nearly empty (keeps the depth logarithmic).
struct BvhBuilder {
  const std::vector<Triangle>& input;
  std::vector<Vector3D> centroids;
  std::vector<std::int32_t> order;
  std::vector<Bvh::Node>& nodes;
  std::vector<Vector3D> scratch;
  int depth = 0;

  std::int32_t build(std::int32_t begin, std::int32_t end, int level);
  std::int32_t split(std::int32_t begin, std::int32_t end, const Obb& box);
};

std::int32_t BvhBuilder::split(std::int32_t begin, std::int32_t end, const Obb& box) {
  int axisIndex = 0;
  box.halfExtents.maxCoeff(&axisIndex);
  const Vector3D axis = box.axes.col(axisIndex);
  const auto first = order.begin() + begin;
  const auto last = order.begin() + end;
  double mean = 0.0;
  for (auto it = first; it != last; ++it)
    mean += centroids[static_cast<std::size_t>(*it)].dot(axis);
  mean /= static_cast<double>(end - begin);
  const auto projection = [&](std::int32_t t) {
    return centroids[static_cast<std::size_t>(t)].dot(axis);
  };
  const auto middle =
      std::stable_partition(first, last, [&](std::int32_t t) { return projection(t) < mean; });
  const std::int32_t mid = static_cast<std::int32_t>(middle - order.begin());
  const std::int32_t minSide = std::max<std::int32_t>(1, (end - begin) / 8);
  if (mid - begin >= minSide && end - mid >= minSide) return mid;
  std::sort(first, last, [&](std::int32_t x, std::int32_t y) {
    const double px = projection(x);
    const double py = projection(y);
    return px < py || (px == py && x < y);
  });
  return begin + (end - begin) / 2;
}

std::int32_t BvhBuilder::build(std::int32_t begin, std::int32_t end, int level) {
  const auto index = static_cast<std::int32_t>(nodes.size());
  nodes.emplace_back();
  depth = std::max(depth, level);
  scratch.clear();
  for (std::int32_t k = begin; k < end; ++k) {
    const Triangle& t = input[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    scratch.insert(scratch.end(), t.v.begin(), t.v.end());
  }
  const Obb box = fitObb(scratch);
  nodes[static_cast<std::size_t>(index)].box = box;
  if (end - begin <= Bvh::kMaxLeafTriangles) {
    nodes[static_cast<std::size_t>(index)].first = begin;
    nodes[static_cast<std::size_t>(index)].count = end - begin;
    return index;
  }
  const std::int32_t mid = split(begin, end, box);
  build(begin, mid, level + 1);
  const std::int32_t second = build(mid, end, level + 1);
  nodes[static_cast<std::size_t>(index)].second = second;
  return index;
}

std::vector<Triangle> triangleSoup(const rw::geometry::TriMesh& mesh) {
  if (mesh.triangles.empty()) throw std::invalid_argument("Bvh: the mesh has no triangles");
  std::vector<Triangle> soup;
  soup.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    Triangle t;
    for (std::size_t k = 0; k < 3; ++k) {
      if (tri[k] >= mesh.vertices.size()) {
        throw std::invalid_argument("Bvh: vertex index " + std::to_string(tri[k]) +
                                    " out of range (" + std::to_string(mesh.vertices.size()) +
                                    " vertices)");
      }
      t.v[k] = mesh.vertices[tri[k]];
    }
    soup.push_back(t);
  }
  return soup;
}

}  // namespace

Bvh::Bvh(const rw::geometry::TriMesh& mesh) {
  const std::vector<Triangle> soup = triangleSoup(mesh);
  BvhBuilder builder{soup, {}, {}, nodes_, {}, 0};
  builder.centroids.reserve(soup.size());
  for (const Triangle& t : soup) builder.centroids.push_back((t.v[0] + t.v[1] + t.v[2]) / 3.0);
  builder.order.resize(soup.size());
  std::iota(builder.order.begin(), builder.order.end(), 0);
  nodes_.reserve(2 * soup.size());
  builder.build(0, static_cast<std::int32_t>(soup.size()), 1);
  depth_ = builder.depth;
  triangles_.reserve(soup.size());
  for (const std::int32_t k : builder.order)
    triangles_.push_back(soup[static_cast<std::size_t>(k)]);
}

}  // namespace rw::proximity
