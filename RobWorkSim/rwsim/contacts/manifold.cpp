#include "rwsim/contacts/manifold.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rwsim::contacts::detail {
namespace {

using Eigen::Vector2d;
using rw::math::Vector3D;
using Index = std::int32_t;

/// Chosen points closer than this (m) to the first one add nothing.
constexpr double kMinSpread = 1e-6;
/// A candidate must add at least this area (m^2) to be chosen after the first two.
constexpr double kMinArea = 1e-12;
/// Scores within this relative amount of the best count as ties (the earliest candidate wins).
constexpr double kScoreTie = 1e-9;
/// Squared distances within this fraction of the largest count as equally far.
constexpr double kFarthestTie = 1e-6;
/// Rounds of swap refinement after the greedy choice.
constexpr int kRefinePasses = 3;
/// Refinement only runs on outlines of at most this many points per chosen one; the greedy
/// choice on large, round outlines is already close to the best.
constexpr std::size_t kRefineOutline = 3;

double cross2(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Two unit tangents spanning the plane normal to `n`, chosen deterministically and without
/// jumping when n changes by rounding (the first axis n is not close to).
void tangentBasis(const Vector3D& n, Vector3D& t1, Vector3D& t2) {
  int axis = 0;
  while (axis < 2 && std::abs(n[axis]) > 0.6) ++axis;
  t1 = n.cross(Vector3D::Unit(axis)).normalized();
  t2 = n.cross(t1);
}

/// The earliest of `candidates` (not yet chosen) whose score is within kScoreTie of the
/// largest, or -1 if there is none; `bestScore` receives the largest score.
template <class Score>
Index argmaxWithTies(const std::vector<Index>& candidates, const std::vector<Index>& chosen,
                     Score score, double& bestScore, std::vector<double>& scores) {
  bestScore = -std::numeric_limits<double>::infinity();
  scores.clear();
  for (const Index i : candidates) {
    const bool taken = std::find(chosen.begin(), chosen.end(), i) != chosen.end();
    scores.push_back(taken ? -std::numeric_limits<double>::infinity() : score(i));
    bestScore = std::max(bestScore, scores.back());
  }
  if (bestScore == -std::numeric_limits<double>::infinity()) return -1;
  const double threshold = bestScore - kScoreTie * std::abs(bestScore);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (scores[k] >= threshold) return candidates[k];
  }
  return -1;
}

/// Convex hull (counter-clockwise, collinear points dropped) of the planar points `indices`,
/// written to `hull`; `sorted` is scratch.
void planarHull(const std::vector<Eigen::Vector2d>& q, const std::vector<Index>& indices,
                std::vector<Index>& sorted, std::vector<Index>& hull) {
  sorted = indices;
  std::sort(sorted.begin(), sorted.end(), [&](Index a, Index b) {
    const Vector2d& pa = q[static_cast<std::size_t>(a)];
    const Vector2d& pb = q[static_cast<std::size_t>(b)];
    if (pa.x() != pb.x()) return pa.x() < pb.x();
    if (pa.y() != pb.y()) return pa.y() < pb.y();
    return a < b;
  });
  hull.clear();
  const auto turn = [&](Index o, Index a, Index b) {
    const Vector2d& po = q[static_cast<std::size_t>(o)];
    return cross2(q[static_cast<std::size_t>(a)] - po, q[static_cast<std::size_t>(b)] - po);
  };
  for (int pass = 0; pass < 2 && !sorted.empty(); ++pass) {
    const std::size_t base = hull.size();
    for (std::size_t k = 0; k < sorted.size(); ++k) {
      const Index p = pass == 0 ? sorted[k] : sorted[sorted.size() - 1 - k];
      while (hull.size() >= base + 2 && turn(hull[hull.size() - 2], hull.back(), p) <= 0.0) {
        hull.pop_back();
      }
      hull.push_back(p);
    }
    hull.pop_back();
  }
}

/// Area of a counter-clockwise polygon of planar points.
double polygonArea(const std::vector<Eigen::Vector2d>& q, const std::vector<Index>& polygon) {
  double area = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    area += cross2(q[static_cast<std::size_t>(polygon[k])],
                   q[static_cast<std::size_t>(polygon[(k + 1) % polygon.size()])]);
  }
  return 0.5 * area;
}

