#include "rw/proximity/gjk.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rw::proximity {

using rw::math::Transform3D;
using rw::math::Vector3D;

namespace {

constexpr int kMaxIterations = 128;
constexpr double kRelativeTolerance = 1e-10;
constexpr double kTinySquaredNorm = 1e-30;

// One vertex of the simplex: w = a - b with a on shape A and b on shape B.
struct SimplexVertex {
  Vector3D w;
  Vector3D a;
  Vector3D b;
};

struct Simplex {
  std::array<SimplexVertex, 4> v;
  std::array<double, 4> lambda{};
  int size = 0;
};

// The smallest sub-simplex holding the point closest to the origin: indices and weights.
struct SubSimplex {
  int count = 0;
  std::array<int, 4> index{};
  std::array<double, 4> weight{};
  Vector3D point = Vector3D::Zero();
};

SubSimplex vertexOf(const Simplex& s, int i) {
  SubSimplex r;
  r.count = 1;
  r.index[0] = i;
  r.weight[0] = 1.0;
  r.point = s.v[static_cast<std::size_t>(i)].w;
  return r;
}

// Point a + t (b - a) of edge (i, j), t = num / den, clamped to the edge.
SubSimplex edgeOf(const Simplex& s, int i, int j, double num, double den) {
  if (!(den > 0.0) || num <= 0.0) return vertexOf(s, i);
  if (num >= den) return vertexOf(s, j);
  const double t = num / den;
  SubSimplex r;
  r.count = 2;
  r.index = {i, j, 0, 0};
  r.weight = {1.0 - t, t, 0.0, 0.0};
  const Vector3D& a = s.v[static_cast<std::size_t>(i)].w;
  const Vector3D& b = s.v[static_cast<std::size_t>(j)].w;
  r.point = a + t * (b - a);
  return r;
}

SubSimplex closestOnSegment(const Simplex& s, int i, int j) {
  const Vector3D& a = s.v[static_cast<std::size_t>(i)].w;
  const Vector3D ab = s.v[static_cast<std::size_t>(j)].w - a;
  return edgeOf(s, i, j, -a.dot(ab), ab.squaredNorm());
}

SubSimplex closerOf(const SubSimplex& x, const SubSimplex& y) {
  return y.point.squaredNorm() < x.point.squaredNorm() ? y : x;
}

// Closest point of triangle (i, j, k) to the origin by its Voronoi regions.
SubSimplex closestOnTriangle(const Simplex& s, int i, int j, int k) {
  const Vector3D& a = s.v[static_cast<std::size_t>(i)].w;
  const Vector3D& b = s.v[static_cast<std::size_t>(j)].w;
  const Vector3D& c = s.v[static_cast<std::size_t>(k)].w;
  const Vector3D ab = b - a;
  const Vector3D ac = c - a;
  const double d1 = -ab.dot(a);
  const double d2 = -ac.dot(a);
  if (d1 <= 0.0 && d2 <= 0.0) return vertexOf(s, i);
  const double d3 = -ab.dot(b);
  const double d4 = -ac.dot(b);
  if (d3 >= 0.0 && d4 <= d3) return vertexOf(s, j);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return edgeOf(s, i, j, d1, d1 - d3);
  const double d5 = -ab.dot(c);
  const double d6 = -ac.dot(c);
  if (d6 >= 0.0 && d5 <= d6) return vertexOf(s, k);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return edgeOf(s, i, k, d2, d2 - d6);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    return edgeOf(s, j, k, d4 - d3, (d4 - d3) + (d5 - d6));
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // Degenerate (collinear) triangle: the best of its edges.
    return closerOf(closerOf(closestOnSegment(s, i, j), closestOnSegment(s, i, k)),
                    closestOnSegment(s, j, k));
  }
  SubSimplex r;
  r.count = 3;
  r.index = {i, j, k, 0};
  const double v = vb / sum;
  const double w = vc / sum;
  r.weight = {1.0 - v - w, v, w, 0.0};
  r.point = a + v * ab + w * ac;
  return r;
}

double det3(const Vector3D& x, const Vector3D& y, const Vector3D& z) { return x.dot(y.cross(z)); }

// Barycentric weights of the origin inside tetrahedron 0123.
SubSimplex insideTetrahedron(const Simplex& s) {
  const Vector3D& w0 = s.v[0].w;
  const Vector3D e1 = s.v[1].w - w0;
  const Vector3D e2 = s.v[2].w - w0;
  const Vector3D e3 = s.v[3].w - w0;
  const double volume = det3(e1, e2, e3);
  SubSimplex r;
  r.count = 4;
  r.index = {0, 1, 2, 3};
  if (volume == 0.0) {
    r.weight = {1.0, 0.0, 0.0, 0.0};
    return r;
  }
  const double l1 = std::clamp(det3(-w0, e2, e3) / volume, 0.0, 1.0);
  const double l2 = std::clamp(det3(e1, -w0, e3) / volume, 0.0, 1.0);
  const double l3 = std::clamp(det3(e1, e2, -w0) / volume, 0.0, 1.0);
  const double l0 = std::max(0.0, 1.0 - l1 - l2 - l3);
  const double sum = l0 + l1 + l2 + l3;
  r.weight = {l0 / sum, l1 / sum, l2 / sum, l3 / sum};
  return r;
}

