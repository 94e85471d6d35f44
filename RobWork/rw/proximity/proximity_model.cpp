#include "rw/proximity/proximity_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace rw::proximity {

using rw::geometry::Geometry;
using rw::geometry::GeometryType;
using rw::math::Vector3D;

namespace {

// Hulls with fewer points are searched point by point.
constexpr std::size_t kMinPointsForClimbing = 16;

bool lexicographicLess(const Vector3D& x, const Vector3D& y) {
  return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
}

// The distinct vertices used by the mesh's triangles, in a fixed order.
std::vector<Vector3D> distinctVertices(const rw::geometry::TriMesh& mesh) {
  std::vector<Vector3D> points;
  points.reserve(3 * mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    for (const std::uint32_t k : tri) {
      if (k < mesh.vertices.size()) points.push_back(mesh.vertices[k]);
    }
  }
  std::sort(points.begin(), points.end(), lexicographicLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

// The edges of the mesh between its distinct vertices (indices into the sorted `points`), or
// nothing unless every edge is shared by exactly two triangles (a closed surface).
std::vector<std::pair<std::int32_t, std::int32_t>> closedSurfaceEdges(
    const rw::geometry::TriMesh& mesh, const std::vector<Vector3D>& points) {
  const auto indexOf = [&](std::uint32_t vertex) {
    const auto it =
        std::lower_bound(points.begin(), points.end(), mesh.vertices[vertex], lexicographicLess);
    return static_cast<std::int32_t>(it - points.begin());
  };
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  for (const auto& tri : mesh.triangles) {
    const std::array<std::int32_t, 3> v{indexOf(tri[0]), indexOf(tri[1]), indexOf(tri[2])};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      edges.emplace_back(std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3]));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<std::int32_t, std::int32_t>> unique;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) return {};
    unique.push_back(edges[i]);
    i = j;
  }
  return unique;
}

// A sphere around points: centre of their bounding box, radius to the farthest point.
void sphereAround(const std::vector<Vector3D>& points, Vector3D& center, double& radius) {
  rw::geometry::Aabb box;
  for (const Vector3D& p : points) box.extend(p);
  center = 0.5 * (box.min + box.max);
  double squared = 0.0;
  for (const Vector3D& p : points) squared = std::max(squared, (p - center).squaredNorm());
  radius = std::sqrt(squared);
}

Obb centredBox(const Vector3D& halfExtents) {
  Obb box;
  box.halfExtents = halfExtents;
  return box;
}

}  // namespace

ProximityModel::ProximityModel(const Geometry& geometry) : type_(geometry.type()) {
  const std::vector<double>& p = geometry.parameters();
  switch (type_) {
    case GeometryType::kBox:
      dims_ = 0.5 * Vector3D(p.at(0), p.at(1), p.at(2));
      convexBox_ = centredBox(dims_);
      boundRadius_ = dims_.norm();
      return;
    case GeometryType::kSphere:
      dims_ = Vector3D(p.at(0), 0.0, 0.0);
      convexBox_ = centredBox(Vector3D::Constant(p.at(0)));
      boundRadius_ = p.at(0);
      return;
    case GeometryType::kCylinder:
    case GeometryType::kCone:
      dims_ = Vector3D(p.at(0), 0.0, 0.5 * p.at(1));
      convexBox_ = centredBox(Vector3D(dims_.x(), dims_.x(), dims_.z()));
      boundRadius_ = std::hypot(dims_.x(), dims_.z());
      return;
    case GeometryType::kFrustum:
      dims_ = Vector3D(p.at(0), p.at(1), 0.5 * p.at(2));
      convexBox_ = centredBox(
          Vector3D(std::max(dims_.x(), dims_.y()), std::max(dims_.x(), dims_.y()), dims_.z()));
      boundRadius_ = std::hypot(std::max(dims_.x(), dims_.y()), dims_.z());
      return;
    case GeometryType::kPlane:
      kind_ = Kind::kPlane;
      boundRadius_ = std::numeric_limits<double>::infinity();
      return;
    case GeometryType::kTube:
    case GeometryType::kMesh:
      break;
  }
  const rw::geometry::TriMesh& mesh = geometry.triangles();
  bvh_.emplace(mesh);
  hullPoints_ = distinctVertices(mesh);
  sphereAround(hullPoints_, boundCenter_, boundRadius_);
  if (type_ == GeometryType::kMesh && geometry.isConvex()) {
    convexBox_ = fitObb(hullPoints_);
    if (hullPoints_.size() >= kMinPointsForClimbing) buildHullGraph(mesh);
  } else {
    kind_ = Kind::kMesh;
    hullPoints_.clear();
    hullPoints_.shrink_to_fit();
  }
}

void ProximityModel::buildHullGraph(const rw::geometry::TriMesh& mesh) {
  const auto edges = closedSurfaceEdges(mesh, hullPoints_);
  if (edges.empty()) return;
  std::vector<std::int32_t> degree(hullPoints_.size(), 0);
  for (const auto& [a, b] : edges) {
    ++degree[static_cast<std::size_t>(a)];
    ++degree[static_cast<std::size_t>(b)];
  }
  hullOffsets_.assign(hullPoints_.size() + 1, 0);
  for (std::size_t i = 0; i < hullPoints_.size(); ++i) {
    hullOffsets_[i + 1] = hullOffsets_[i] + degree[i];
  }
  hullNeighbours_.resize(static_cast<std::size_t>(hullOffsets_.back()));
  std::vector<std::int32_t> fill(hullOffsets_.begin(), hullOffsets_.end() - 1);
  for (const auto& [a, b] : edges) {
    hullNeighbours_[static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++)] = b;
    hullNeighbours_[static_cast<std::size_t>(fill[static_cast<std::size_t>(b)]++)] = a;
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      const Vector3D d = sign * Vector3D::Unit(axis);
      const auto farthest = std::max_element(
          hullPoints_.begin(), hullPoints_.end(),
          [&](const Vector3D& x, const Vector3D& y) { return x.dot(d) < y.dot(d); });
      hullAnchors_.push_back(static_cast<std::int32_t>(farthest - hullPoints_.begin()));
    }
  }
}

ConvexShape ProximityModel::convexShape() const {
  switch (type_) {
    case GeometryType::kBox:
      return ConvexShape::box(dims_);
    case GeometryType::kSphere:
      return ConvexShape::sphere(dims_.x());
    case GeometryType::kCylinder:
      return ConvexShape::cylinder(dims_.x(), dims_.z());
    case GeometryType::kCone:
      return ConvexShape::cone(dims_.x(), dims_.z());
    case GeometryType::kFrustum:
      return ConvexShape::frustum(dims_.x(), dims_.y(), dims_.z());
    case GeometryType::kTube:
    case GeometryType::kPlane:
    case GeometryType::kMesh:
      break;
  }
  if (!hullOffsets_.empty()) {
    return ConvexShape::hull(hullPoints_, {hullOffsets_, hullNeighbours_, hullAnchors_});
  }
  return ConvexShape::hull(hullPoints_);
}

}  // namespace rw::proximity
