#include "rw/graspplanning/grasp_wrench_space.hpp"

#include <libqhull_r/libqhull_r.h>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "rw/common/memory_stream.hpp"

namespace rw::graspplanning {
namespace {

using rw::math::Vector3D;

constexpr std::array<std::string_view, 6> kStatusNames = {
    "ForceClosure", "NotForceClosure", "TooFewPoints", "Flat", "InvalidInput", "QhullError"};
static_assert(kStatusNames.size() == static_cast<std::size_t>(GwsStatus::kQhullError) + 1,
              "kStatusNames must name every GwsStatus");

// A 6-D hull needs at least 7 affinely independent points.
constexpr int kMinHullPoints = 7;
// Contacts closer than this (position in metres, unit normal, mu, force) count as one contact.
constexpr double kDuplicateTolerance = 1e-9;
// The origin counts as strictly inside only if every facet is farther than this, relative to the
// largest wrench norm; it absorbs Qhull's rounding (qh.DISTround is ~4e-15 here). The same bound
// decides flatness: all points lie within sigma_min (smallest singular value of the centred
// points) of a hyperplane, so epsilon <= sigma_min, and a set with sigma_min below the bound could
// only have an epsilon we would report as 0 anyway.
constexpr double kInsideTolerance = 1e-12;

// Qhull options, chosen deliberately. First try (exact):
//  - no "QJ": joggling perturbs the input (by ~1e-10 here), so epsilon would no longer be exact to
//    rounding, and it turns a flat wrench set into a sliver with a tiny, meaningless epsilon.
//  - "Qx C-0" (Qhull's defaults in 5-D and up, spelled out): exact pre-merges and merging of
//    facets whose hyperplanes agree within rounding, so facet offsets stay exact to rounding.
//  - no "Qt": triangulating merged facets only splits them into pieces with the same
//    hyperplane, so it cannot change epsilon, and costs time.
//  - no output options: we read facet->normal/offset directly (unit outward normal, inside
//    points have normal . x + offset < 0).
// Flat sets never reach Qhull (see flatness()). Nearly flat ones (thickness ~1e-8) can still
// make merging fail (QH6347 wide merge, QH6271 dupridge); Qhull's own remedy is joggle, so we
// retry with "QJ QR-2": "QR-2" fixes the random seed at 2 without rotating the input, so the
// retry is deterministic too. Such sets have epsilon <= their thickness, i.e. tiny.
// With a fixed input order (we sort it) both runs are deterministic. The lazy hull
// (runQhullLazy) uses the exact options too; Qhull's incremental qh_addpoint needs no joggle.
constexpr char kExactOptions[] = "qhull Qx C-0";
constexpr char kJoggleOptions[] = "qhull QJ QR-2";

// RobWork's tangent choice for a unit normal (GWSMeasure3D): it fixes the cone's edge pattern.
Vector3D tangentOf(const Vector3D& n) {
  constexpr double kAxisTolerance = 1e-6;
  if (std::abs(n.x()) < kAxisTolerance && std::abs(n.y()) < kAxisTolerance) {
    return Vector3D(0.0, -n.z(), n.y()).normalized();
  }
  return Vector3D(-n.y(), n.x(), 0.0).normalized();
}

// A linearised friction cone: edges scale * (axis + mu * unit tangent), applied at position.
struct Cone {
  Vector3D position;
  Vector3D axis;  // unit
  double mu = 0.0;
  double scale = 1.0;
  int cluster = -1;
};

// Axis (not normalised) and scale of a contact's cone under `force`.
std::pair<Vector3D, double> axisAndScale(const Contact3D& c, GwsForce force) {
  switch (force) {
    case GwsForce::kMeasuredNormalForce:
      return {c.normal, c.normalForce};
    case GwsForce::kMeasuredForce:
      return {c.force, c.force.norm()};
    case GwsForce::kUnitNormal:
      break;
  }
  return {c.normal, 1.0};
}

bool allFinite(const Contact3D& c, GwsForce force) {
  const bool finite = c.position.allFinite() && c.normal.allFinite() && std::isfinite(c.mu);
  switch (force) {
    case GwsForce::kMeasuredNormalForce:
      return finite && std::isfinite(c.normalForce);
    case GwsForce::kMeasuredForce:
      return finite && c.force.allFinite();
    case GwsForce::kUnitNormal:
      break;
  }
  return finite;
}

// Checks the contacts and turns them into cones; drops cones with a measured force below
// kGwsMinForce. nullopt if invalid.
std::optional<std::vector<Cone>> validCones(std::span<const Contact3D> contacts, const Vector3D& c,
                                            double r, GwsForce force) {
  if (!c.allFinite() || !std::isfinite(r) || r <= 0.0) return std::nullopt;
  std::vector<Cone> out;
  out.reserve(contacts.size());
  for (const Contact3D& contact : contacts) {
    if (!allFinite(contact, force) || contact.mu < 0.0) return std::nullopt;
    if (!(contact.normal.norm() > 1e-12)) return std::nullopt;
    if (force == GwsForce::kMeasuredNormalForce && contact.normalForce < 0.0) return std::nullopt;
    const auto [axis, scale] = axisAndScale(contact, force);
    if (force != GwsForce::kUnitNormal && scale < kGwsMinForce) continue;
    out.push_back(Cone{contact.position, axis / axis.norm(), contact.mu, scale, contact.cluster});
  }
  return out;
}

std::array<double, 9> sortKey(const Cone& c) {
  return {c.position.x(), c.position.y(), c.position.z(),
          c.axis.x(),     c.axis.y(),     c.axis.z(),
          c.mu,           c.scale,        static_cast<double>(c.cluster)};
}

bool sameCone(const Cone& a, const Cone& b) {
  return (a.position - b.position).norm() <= kDuplicateTolerance &&
         (a.axis - b.axis).norm() <= kDuplicateTolerance &&
         std::abs(a.mu - b.mu) <= kDuplicateTolerance &&
         std::abs(a.scale - b.scale) <= kDuplicateTolerance && a.cluster == b.cluster;
}

// Sorts cones lexicographically (a canonical order) and keeps the first of near-duplicates.
std::vector<Cone> canonicalCones(std::vector<Cone> cones) {
  std::sort(cones.begin(), cones.end(),
            [](const Cone& a, const Cone& b) { return sortKey(a) < sortKey(b); });
  std::vector<Cone> kept;
  for (const Cone& c : cones) {
    const bool duplicate =
        std::any_of(kept.begin(), kept.end(), [&](const Cone& k) { return sameCone(k, c); });
    if (!duplicate) kept.push_back(c);
  }
  return kept;
}

// One cone per cluster id >= 0 (scale-weighted means, summed scale); cones of cluster -1 stay.
// The input is canonical, so each sum runs in a fixed order; the output is canonical again.
std::vector<Cone> mergeClusters(const std::vector<Cone>& cones) {
  std::vector<Cone> out;
  std::vector<int> done;
  for (std::size_t i = 0; i < cones.size(); ++i) {
    const int id = cones[i].cluster;
    if (id < 0) {
      out.push_back(cones[i]);
      continue;
    }
    if (std::find(done.begin(), done.end(), id) != done.end()) continue;
    done.push_back(id);
    Vector3D position = Vector3D::Zero();
    Vector3D axis = Vector3D::Zero();
    double mu = 0.0;
    double scale = 0.0;
    for (std::size_t j = i; j < cones.size(); ++j) {
      const Cone& c = cones[j];
      if (c.cluster != id) continue;
      position += c.scale * c.position;
      axis += c.scale * c.axis;
      mu += c.scale * c.mu;
      scale += c.scale;
    }
    // A cluster whose axes cancel has no direction; keep its first cone's.
    const double length = axis.norm();
    out.push_back(Cone{position / scale, length > 1e-12 ? Vector3D(axis / length) : cones[i].axis,
                       mu / scale, scale, id});
  }
  return canonicalCones(std::move(out));
}

// Uniform double in [-a, a] from the top 53 bits of one draw (the same on every platform, unlike
// std::uniform_real_distribution).
double jitter(std::mt19937_64& rng, double a) {
  const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return a * (2.0 * u - 1.0);
}

// The VisGraB-era rule: each cone followed by a jittered copy (see GwsOptions).
std::vector<Cone> withJitteredCopies(const std::vector<Cone>& cones, const GwsOptions& options) {
  std::mt19937_64 rng(options.jitterSeed);
  std::vector<Cone> out;
  out.reserve(2 * cones.size());
  for (const Cone& c : cones) {
    out.push_back(c);
    Cone copy = c;
    for (int k = 0; k < 3; ++k) copy.axis(k) += jitter(rng, options.jitterAxis);
    for (int k = 0; k < 3; ++k) copy.position(k) += jitter(rng, options.jitterPosition);
    const double length = copy.axis.norm();
    copy.axis = length > 1e-12 ? Vector3D(copy.axis / length) : c.axis;
    out.push_back(copy);
  }
  return out;
}

bool lexLess(const Wrench6D& a, const Wrench6D& b) {
  return std::lexicographical_compare(a.data(), a.data() + 6, b.data(), b.data() + 6);
}

// Sorted, exactly deduplicated points with -0.0 turned into +0.0: Qhull's canonical input.
std::vector<Wrench6D> canonicalPoints(std::span<const Wrench6D> wrenches) {
  std::vector<Wrench6D> points(wrenches.begin(), wrenches.end());
  for (Wrench6D& w : points) w.array() += 0.0;
  std::sort(points.begin(), points.end(), lexLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

// Smallest singular value of the centred points: their largest distance from a hyperplane is at
// most this. JacobiSVD resolves it to ~1e-16 of the largest (a 6x6 scatter matrix would not).
double flatness(const std::vector<Wrench6D>& points) {
  Eigen::Matrix<double, Eigen::Dynamic, 6> centred(static_cast<Eigen::Index>(points.size()), 6);
  Wrench6D mean = Wrench6D::Zero();
  for (const Wrench6D& w : points) mean += w;
  mean /= static_cast<double>(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    centred.row(static_cast<Eigen::Index>(i)) = (points[i] - mean).transpose();
  }
  return Eigen::JacobiSVD<Eigen::Matrix<double, Eigen::Dynamic, 6>>(centred).singularValues()(5);
}

struct HullOutcome {
  int exitCode = 0;
  int facets = 0;
  double minFacetDistance = 0.0;  // min over facets of -offset (signed distance of the origin)
  std::string message;
};

// Builds the 6-D hull of `points` on a private qhT (reentrant Qhull) and reads facet offsets.
HullOutcome runQhull(const std::vector<Wrench6D>& points, std::string_view qhullOptions) {
  std::vector<double> coordinates;
  coordinates.reserve(points.size() * 6);
  for (const Wrench6D& w : points) coordinates.insert(coordinates.end(), w.data(), w.data() + 6);
  std::string options(qhullOptions);  // qh_new_qhull takes a mutable C string
  HullOutcome out;
  rw::common::MemoryStream errors;
  auto qh = std::make_unique<qhT>();
  qh_zero(qh.get(), errors.file());
  out.exitCode = qh_new_qhull(qh.get(), 6, static_cast<int>(points.size()), coordinates.data(),
                              False, options.data(), nullptr, errors.file());
  if (out.exitCode == qh_ERRnone) {
    double minDistance = std::numeric_limits<double>::infinity();
    for (facetT* f = qh->facet_list; f != nullptr && f->next != nullptr; f = f->next) {
      minDistance = std::min(minDistance, -f->offset);
      ++out.facets;
    }
    out.minFacetDistance = minDistance;
  } else {
    out.message = errors.text();
  }
  qh_freeqhull(qh.get(), !qh_ALL);
  int curLong = 0;
  int totLong = 0;
  qh_memfreeshort(qh.get(), &curLong, &totLong);
  return out;
}

// Adds `point` to the hull if Qhull finds it outside. Qhull reports errors with longjmp, so
// nothing here may need a destructor. Returns Qhull's exit code (0: fine).
int addPoint(qhT* qh, double* point) {
  const int exitCode = setjmp(qh->errexit);
  if (exitCode == 0) {
    qh->NOerrexit = False;
    realT distance = 0.0;
    boolT outside = False;
    facetT* facet = qh_findbestfacet(qh, point, !qh_ALL, &distance, &outside);
    if (outside) {
      // A point outside qh_new_qhull's array goes into other_points, so qh_pointid knows it.
      qh_setappend(qh, &qh->other_points, point);
      qh_addpoint(qh, point, facet, !qh_ALL);
    }
  }
  qh->NOerrexit = True;
  return exitCode;
}

// Index of the first point with the largest dot product with `direction`.
std::size_t supportIndex(const std::vector<Wrench6D>& points, const Wrench6D& direction) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (direction.dot(points[i]) > direction.dot(points[best])) best = i;
  }
  return best;
}

// Where the lazy hull starts: the support points of the 12 directions +-e_i; while they span
// fewer than 6 dimensions (smallest singular value of the centred points <= tolerance), also the
// support points of +-v, v the direction they are flat in (at most 6 times). Ascending, distinct;
// empty if no full-dimensional start was found.
std::vector<std::size_t> lazyStart(const std::vector<Wrench6D>& points, double tolerance) {
  std::vector<std::size_t> chosen;
  auto add = [&](const Wrench6D& direction) {
    const std::size_t i = supportIndex(points, direction);
    if (std::find(chosen.begin(), chosen.end(), i) != chosen.end()) return false;
    chosen.push_back(i);
    return true;
  };
  for (int axis = 0; axis < 6; ++axis) {
    add(Wrench6D::Unit(axis));
    add(-Wrench6D::Unit(axis));
  }
  for (int round = 0; round < 6; ++round) {
    Eigen::Matrix<double, Eigen::Dynamic, 6> centred(static_cast<Eigen::Index>(chosen.size()), 6);
    Wrench6D mean = Wrench6D::Zero();
    for (const std::size_t i : chosen) mean += points[i];
    mean /= static_cast<double>(chosen.size());
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      centred.row(static_cast<Eigen::Index>(k)) = (points[chosen[k]] - mean).transpose();
    }
    const Eigen::JacobiSVD<Eigen::Matrix<double, Eigen::Dynamic, 6>> svd(centred,
                                                                         Eigen::ComputeFullV);
    if (chosen.size() >= static_cast<std::size_t>(kMinHullPoints) &&
        svd.singularValues()(5) > tolerance) {
      std::sort(chosen.begin(), chosen.end());
      return chosen;
    }
    const Wrench6D flat = svd.matrixV().col(5);
    const bool grew = add(flat);
    if (!add(-flat) && !grew) break;
  }
  return {};
}

// Epsilon by a lazily grown hull (the expanding-polytope idea of EPA, with Qhull keeping the
// hull): start from lazyStart(); repeat: take the facet nearest to the origin
// (signed: negative when the origin is beyond it); if no point of `points` lies more than
// `tolerance` beyond its hyperplane, that hyperplane supports the whole set, so the set's
// epsilon is at most its distance, and at least it, because the partial hull lies inside the
// whole hull: done; else add the point farthest beyond it. Exact like the full hull (to
// `tolerance`), but the partial hull usually has far fewer facets. exitCode -1 when it does
// not apply (the start is flat or Qhull does not take a point it should): use the full hull.
HullOutcome runQhullLazy(const std::vector<Wrench6D>& points, std::string_view qhullOptions,
                         double tolerance) {
  HullOutcome out;
  out.exitCode = -1;
  const std::vector<std::size_t> start = lazyStart(points, tolerance);
  if (start.empty()) return out;
  std::vector<Wrench6D> startPoints;
  for (const std::size_t i : start) startPoints.push_back(points[i]);
  std::vector<double> coordinates;
  coordinates.reserve(points.size() * 6);
  for (const Wrench6D& w : points) coordinates.insert(coordinates.end(), w.data(), w.data() + 6);
  std::vector<double> startCoordinates;
  for (const Wrench6D& w : startPoints) {
    startCoordinates.insert(startCoordinates.end(), w.data(), w.data() + 6);
  }
  std::vector<bool> added(points.size(), false);
  for (const std::size_t i : start) added[i] = true;
  std::string options(qhullOptions);
  rw::common::MemoryStream errors;
  auto qh = std::make_unique<qhT>();
  qh_zero(qh.get(), errors.file());
  out.exitCode =
      qh_new_qhull(qh.get(), 6, static_cast<int>(startPoints.size()), startCoordinates.data(),
                   False, options.data(), nullptr, errors.file());
  while (out.exitCode == qh_ERRnone) {
    facetT* nearest = nullptr;
    int facets = 0;
    for (facetT* f = qh->facet_list; f != nullptr && f->next != nullptr; f = f->next) {
      if (nearest == nullptr || -f->offset < -nearest->offset) nearest = f;
      ++facets;
    }
    if (nearest == nullptr) {
      out.exitCode = -1;
      break;
    }
    const Eigen::Map<const Wrench6D> normal(nearest->normal);
    std::size_t farthest = 0;
    double beyond = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double d = normal.dot(points[i]) + nearest->offset;
      if (d > beyond) {
        beyond = d;
        farthest = i;
      }
    }
    if (beyond <= tolerance) {
      out.facets = facets;
      out.minFacetDistance = -nearest->offset;
      break;
    }
    if (added[farthest]) {
      out.exitCode = -1;
      break;
    }
    added[farthest] = true;
    out.exitCode = addPoint(qh.get(), coordinates.data() + 6 * farthest);
  }
  if (out.exitCode > 0) out.message = errors.text();
  qh_freeqhull(qh.get(), !qh_ALL);
  int curLong = 0;
  int totLong = 0;
  qh_memfreeshort(qh.get(), &curLong, &totLong);
  return out;
}