SubSimplex closestOnTetrahedron(const Simplex& s) {
  static constexpr std::array<std::array<int, 4>, 4> kFaces{
      {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}}};
  bool found = false;
  SubSimplex best{};
  for (const auto& f : kFaces) {
    const Vector3D& a = s.v[static_cast<std::size_t>(f[0])].w;
    const Vector3D n = (s.v[static_cast<std::size_t>(f[1])].w - a)
                           .cross(s.v[static_cast<std::size_t>(f[2])].w - a);
    const double originSide = -n.dot(a);
    const double oppositeSide = n.dot(s.v[static_cast<std::size_t>(f[3])].w - a);
    if (oppositeSide != 0.0 && originSide * oppositeSide >= 0.0) continue;
    const SubSimplex candidate = closestOnTriangle(s, f[0], f[1], f[2]);
    best = found ? closerOf(best, candidate) : candidate;
    found = true;
  }
  return found ? best : insideTetrahedron(s);
}

// Replaces the simplex by its sub-simplex closest to the origin and returns that point.
Vector3D reduce(Simplex& s) {
  SubSimplex sub{};
  switch (s.size) {
    case 1:
      sub = vertexOf(s, 0);
      break;
    case 2:
      sub = closestOnSegment(s, 0, 1);
      break;
    case 3:
      sub = closestOnTriangle(s, 0, 1, 2);
      break;
    default:
      sub = closestOnTetrahedron(s);
      break;
  }
  Simplex reduced;
  reduced.size = sub.count;
  for (int n = 0; n < sub.count; ++n) {
    const auto un = static_cast<std::size_t>(n);
    reduced.v[un] = s.v[static_cast<std::size_t>(sub.index[un])];
    reduced.lambda[un] = sub.weight[un];
  }
  s = reduced;
  return sub.point;
}

// Turns the closest points of the cores into those of the shapes grown by their margins.
GjkResult applyMargins(const Vector3D& coreA, const Vector3D& coreB, double coreDistance,
                       double marginA, double marginB) {
  GjkResult r;
  const double margin = marginA + marginB;
  if (coreDistance > margin) {
    const Vector3D n = (coreB - coreA) / coreDistance;
    r.distance = coreDistance - margin;
    r.pointA = coreA + marginA * n;
    r.pointB = coreB - marginB * n;
    return r;
  }
  r.distance = 0.0;
  if (coreDistance > 0.0) {
    // A point within marginA of coreA and within marginB of coreB.
    r.pointA = coreA + (coreB - coreA) * (marginA / margin);
  } else {
    r.pointA = 0.5 * (coreA + coreB);
  }
  r.pointB = r.pointA;
  return r;
}

}  // namespace

GjkResult gjkDistance(const ConvexShape& a, const ConvexShape& b, const Transform3D& X_ab,
                      double stopBelow, double stopAbove) {
  const auto R = X_ab.linear();
  const Vector3D t = X_ab.translation();
  const double margin = a.margin() + b.margin();
  Simplex s;
  s.size = 1;
  s.v[0].a = a.corePoint();
  s.v[0].b = R * b.corePoint() + t;
  s.v[0].w = s.v[0].a - s.v[0].b;
  s.lambda[0] = 1.0;
  Vector3D v = s.v[0].w;
  bool overlap = false;
  std::int32_t hintA = -1;
  std::int32_t hintB = -1;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const double vv = v.squaredNorm();
    if (vv <= kTinySquaredNorm) {
      overlap = true;
      break;
    }
    if (std::sqrt(vv) - margin <= stopBelow) break;
    const Vector3D pa = a.support(-v, hintA);
    const Vector3D pb = R * b.support(R.transpose() * v, hintB) + t;
    const Vector3D w = pa - pb;
    const double vw = v.dot(w);
    if (vw > 0.0) {
      const double lowerBound = vw / std::sqrt(vv) - margin;
      if (lowerBound > stopAbove) {
        GjkResult r;
        r.distance = lowerBound;
        r.exceeded = true;
        return r;
      }
    }
    if (vv - vw <= kRelativeTolerance * vv) break;
    s.v[static_cast<std::size_t>(s.size)] = SimplexVertex{w, pa, pb};
    ++s.size;
    v = reduce(s);
    if (s.size == 4) {
      overlap = true;
      break;
    }
    if (v.squaredNorm() >= vv) break;
  }
  Vector3D coreA = Vector3D::Zero();
  Vector3D coreB = Vector3D::Zero();
  for (int n = 0; n < s.size; ++n) {
    const auto un = static_cast<std::size_t>(n);
    coreA += s.lambda[un] * s.v[un].a;
    coreB += s.lambda[un] * s.v[un].b;
  }
  const double coreDistance = overlap ? 0.0 : v.norm();
  return applyMargins(coreA, coreB, coreDistance, a.margin(), b.margin());
}

}  // namespace rw::proximity