/// Area added to the polygon `hull` (counter-clockwise; two points form a segment) by point q.
double areaGain(const std::vector<Eigen::Vector2d>& planar, const std::vector<Index>& h,
                const Vector2d& q) {
  const auto at = [&](std::size_t k) -> const Vector2d& {
    return planar[static_cast<std::size_t>(h[k % h.size()])];
  };
  if (h.size() < 2) return 0.0;
  if (h.size() == 2) return 0.5 * std::abs(cross2(at(1) - at(0), q - at(0)));
  double gain = 0.0;
  for (std::size_t k = 0; k < h.size(); ++k) {
    gain += 0.5 * std::max(0.0, -cross2(at(k + 1) - at(k), q - at(k)));
  }
  return gain;
}

/// Adds point q to the counter-clockwise hull h of chosen points (at least two; q outside it):
/// the edges q sees are replaced by two edges through q.
void insertIntoHull(const std::vector<Eigen::Vector2d>& planar, std::vector<Index>& h, Index q,
                    std::vector<Index>& scratch) {
  const auto at = [&](std::size_t k) -> const Vector2d& {
    return planar[static_cast<std::size_t>(h[k % h.size()])];
  };
  const Vector2d& p = planar[static_cast<std::size_t>(q)];
  if (h.size() == 2) {
    const bool left = cross2(at(1) - at(0), p - at(0)) > 0.0;
    scratch.assign(3, h[0]);
    scratch[1] = left ? h[1] : q;
    scratch[2] = left ? q : h[1];
    h.swap(scratch);
    return;
  }
  const std::size_t n = h.size();
  const auto visible = [&](std::size_t k) { return cross2(at(k + 1) - at(k), p - at(k)) < 0.0; };
  std::size_t first = n;
  for (std::size_t k = 0; k < n; ++k) {
    if (visible(k) && !visible(k + n - 1)) first = k;
  }
  if (first == n) return;
  std::size_t last = first;
  while (visible(last + 1) && (last + 1) % n != first) ++last;
  scratch.clear();
  for (std::size_t k = last + 1;; ++k) {
    scratch.push_back(h[k % n]);
    if (k % n == first) break;
  }
  scratch.push_back(q);
  h.swap(scratch);
}

/// Greedy choice after the first point: the farthest outline point, then those adding most
/// area.
void chooseGreedily(ReduceScratch& s, std::size_t limit) {
  const Vector2d origin = s.planar[static_cast<std::size_t>(s.chosen[0])];
  double score = 0.0;
  const Index second = argmaxWithTies(
      s.outline, s.chosen,
      [&](Index i) { return (s.planar[static_cast<std::size_t>(i)] - origin).squaredNorm(); },
      score, s.scores);
  if (second < 0 || score <= kMinSpread * kMinSpread) return;
  s.chosen.push_back(second);
  s.hull.assign(2, s.chosen[0]);
  s.hull[1] = second;
  while (s.chosen.size() < limit) {
    const Index next = argmaxWithTies(
        s.outline, s.chosen,
        [&](Index i) { return areaGain(s.planar, s.hull, s.planar[static_cast<std::size_t>(i)]); },
        score, s.scores);
    if (next < 0 || score <= kMinArea) break;
    s.chosen.push_back(next);
    insertIntoHull(s.planar, s.hull, next, s.sorted);
  }
}

/// Swaps chosen points for outline points while that grows the area (small outlines only);
/// the first point only for one as deep (within kDepthTie). The area with point c replaced by q is
/// the area of the others' hull plus what q adds to it.
void refineBySwaps(ReduceScratch& s) {
  if (s.chosen.size() < 3 || s.outline.size() <= s.chosen.size() ||
      s.outline.size() > kRefineOutline * s.chosen.size()) {
    return;
  }
  double area = polygonArea(s.planar, s.hull);
  for (int pass = 0; pass < kRefinePasses; ++pass) {
    bool improved = false;
    for (std::size_t c = 0; c < s.chosen.size(); ++c) {
      s.others.clear();
      for (std::size_t k = 0; k < s.chosen.size(); ++k) {
        if (k != c) s.others.push_back(s.chosen[k]);
      }
      planarHull(s.planar, s.others, s.sorted, s.trial);
      const double base = s.trial.size() >= 3 ? polygonArea(s.planar, s.trial) : 0.0;
      Index best = -1;
      double bestArea = area + kMinArea + kScoreTie * area;
      for (const Index q : s.outline) {
        if (c == 0 && s.tiedDeepest[static_cast<std::size_t>(q)] == 0) continue;
        if (std::find(s.chosen.begin(), s.chosen.end(), q) != s.chosen.end()) continue;
        const double trialArea =
            base + areaGain(s.planar, s.trial, s.planar[static_cast<std::size_t>(q)]);
        if (trialArea > bestArea) {
          bestArea = trialArea;
          best = q;
        }
      }
      if (best < 0) continue;
      s.chosen[c] = best;
      area = bestArea;
      improved = true;
    }
    if (!improved) break;
  }
}

