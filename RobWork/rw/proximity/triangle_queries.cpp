#include "rw/proximity/triangle_queries.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rw::proximity {

using rw::math::Vector3D;

Vector3D closestPointOnTriangle(const Vector3D& p, const Triangle& t) {
  const Vector3D& a = t.v[0];
  const Vector3D& b = t.v[1];
  const Vector3D& c = t.v[2];
  const Vector3D ab = b - a;
  const Vector3D ac = c - a;
  const Vector3D ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vector3D bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double den = d1 - d3;
    return den > 0.0 ? Vector3D(a + (d1 / den) * ab) : a;
  }
  const Vector3D cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double den = d2 - d6;
    return den > 0.0 ? Vector3D(a + (d2 / den) * ac) : a;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double den = (d4 - d3) + (d5 - d6);
    return den > 0.0 ? Vector3D(b + ((d4 - d3) / den) * (c - b)) : b;
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    // Degenerate triangle: the nearest of its edges.
    Vector3D best = a;
    double bestSquared = (p - a).squaredNorm();
    const std::array<std::array<const Vector3D*, 2>, 3> edges{{{&a, &b}, {&b, &c}, {&c, &a}}};
    for (const auto& e : edges) {
      Vector3D onEdge;
      Vector3D onPoint;
      const double d = closestPointsOnSegments(*e[0], *e[1], p, p, onEdge, onPoint);
      if (d < bestSquared) {
        bestSquared = d;
        best = onEdge;
      }
    }
    return best;
  }
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

double closestPointsOnSegments(const Vector3D& p1, const Vector3D& q1, const Vector3D& p2,
                               const Vector3D& q2, Vector3D& c1, Vector3D& c2) {
  const Vector3D d1 = q1 - p1;
  const Vector3D d2 = q2 - p2;
  const Vector3D r = p1 - p2;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  double s = 0.0;
  double t = 0.0;
  if (a <= 0.0 && e <= 0.0) {
    // Both are points.
  } else if (a <= 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  c1 = p1 + s * d1;
  c2 = p2 + t * d2;
  return (c1 - c2).squaredNorm();
}

namespace {

// True when the projections of the triangles onto `axis` are more than `tolerance` apart.
bool separatedAlong(const Vector3D& axis, const Triangle& a, const Triangle& b,
                    const Vector3D& origin, double tolerance) {
  const double a0 = axis.dot(a.v[0] - origin);
  const double a1 = axis.dot(a.v[1] - origin);
  const double a2 = axis.dot(a.v[2] - origin);
  const double b0 = axis.dot(b.v[0] - origin);
  const double b1 = axis.dot(b.v[1] - origin);
  const double b2 = axis.dot(b.v[2] - origin);
  const double gap = std::max(std::min({b0, b1, b2}) - std::max({a0, a1, a2}),
                              std::min({a0, a1, a2}) - std::max({b0, b1, b2}));
  return gap > 0.0 && gap * gap > tolerance * tolerance * axis.squaredNorm();
}

// A point where an edge of `a` passes through the interior or boundary of `b`.
bool edgePierces(const Triangle& a, const Triangle& b, Vector3D& point) {
  const Vector3D n = (b.v[1] - b.v[0]).cross(b.v[2] - b.v[0]);
  if (n.squaredNorm() == 0.0) return false;
  std::array<double, 3> side{};
  for (std::size_t k = 0; k < 3; ++k) side[k] = n.dot(a.v[k] - b.v[0]);
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t l = (k + 1) % 3;
    if (side[k] == side[l] || (side[k] > 0.0 && side[l] > 0.0) ||
        (side[k] < 0.0 && side[l] < 0.0)) {
      continue;
    }
    const Vector3D p = a.v[k] + (side[k] / (side[k] - side[l])) * (a.v[l] - a.v[k]);
    bool inside = true;
    for (std::size_t m = 0; m < 3 && inside; ++m) {
      const Vector3D& from = b.v[m];
      const Vector3D& to = b.v[(m + 1) % 3];
      inside = (to - from).cross(p - from).dot(n) >= 0.0;
    }
    if (inside) {
      point = p;
      return true;
    }
  }
  return false;
}

void keepCloser(DistanceResult& best, double squared, const Vector3D& pa, const Vector3D& pb) {
  if (squared < best.distance) {
    best.distance = squared;
    best.pointA = pa;
    best.pointB = pb;
  }
}

}  // namespace

bool trianglesIntersect(const Triangle& a, const Triangle& b, double tolerance) {
  const Vector3D& origin = a.v[0];
  const std::array<Vector3D, 3> ea{a.v[1] - a.v[0], a.v[2] - a.v[1], a.v[0] - a.v[2]};
  const std::array<Vector3D, 3> eb{b.v[1] - b.v[0], b.v[2] - b.v[1], b.v[0] - b.v[2]};
  const Vector3D na = ea[0].cross(ea[1]);
  const Vector3D nb = eb[0].cross(eb[1]);
  if (separatedAlong(nb, a, b, origin, tolerance)) return false;
  if (separatedAlong(na, a, b, origin, tolerance)) return false;
  for (const Vector3D& u : ea) {
    for (const Vector3D& w : eb) {
      if (separatedAlong(u.cross(w), a, b, origin, tolerance)) return false;
    }
  }
  for (std::size_t k = 0; k < 3; ++k) {
    if (separatedAlong(na.cross(ea[k]), a, b, origin, tolerance)) return false;
    if (separatedAlong(nb.cross(eb[k]), a, b, origin, tolerance)) return false;
  }
  return true;
}

DistanceResult triangleDistance(const Triangle& a, const Triangle& b) {
  Vector3D pierce;
  if (edgePierces(a, b, pierce) || edgePierces(b, a, pierce)) {
    return DistanceResult{0.0, pierce, pierce};
  }
  // Disjoint (or touching) triangles: the closest pair involves a vertex or two edges.
  DistanceResult best;
  for (std::size_t k = 0; k < 3; ++k) {
    const Vector3D onB = closestPointOnTriangle(a.v[k], b);
    keepCloser(best, (onB - a.v[k]).squaredNorm(), a.v[k], onB);
    const Vector3D onA = closestPointOnTriangle(b.v[k], a);
    keepCloser(best, (onA - b.v[k]).squaredNorm(), onA, b.v[k]);
  }
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      Vector3D pa;
      Vector3D pb;
      const double d =
          closestPointsOnSegments(a.v[i], a.v[(i + 1) % 3], b.v[j], b.v[(j + 1) % 3], pa, pb);
      keepCloser(best, d, pa, pb);
    }
  }
  best.distance = std::sqrt(best.distance);
  return best;
}

}  // namespace rw::proximity
