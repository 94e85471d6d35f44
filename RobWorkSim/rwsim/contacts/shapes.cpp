#include "rwsim/contacts/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace rwsim::contacts {
namespace detail {
namespace {

using rw::geometry::Aabb;
using rw::geometry::TriMesh;
using rw::math::Vector3D;
using Index = std::int32_t;

/// Vertices within this fraction of the bounding-box diagonal of a plane lie on it.
constexpr double kFlatRelTolerance = 1e-6;
/// A flat mesh is its convex hull when their areas agree within this fraction.
constexpr double kAreaRelTolerance = 1e-6;
/// A closed mesh's edge is convex when the neighbour's far vertex lies this far (m) below the
/// triangle's plane and their normals differ.
constexpr double kConvexEdgeDepth = 1e-12;
constexpr double kSameNormalDot = 1.0 - 1e-9;

double perpDot(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Counter-clockwise convex hull (monotone chain, collinear points dropped) of planar points.
std::vector<Index> planarHull(const std::vector<Eigen::Vector2d>& q) {
  std::vector<Index> order(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) order[i] = static_cast<Index>(i);
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    const auto& pa = q[static_cast<std::size_t>(a)];
    const auto& pb = q[static_cast<std::size_t>(b)];
    return pa.x() < pb.x() ||
           (pa.x() == pb.x() && (pa.y() < pb.y() || (pa.y() == pb.y() && a < b)));
  });
  std::vector<Index> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Index p = pass == 0 ? order[k] : order[order.size() - 1 - k];
      while (hull.size() >= base + 2) {
        const auto& o = q[static_cast<std::size_t>(hull[hull.size() - 2])];
        const auto& a = q[static_cast<std::size_t>(hull.back())];
        if (perpDot(a - o, q[static_cast<std::size_t>(p)] - o) > 0.0) break;
        hull.pop_back();
      }
      hull.push_back(p);
    }
    hull.pop_back();
  }
  return hull;
}

/// Largest rounding of a round shape's rims (m): overlaps deeper than this (or than a quarter of
/// the shape's half height or radius) fall back to the tessellation.
constexpr double kMaxRounding = 0.002;

/// Distance of point p from the segment [a, b] (in a meridian plane: radius, height).
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t =
      ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

/// The core of a frustum (radii bottom, top over z in [-h, h]) shrunk by `rounding` (every
/// face moved inwards by it, the part near a cone's apex cut off where the shrunk side passes
/// the axis): its ConvexShape, centre height and how far the frustum reaches beyond it. Both
/// are solids of revolution, so that reach is the larger distance of the frustum's two rim
/// corners (or apex) from the core's profile in a meridian plane.
RoundCore frustumCore(double bottom, double top, double h, double rounding) {
  const double height = 2.0 * h;
  const double slope = (top - bottom) / height;
  const double inset = rounding * std::hypot(height, top - bottom) / height;
  const auto shrunk = [&](double z) { return bottom + slope * (z + h) - inset; };
  double zlo = -h + rounding;
  double zhi = h - rounding;
  if (shrunk(zlo) < 0.0) zlo = -h + (inset - bottom) / slope;
  if (shrunk(zhi) < 0.0) zhi = -h + (inset - bottom) / slope;
  const double rlo = std::max(0.0, shrunk(zlo));
  const double rhi = std::max(0.0, shrunk(zhi));
  const std::array<Eigen::Vector2d, 4> profile{Eigen::Vector2d(0.0, zlo), Eigen::Vector2d(rlo, zlo),
                                               Eigen::Vector2d(rhi, zhi),
                                               Eigen::Vector2d(0.0, zhi)};
  double reach = rounding;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(bottom, -h), Eigen::Vector2d(top, h)}) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < profile.size(); ++k) {
      d = std::min(d, distanceToSegment(corner, profile[k], profile[(k + 1) % profile.size()]));
    }
    reach = std::max(reach, d);
  }
  return {rw::proximity::ConvexShape::frustum(rlo, rhi, 0.5 * (zhi - zlo)), 0.5 * (zlo + zhi),
          reach};
}

double roundingOf(double bottom, double top, double h) {
  return std::min(kMaxRounding, 0.25 * std::min(h, std::max(bottom, top)));
}

void addQuad(TriMesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

}  // namespace

Aabb SphereShape::localBounds() const {
  Aabb box;
  box.min = Vector3D::Constant(-radius_);
  box.max = Vector3D::Constant(radius_);
  return box;
}

Aabb HalfSpaceShape::localBounds() const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Aabb box;
  box.min = Vector3D::Constant(-kInf);
  box.max = Vector3D(kInf, kInf, 0.0);
  return box;
}