// Epsilon of a canonical point set with at least kMinHullPoints points.
GwsResult hullEpsilon(const std::vector<Wrench6D>& points, GwsHull method) {
  GwsResult result;
  result.points = static_cast<int>(points.size());
  double maxNorm = 0.0;
  for (const Wrench6D& w : points) maxNorm = std::max(maxNorm, w.norm());
  const double thickness = flatness(points);
  if (thickness <= kInsideTolerance * maxNorm) {
    std::ostringstream detail;
    detail << "wrench points span fewer than 6 dimensions (smallest singular value " << thickness
           << ")";
    result.status = GwsStatus::kFlat;
    result.detail = detail.str();
    return result;
  }
  HullOutcome hull;
  hull.exitCode = -1;
  if (method == GwsHull::kLazy) {
    hull = runQhullLazy(points, kExactOptions, kInsideTolerance * maxNorm);
  }
  if (hull.exitCode != qh_ERRnone) {
    result.wholeHull = true;
    hull = runQhull(points, kExactOptions);
  }
  if (hull.exitCode != qh_ERRnone) {
    result.joggled = true;
    hull = runQhull(points, kJoggleOptions);
  }
  if (hull.exitCode != qh_ERRnone) {
    result.status = hull.exitCode == qh_ERRsingular ? GwsStatus::kFlat : GwsStatus::kQhullError;
    result.detail = std::move(hull.message);
    return result;
  }
  result.facets = hull.facets;
  if (hull.minFacetDistance > kInsideTolerance * maxNorm) {
    result.epsilon = hull.minFacetDistance;
    result.forceClosure = true;
    result.status = GwsStatus::kForceClosure;
  } else {
    result.status = GwsStatus::kNotForceClosure;
  }
  return result;
}

