#include "visgrab/objects/convex_decomposition.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "visgrab/objects/convex_hull.hpp"

namespace visgrab::objects {

namespace {

using rw::math::Vector3D;

// A triangle of a part. `surface`: a piece of the input mesh (else of a cut's cap fan, whose
// triangles may reach outside the part and only integrate correctly with their signs).
struct Triangle {
  std::array<Vector3D, 3> v;
  bool surface = true;
};

// A part: a triangle soup whose signed integrals equal those of the solid part.
struct Part {
  std::vector<Triangle> triangles;
  double volume = 0.0;
  double hullVolume = 0.0;
  bool final = false;
};

double soupVolume(const std::vector<Triangle>& soup) {
  double six = 0.0;
  for (const Triangle& t : soup) six += t.v[0].dot(t.v[1].cross(t.v[2]));
  return six / 6.0;
}

std::vector<Vector3D> surfacePoints(const std::vector<Triangle>& soup) {
  std::vector<Vector3D> points;
  for (const Triangle& t : soup) {
    if (t.surface) points.insert(points.end(), t.v.begin(), t.v.end());
  }
  return points;
}

// Hull volume of `points`, or `fallback` when they span no volume.
double hullVolumeOf(const std::vector<Vector3D>& points, double fallback) {
  try {
    return meshVolume(convexHull(points));
  } catch (const std::invalid_argument&) {
    return fallback;
  }
}

// The part of `soup` where n.x <= d, its cut closed by a fan over the cut segments.
std::vector<Triangle> clip(const std::vector<Triangle>& soup, const Vector3D& n, double d) {
  std::vector<Triangle> out;
  std::vector<std::array<Vector3D, 2>> segments;  // the cap's boundary, oriented for the cap
  for (const Triangle& t : soup) {
    std::array<double, 3> s{};
    int inside = 0;
    for (int i = 0; i < 3; ++i) {
      s[static_cast<std::size_t>(i)] = n.dot(t.v[static_cast<std::size_t>(i)]) - d;
      if (s[static_cast<std::size_t>(i)] <= 0.0) ++inside;
    }
    if (inside == 3) {
      out.push_back(t);
      continue;
    }
    if (inside == 0) continue;
    std::array<Vector3D, 4> polygon;
    int count = 0;
    Vector3D exit = Vector3D::Zero();
    Vector3D entry = Vector3D::Zero();
    for (std::size_t i = 0; i < 3; ++i) {
      const std::size_t j = (i + 1) % 3;
      const bool in = s[i] <= 0.0;
      if (in) polygon[static_cast<std::size_t>(count++)] = t.v[i];
      if (in != (s[j] <= 0.0)) {
        const Vector3D p = t.v[i] + (s[i] / (s[i] - s[j])) * (t.v[j] - t.v[i]);
        polygon[static_cast<std::size_t>(count++)] = p;
        (in ? exit : entry) = p;
      }
    }
    for (int k = 1; k + 1 < count; ++k) {
      out.push_back({{polygon[0], polygon[static_cast<std::size_t>(k)],
                      polygon[static_cast<std::size_t>(k + 1)]},
                     t.surface});
    }
    // The kept polygon runs exit -> entry along the plane; the cap runs the other way.
    segments.push_back({entry, exit});
  }
  if (!segments.empty()) {
    const Vector3D apex = segments.front()[0];
    for (const auto& [a, b] : segments) out.push_back({{apex, a, b}, false});
  }
  return out;
}

// Solid angle of triangle (a, b, c) seen from the origin, signed (Van Oosterom and Strackee);
// 0 when the origin lies in the triangle's plane (its principal value for points on the surface).
double solidAngle(const Vector3D& a, const Vector3D& b, const Vector3D& c) {
  const double la = a.norm();
  const double lb = b.norm();
  const double lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  if (std::abs(numerator) <= 1e-12 * la * lb * lc) return 0.0;
  const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

// Generalised winding number of the soup about p: 1 inside, 0 outside, a fraction on the
// boundary (1/2 on a face).
double windingNumber(const std::vector<Triangle>& soup, const Vector3D& p) {
  double sum = 0.0;
  for (const Triangle& t : soup) sum += solidAngle(t.v[0] - p, t.v[1] - p, t.v[2] - p);
  return sum / (4.0 * std::numbers::pi);
}

// The points whose hull is the part's: its surface points and the cap points that lie on the
// part (the fans' points outside it are dropped).
std::vector<Vector3D> hullPoints(const std::vector<Triangle>& soup) {
  auto lexLess = [](const Vector3D& a, const Vector3D& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::vector<Vector3D> points = surfacePoints(soup);
  std::sort(points.begin(), points.end(), lexLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::vector<Vector3D> capPoints;
  for (const Triangle& t : soup) {
    if (!t.surface) capPoints.insert(capPoints.end(), t.v.begin(), t.v.end());
  }
  std::sort(capPoints.begin(), capPoints.end(), lexLess);
  capPoints.erase(std::unique(capPoints.begin(), capPoints.end()), capPoints.end());
  const std::size_t surface = points.size();
  for (const Vector3D& p : capPoints) {
    if (std::binary_search(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(surface), p,
                           lexLess)) {
      continue;
    }
    if (windingNumber(soup, p) > 1e-3) points.push_back(p);
  }
  return points;
}

// A part with its volume and its hull's volume. `exact`: the hull of hullPoints(); else of the
// surface points only (cheaper, for ranking candidate cuts: it leaves out the rare points
// where three cuts meet inside the mesh).
Part makePart(std::vector<Triangle> triangles, bool exact) {
  Part part;
  part.triangles = std::move(triangles);
  part.volume = soupVolume(part.triangles);
  part.hullVolume =
      hullVolumeOf(exact ? hullPoints(part.triangles) : surfacePoints(part.triangles), part.volume);
  return part;
}

// Candidate cut positions along `axis` strictly inside (lo, hi): evenly spaced, plus the part's
// own vertex coordinates (where a concave corner sits) when there are few distinct ones.
std::vector<double> cutPositions(const std::vector<Vector3D>& points, int axis, double lo,
                                 double hi, int count) {
  std::vector<double> own;
  const double margin = 1e-6 * (hi - lo);
  for (const Vector3D& p : points) {
    if (p[axis] > lo + margin && p[axis] < hi - margin) own.push_back(p[axis]);
  }
  std::sort(own.begin(), own.end());
  own.erase(std::unique(own.begin(), own.end()), own.end());
  std::vector<double> cuts;
  if (static_cast<int>(own.size()) <= 2 * count) cuts = own;  // first: they win ties
  for (int j = 1; j <= count; ++j) cuts.push_back(lo + (hi - lo) * j / (count + 1));
  // A hair off the vertices: a plane through a vertex or a face of the mesh would need the
  // triangles lying in it sorted to one side; 1e-7 of the extent leaves slivers of no weight.
  for (double& d : cuts) d += 1e-7 * (hi - lo);
  return cuts;
}

// Cuts `part` by the best axis-aligned plane; false if no cut reduces its concavity.
bool split(const Part& part, const DecompositionOptions& options, double minVolume, Part& lower,
           Part& upper) {
  const std::vector<Vector3D> points = surfacePoints(part.triangles);
  rw::geometry::Aabb box;
  for (const Vector3D& p : points) box.extend(p);
  // A cut must remove at least 1 % of the part's excess: cuts that only shuffle it (a prism cut
  // across its axis) would otherwise win by rounding.
  double best = 0.99 * (part.hullVolume - part.volume);
  bool found = false;
  for (int axis = 0; axis < 3; ++axis) {
    const Vector3D n = Vector3D::Unit(axis);
    for (const double d :
         cutPositions(points, axis, box.min[axis], box.max[axis], options.cutsPerAxis)) {
      Part a = makePart(clip(part.triangles, n, d), false);
      Part b = makePart(clip(part.triangles, -n, -d), false);
      if (a.volume < minVolume || b.volume < minVolume) continue;
      const double concavity = (a.hullVolume - a.volume) + (b.hullVolume - b.volume);
      if (concavity < best - 1e-9 * part.volume) {  // ties: the first candidate
        best = concavity;
        lower = std::move(a);
        upper = std::move(b);
        found = true;
      }
    }
  }
  if (found) {
    lower = makePart(std::move(lower.triangles), true);
    upper = makePart(std::move(upper.triangles), true);
  }
  return found;
}

}  // namespace

ConvexDecomposition decomposeConvex(const rw::geometry::TriMesh& mesh,
                                    const DecompositionOptions& options) {
  std::vector<Triangle> soup;
  soup.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    soup.push_back({{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]}, true});
  }
  ConvexDecomposition result;
  result.meshVolume = soupVolume(soup);
  if (!(result.meshVolume > 0.0)) {
    throw std::invalid_argument("decomposeConvex: the mesh has no positive volume (" +
                                std::to_string(result.meshVolume) + " m^3)");
  }
  const double minVolume = 1e-3 * result.meshVolume;
  const double smallExcess = 2e-3 * result.meshVolume;
  std::vector<Part> parts;
  parts.push_back(makePart(std::move(soup), true));
  while (static_cast<int>(parts.size()) < std::max(1, options.maxPieces)) {
    // The part with the largest excess that is still worth cutting.
    std::size_t worst = parts.size();
    double worstExcess = 0.0;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const Part& p = parts[i];
      const double excess = p.hullVolume - p.volume;
      if (p.final || excess <= options.concavity * p.volume || excess < smallExcess) continue;
      if (excess > worstExcess) {
        worstExcess = excess;
        worst = i;
      }
    }
    if (worst == parts.size()) break;
    Part lower;
    Part upper;
    if (!split(parts[worst], options, minVolume, lower, upper)) {
      parts[worst].final = true;
      continue;
    }
    parts[worst] = std::move(lower);
    parts.push_back(std::move(upper));
  }
  for (const Part& part : parts) {
    try {
      result.pieces.push_back(convexHull(hullPoints(part.triangles)));
    } catch (const std::invalid_argument&) {
      // A sliver whose points span no volume (a cut through a thin wall of a mesh that is not a
      // clean solid): nothing to collide with.
      if (part.volume >= minVolume) throw;
      ++result.flatPartsDropped;
      continue;
    }
    result.piecesVolume += meshVolume(result.pieces.back());
  }
  return result;
}

}  // namespace visgrab::objects