RoundShape::RoundShape(double bottom, double top, double halfHeight, Polytope tessellation)
    : ContactShape(Kind::kRound),
      bottom_(bottom),
      top_(top),
      halfHeight_(halfHeight),
      rounding_(roundingOf(bottom, top, halfHeight)),
      core_(frustumCore(bottom, top, halfHeight, rounding_)),
      polytope_(std::move(tessellation)) {}

Vector3D RoundShape::support(const Vector3D& d) const {
  const double planar = std::hypot(d.x(), d.y());
  const auto rim = [&](double radius, double z) {
    if (planar <= 0.0) return Vector3D(0.0, 0.0, z);
    return Vector3D(d.x() * radius / planar, d.y() * radius / planar, z);
  };
  const Vector3D topRim = rim(top_, halfHeight_);
  const Vector3D bottomRim = rim(bottom_, -halfHeight_);
  return topRim.dot(d) >= bottomRim.dot(d) ? topRim : bottomRim;
}

Aabb RoundShape::localBounds() const {
  const double r = std::max(bottom_, top_);
  Aabb box;
  box.min = Vector3D(-r, -r, -halfHeight_);
  box.max = Vector3D(r, r, halfHeight_);
  return box;
}

PolytopeShape::PolytopeShape(std::vector<Polytope> pieces)
    : ContactShape(Kind::kConvex), pieces_(std::move(pieces)) {
  for (const Polytope& p : pieces_) {
    bounds_.extend(p.bounds().min);
    bounds_.extend(p.bounds().max);
  }
}

MeshShape::MeshShape(const TriMesh& mesh) : ContactShape(Kind::kMesh), bvh_(mesh) {
  const auto& triangles = bvh_.triangles();
  info_.resize(triangles.size());
  std::map<std::array<double, 3>, Index> ids;
  std::vector<std::array<Index, 3>> corners(triangles.size());
  std::map<std::pair<Index, Index>, Index> halfEdges;
  bool closed = true;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& v = triangles[i].v;
    for (const Vector3D& p : v) bounds_.extend(p);
    const Vector3D cross = (v[1] - v[0]).cross(v[2] - v[0]);
    if (cross.norm() > 0.0) info_[i].normal = cross.normalized();
    for (int k = 0; k < 3; ++k) {
      const Vector3D& p = v[static_cast<std::size_t>(k)];
      corners[i][static_cast<std::size_t>(k)] =
          ids.try_emplace({p.x(), p.y(), p.z()}, static_cast<Index>(ids.size())).first->second;
    }
    for (int k = 0; k < 3; ++k) {
      const std::pair<Index, Index> key{corners[i][static_cast<std::size_t>(k)],
                                        corners[i][static_cast<std::size_t>((k + 1) % 3)]};
      closed = closed && halfEdges.try_emplace(key, static_cast<Index>(i)).second;
    }
  }
  for (std::size_t i = 0; closed && i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const auto twin = halfEdges.find({corners[i][static_cast<std::size_t>((k + 1) % 3)],
                                        corners[i][static_cast<std::size_t>(k)]});
      if (twin == halfEdges.end()) {
        closed = false;
        break;
      }
      const auto j = static_cast<std::size_t>(twin->second);
      const Vector3D& n = info_[i].normal;
      const Vector3D& n2 = info_[j].normal;
      const Vector3D& a = triangles[i].v[static_cast<std::size_t>(k)];
      double below = 0.0;
      for (const Vector3D& w : triangles[j].v) below = std::min(below, n.dot(w - a));
      if (below < -kConvexEdgeDepth && n2.squaredNorm() > 0.0 && n.dot(n2) < kSameNormalDot) {
        info_[i].neighbour[static_cast<std::size_t>(k)] = n2;
      }
    }
  }
  oneSided_ = closed;
  if (!closed) {
    for (TriangleInfo& t : info_) t.neighbour = {};
  }
}