// The edge wrenches of each cone, `edges` per cone, in cone order.
std::vector<Wrench6D> coneWrenches(const std::vector<Cone>& cones, const Vector3D& centerOfMass,
                                   double maxRadius, int edges) {
  std::vector<Wrench6D> wrenches;
  wrenches.reserve(cones.size() * static_cast<std::size_t>(edges));
  for (const Cone& c : cones) {
    const Vector3D& n = c.axis;
    const Vector3D t = tangentOf(n);
    const Vector3D b = n.cross(t);
    const Vector3D arm = c.position - centerOfMass;
    for (int k = 0; k < edges; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / edges;
      const Vector3D f = c.scale * (n + c.mu * (std::cos(angle) * t + std::sin(angle) * b));
      Wrench6D w;
      w.head<3>() = f;
      w.tail<3>() = arm.cross(f) / maxRadius;
      wrenches.push_back(w);
    }
  }
  return wrenches;
}

}  // namespace

std::string_view toString(GwsStatus status) {
  return kStatusNames.at(static_cast<std::size_t>(status));
}

std::vector<Wrench6D> contactWrenches(std::span<const Contact3D> contacts,
                                      const Vector3D& centerOfMass, double maxRadius,
                                      const GwsOptions& options) {
  if (options.coneEdges < 3)
    throw std::invalid_argument("GwsOptions::coneEdges must be at least 3");
  std::vector<Cone> cones;
  cones.reserve(contacts.size());
  for (const Contact3D& c : contacts) {
    const auto [axis, scale] = axisAndScale(c, options.force);
    cones.push_back(Cone{c.position, axis.normalized(), c.mu, scale, c.cluster});
  }
  return coneWrenches(cones, centerOfMass, maxRadius, options.coneEdges);
}