/// The first point: among the deepest (within kDepthTie), the farthest from the candidates'
/// centroid (an extreme point), ties broken by position along the first tangent.
Index firstPoint(ReduceScratch& s) {
  Vector2d centroid = Vector2d::Zero();
  for (const Vector2d& q : s.planar) centroid += q;
  centroid /= static_cast<double>(s.planar.size());
  double farthest = 0.0;
  for (std::size_t i = 0; i < s.planar.size(); ++i) {
    if (s.tiedDeepest[i] != 0)
      farthest = std::max(farthest, (s.planar[i] - centroid).squaredNorm());
  }
  const double threshold = farthest * (1.0 - kFarthestTie);
  double score = 0.0;
  return argmaxWithTies(
      s.all, s.chosen,
      [&](Index i) {
        const auto k = static_cast<std::size_t>(i);
        if (s.tiedDeepest[k] == 0 || (s.planar[k] - centroid).squaredNorm() < threshold) {
          return -std::numeric_limits<double>::infinity();
        }
        return s.planar[k].x() + 1e-3 * s.planar[k].y();
      },
      score, s.scores);
}

}  // namespace

void reduceManifold(std::span<const ContactPoint> points, const Vector3D& normal, int maxPoints,
                    std::vector<ContactPoint>& out, ReduceScratch& s) {
  if (points.empty()) return;
  const auto limit = static_cast<std::size_t>(std::max(1, maxPoints));
  Vector3D t1;
  Vector3D t2;
  tangentBasis(normal, t1, t2);
  s.planar.clear();
  s.all.clear();
  s.tiedDeepest.clear();
  double deepest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    s.planar.emplace_back(points[i].position.dot(t1), points[i].position.dot(t2));
    s.all.push_back(static_cast<Index>(i));
    deepest = std::max(deepest, points[i].depth);
  }
  for (const ContactPoint& p : points) s.tiedDeepest.push_back(p.depth >= deepest - kDepthTie);
  s.chosen.clear();
  s.chosen.push_back(firstPoint(s));
  if (limit >= 2 && points.size() >= 2) {
    planarHull(s.planar, s.all, s.sorted, s.outline);
    // Candidate order (not coordinate order) decides ties: it does not change with rounding.
    std::sort(s.outline.begin(), s.outline.end());
    chooseGreedily(s, limit);
    refineBySwaps(s);
  }
  for (const Index i : s.chosen) out.push_back(points[static_cast<std::size_t>(i)]);
}

void clusterAndReduce(std::span<const ContactPoint> points, int maxPoints,
                      std::vector<ContactPoint>& out, ReduceScratch& s) {
  const double cosLimit = std::cos(kClusterAngle);
  s.cluster.clear();
  s.clusterNormal.clear();
  s.clusterSum.clear();
  for (const ContactPoint& p : points) {
    Index c = 0;
    while (static_cast<std::size_t>(c) < s.clusterNormal.size() &&
           s.clusterNormal[static_cast<std::size_t>(c)].dot(p.normal) < cosLimit) {
      ++c;
    }
    if (static_cast<std::size_t>(c) == s.clusterNormal.size()) {
      s.clusterNormal.push_back(p.normal);
      s.clusterSum.emplace_back(Vector3D::Zero());
    }
    s.clusterSum[static_cast<std::size_t>(c)] += p.normal;
    s.cluster.push_back(c);
  }
  for (std::size_t c = 0; c < s.clusterNormal.size(); ++c) {
    s.members.clear();
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (s.cluster[i] == static_cast<Index>(c)) s.members.push_back(points[i]);
    }
    const Vector3D& sum = s.clusterSum[c];
    const Vector3D n = sum.squaredNorm() > 0.0 ? Vector3D(sum.normalized()) : s.clusterNormal[c];
    reduceManifold(s.members, n, maxPoints, out, s);
  }
}

}  // namespace rwsim::contacts::detail