std::optional<Polytope> flatConvexPatch(const TriMesh& mesh) {
  Aabb box;
  Vector3D sum = Vector3D::Zero();
  Vector3D largest = Vector3D::Zero();
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vector3D& a = mesh.vertices[t[0]];
    const Vector3D cross = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    sum += cross;
    area += 0.5 * cross.norm();
    if (cross.squaredNorm() > largest.squaredNorm()) largest = cross;
    for (const auto i : t) box.extend(mesh.vertices[i]);
  }
  if (!(area > 0.0)) return std::nullopt;
  Vector3D n = largest.normalized();
  if (n.dot(sum) < 0.0) n = -n;
  const Vector3D& origin = mesh.vertices[mesh.triangles[0][0]];
  const double tolerance = kFlatRelTolerance * (box.max - box.min).norm();
  std::vector<Vector3D> points;
  for (const auto& t : mesh.triangles) {
    for (const auto i : t) {
      if (std::abs(n.dot(mesh.vertices[i] - origin)) > tolerance) return std::nullopt;
      points.emplace_back(mesh.vertices[i] - n.dot(mesh.vertices[i] - origin) * n);
    }
  }
  int axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Vector3D t1 = n.cross(Vector3D::Unit(axis)).normalized();
  const Vector3D t2 = n.cross(t1);
  std::vector<Eigen::Vector2d> planar;
  planar.reserve(points.size());
  for (const Vector3D& p : points) planar.emplace_back(p.dot(t1), p.dot(t2));
  const std::vector<Index> hull = planarHull(planar);
  if (hull.size() < 3) return std::nullopt;
  double hullArea = 0.0;
  for (std::size_t k = 1; k + 1 < hull.size(); ++k) {
    const auto& o = planar[static_cast<std::size_t>(hull[0])];
    hullArea += 0.5 * perpDot(planar[static_cast<std::size_t>(hull[k])] - o,
                              planar[static_cast<std::size_t>(hull[k + 1])] - o);
  }
  if (std::abs(hullArea - area) > kAreaRelTolerance * hullArea) return std::nullopt;
  std::vector<Vector3D> loop;
  loop.reserve(hull.size());
  for (const Index i : hull) loop.push_back(points[static_cast<std::size_t>(i)]);
  return Polytope::flatPolygon(std::move(loop), n);
}

std::vector<Polytope> tubePieces(double inner, double outer, double height, int segments) {
  std::vector<Polytope> pieces;
  for (int i = 0; i < segments; ++i) {
    TriMesh m;
    for (const double z : {-height / 2, height / 2}) {
      for (const double r : {inner, outer}) {
        for (const int k : {i, i + 1}) {
          const double angle = 2.0 * std::numbers::pi * (k % segments) / segments;
          m.vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
        }
      }
    }
    // Corners: bit 0 second angle, bit 1 outer ring, bit 2 top.
    addQuad(m, 2, 3, 7, 6);  // outer wall
    addQuad(m, 0, 4, 5, 1);  // inner wall
    addQuad(m, 4, 6, 7, 5);  // top
    addQuad(m, 0, 1, 3, 2);  // bottom
    addQuad(m, 0, 2, 6, 4);  // side at the first angle
    addQuad(m, 1, 5, 7, 3);  // side at the second angle
    if (auto piece = Polytope::fromConvexMesh(m)) pieces.push_back(std::move(*piece));
  }
  return pieces;
}

}  // namespace detail

std::shared_ptr<const ContactShape> ContactShape::build(const rw::geometry::Geometry& geometry) {
  using rw::geometry::GeometryType;
  const rw::geometry::TriMesh& mesh = geometry.triangles();
  const auto& p = geometry.parameters();
  switch (geometry.type()) {
    case GeometryType::kSphere:
      return std::make_shared<detail::SphereShape>(p[0]);
    case GeometryType::kPlane:
      return std::make_shared<detail::HalfSpaceShape>();
    case GeometryType::kTube: {
      const int segments =
          mesh.vertices.size() % 4 == 0 ? static_cast<int>(mesh.vertices.size() / 4) : 32;
      return std::make_shared<detail::PolytopeShape>(
          detail::tubePieces(p[0], p[0] + p[1], p[2], segments));
    }
    case GeometryType::kCylinder:
    case GeometryType::kCone:
    case GeometryType::kFrustum: {
      auto polytope = detail::Polytope::fromConvexMesh(mesh);
      if (!polytope) break;
      const bool frustum = geometry.type() == GeometryType::kFrustum;
      const double top = frustum ? p[1] : p[0];
      const double bottom = frustum || geometry.type() == GeometryType::kCylinder ? p[0] : 0.0;
      return std::make_shared<detail::RoundShape>(bottom, top, 0.5 * p[frustum ? 2 : 1],
                                                  std::move(*polytope));
    }
    case GeometryType::kBox:
    case GeometryType::kMesh:
      break;
  }
  if (mesh.triangles.empty()) {
    throw std::invalid_argument("ContactShape: mesh '" + geometry.sourceFile() +
                                "' has no triangles");
  }
  if (geometry.type() == GeometryType::kMesh) {
    if (auto patch = detail::flatConvexPatch(mesh)) {
      return std::make_shared<detail::PolytopeShape>(std::vector<detail::Polytope>{*patch});
    }
  }
  if (geometry.isConvex()) {
    if (auto polytope = detail::Polytope::fromConvexMesh(mesh)) {
      return std::make_shared<detail::PolytopeShape>(
          std::vector<detail::Polytope>{std::move(*polytope)});
    }
  }
  return std::make_shared<detail::MeshShape>(mesh);
}

}  // namespace rwsim::contacts