GwsResult gwsEpsilon(std::span<const Contact3D> contacts, const Vector3D& centerOfMass,
                     double maxRadius, const GwsOptions& options) {
  if (options.coneEdges < 3) {
    throw std::invalid_argument("GwsOptions::coneEdges must be at least 3");
  }
  if (options.duplicateBelow < 0) {
    throw std::invalid_argument("GwsOptions::duplicateBelow must not be negative");
  }
  const auto valid = validCones(contacts, centerOfMass, maxRadius, options.force);
  if (!valid) {
    GwsResult result;
    result.status = GwsStatus::kInvalidInput;
    return result;
  }
  std::vector<Cone> cones = canonicalCones(*valid);
  if (options.mergeClusters) cones = mergeClusters(cones);
  if (static_cast<int>(cones.size()) < options.duplicateBelow) {
    cones = withJitteredCopies(cones, options);
  }
  GwsResult result = gwsEpsilonOfWrenches(
      coneWrenches(cones, centerOfMass, maxRadius, options.coneEdges), options.hull);
  result.cones = static_cast<int>(cones.size());
  return result;
}

GwsResult gwsEpsilonOfWrenches(std::span<const Wrench6D> wrenches, GwsHull hull) {
  const bool finite = std::all_of(wrenches.begin(), wrenches.end(),
                                  [](const Wrench6D& w) { return w.allFinite(); });
  GwsResult result;
  if (!finite) {
    result.status = GwsStatus::kInvalidInput;
    return result;
  }
  const std::vector<Wrench6D> points = canonicalPoints(wrenches);
  if (points.size() < static_cast<std::size_t>(kMinHullPoints)) {
    result.points = static_cast<int>(points.size());
    result.status = GwsStatus::kTooFewPoints;
    return result;
  }
  return hullEpsilon(points, hull);
}

}  // namespace rw::graspplanning
