#include "visgrab/vision/ega.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace visgrab::vision {
namespace {

constexpr double kRadPerDeg = M_PI / 180.0;

// A patch seen in its own plane: centre c, normal n, boundary points with their in-plane polar
// angle and radius about c.
struct PatchFrame {
  const SurfacePatch* patch = nullptr;
  Eigen::Vector3d c, n, e1, e2;
  struct Rim {
    Eigen::Vector3d point;
    double angle = 0.0;   // in-plane, about n, from e1 (rad, -pi..pi)
    double radius = 0.0;  // in-plane distance from c
    bool edge = false;
  };
  std::vector<Rim> rim;
  std::vector<Eigen::Vector3d> clusterPoints;
};

PatchFrame frameOf(const SceneSegmentation& s, const SurfacePatch& patch) {
  PatchFrame f;
  f.patch = &patch;
  f.c = patch.centroid;
  f.n = patch.normal;
  f.e1 = patch.axis1;
  f.e2 = patch.axis2;
  for (std::size_t k = 0; k < patch.boundary.size(); ++k) {
    const Eigen::Vector3d p = s.cloud.point(patch.boundary[k]);
    const Eigen::Vector3d d = p - f.c;
    const double x = d.dot(f.e1), y = d.dot(f.e2);
    f.rim.push_back({p, std::atan2(y, x), std::hypot(x, y), static_cast<bool>(patch.edge[k])});
  }
  for (int i : s.clusters[static_cast<std::size_t>(patch.cluster)].cells)
    f.clusterPoints.push_back(s.cloud.point(i));
  return f;
}

// In-plane unit vector at polar angle a.
Eigen::Vector3d inPlane(const PatchFrame& f, double a) {
  return std::cos(a) * f.e1 + std::sin(a) * f.e2;
}

// Smallest absolute difference of two angles (rad).
double angleBetween(double a, double b) {
  const double d = std::remainder(a - b, 2.0 * M_PI);
  return std::abs(d);
}

// The encompassing contact beyond boundary point b in outward direction o, pushing back along
// -o: `wrapDepth` behind the surface (along -n) at the object's outermost visible extent along
// o near the line through b; deeper, down to maxWrapDepth, where the object bulges further out
// (a lying cylinder's widest line), so that the finger closes on the bulge, not above it.
grasp::DesiredContact wrapContact(const PatchFrame& f, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& o, const GraspOptions& options) {
  const Eigen::Vector3d t = f.n.cross(o);
  const double atBoundary = (b - f.c).dot(o);
  double shallow = atBoundary, deep = atBoundary, deepDepth = options.wrapDepth;
  for (const auto& x : f.clusterPoints) {
    const double depth = (b - x).dot(f.n);
    if (depth < -0.003 || depth > options.maxWrapDepth) continue;
    if (std::abs((x - b).dot(t)) > options.lateralTolerance) continue;
    const double extent = (x - f.c).dot(o);
    if (depth <= options.wrapDepth) shallow = std::max(shallow, extent);
    if (extent > deep) deep = extent, deepDepth = std::max(depth, options.wrapDepth);
  }
  const bool bulges = deep > shallow + 0.003;
  const double extent = bulges ? deep : shallow;
  const double depth = bulges ? deepDepth : options.wrapDepth;
  grasp::DesiredContact contact;
  contact.position = b + (extent - atBoundary) * o - depth * f.n;
  contact.direction = -o;
  return contact;
}

// Rim point with the largest radius whose angle is within `window` of a, if any.
const PatchFrame::Rim* outermostNear(const PatchFrame& f, double a, double window, bool edgesOnly) {
  const PatchFrame::Rim* best = nullptr;
  for (const auto& r : f.rim) {
    if (edgesOnly && !r.edge) continue;
    if (angleBetween(r.angle, a) > window) continue;
    if (!best || r.radius > best->radius) best = &r;
  }
  return best;
}

// Rim point farthest from the centre along `dir` (and beyond it) among those whose offset along
// `side` is `offset` within `tolerance`; nullptr if none.
const PatchFrame::Rim* outermostOnLine(const PatchFrame& f, const Eigen::Vector3d& dir,
                                       const Eigen::Vector3d& side, double offset,
                                       double tolerance) {
  const PatchFrame::Rim* best = nullptr;
  double far = 0.0;
  for (const auto& r : f.rim) {
    const Eigen::Vector3d d = r.point - f.c;
    if (std::abs(d.dot(side) - offset) > tolerance) continue;
    if (d.dot(dir) > far) far = d.dot(dir), best = &r;
  }
  return best;
}

struct Ranker {
  const TablePlane& table;
  const GraspOptions& options;
  Eigen::Vector3d up;

  // Shared terms: evidence (patch size), approach from above, contacts clear of the table.
  // nullopt if a contact is too low.
  std::optional<double> base(const PatchFrame& f, const CandidateGrasp& g) const {
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& c : g.contacts) lowest = std::min(lowest, table.height(c.position));
    if (lowest < options.minContactHeight) return std::nullopt;
    const double evidence = std::log(static_cast<double>(f.patch->cells.size()) / 60.0);
    const double fromAbove = std::max(0.0, -g.approach.dot(up));
    const double clearance = std::min(1.0, lowest / options.clearHeight);
    return evidence + 1.5 * fromAbove + 1.5 * (clearance - 1.0);
  }
};

// The score of an encompassing grasp (two or three fingers) `width` wide: false when the width
// is out of range or a contact too low; else the shared terms plus the closeness to the
// preferred width.
bool scoreEncompassing(const PatchFrame& f, const Ranker& rank, const GraspOptions& o, double width,
                       CandidateGrasp& g) {
  if (width < o.minWidth || width > o.maxWidth) return false;
  const auto b = rank.base(f, g);
  if (!b) return false;
  g.score = *b + 1.0 - std::abs(width - o.preferredWidth) / (o.maxWidth - o.minWidth);
  return true;
}

void twoFingerEncompassing(const PatchFrame& f, const Ranker& rank, int patchIndex,
                           std::vector<CandidateGrasp>& out) {
  const auto& o = rank.options;
  for (int k = 0; k < o.axes; ++k) {
    const double a = M_PI * k / o.axes;
    const Eigen::Vector3d u = inPlane(f, a), v = f.n.cross(u);
    const auto* plus = outermostOnLine(f, u, v, 0.0, o.lateralTolerance);
    const auto* minus = outermostOnLine(f, -u, v, 0.0, o.lateralTolerance);
    if (!plus || !minus) continue;
    CandidateGrasp g;
    g.type = GraspType::kS2Ega1;
    g.patch = patchIndex;
    g.approach = -f.n;
    g.contacts = {wrapContact(f, plus->point, u, o), wrapContact(f, minus->point, -u, o)};
    const double width = (g.contacts[0].position - g.contacts[1].position).norm();
    if (scoreEncompassing(f, rank, o, width, g)) out.push_back(std::move(g));
  }
}

void twoFingerPinch(const PatchFrame& f, const Ranker& rank, int patchIndex,
                    std::vector<CandidateGrasp>& out) {
  const auto& o = rank.options;
  const double window = M_PI / o.directions;
  for (int k = 0; k < o.directions; ++k) {
    const double a = -M_PI + 2.0 * M_PI * k / o.directions;
    const auto* r = outermostNear(f, a, window, /*edgesOnly=*/true);
    if (!r || r->radius < o.pinchInset + 0.005) continue;
    const Eigen::Vector3d out3 = inPlane(f, r->angle);
    CandidateGrasp g;
    g.type = GraspType::kS2Ega3;
    g.patch = patchIndex;
    g.approach = -out3;
    grasp::DesiredContact front, back;
    front.position = r->point - o.pinchInset * out3;
    front.direction = -f.n;
    // The back is not seen; what is seen of the object behind the surface near the pinch (its
    // other faces) bounds it. At least pinchThickness, at most what the hand can span.
    const Eigen::Vector3d t = f.n.cross(out3);
    double depth = 0.0;
    for (const auto& x : f.clusterPoints) {
      const Eigen::Vector3d d = x - front.position;
      if (std::abs(d.dot(t)) > o.lateralTolerance) continue;
      const double along = d.dot(out3);
      if (along < -o.pinchInset || along > o.pinchInset) continue;
      depth = std::max(depth, -d.dot(f.n));
    }
    const double thickness = std::max(o.pinchThickness, depth + o.pinchMargin);
    if (thickness > o.maxWidth) continue;
    back.position = front.position - thickness * f.n;
    back.direction = f.n;
    g.contacts = {front, back};
    const auto b = rank.base(f, g);
    if (!b) continue;
    g.score = *b;
    out.push_back(std::move(g));
  }
}

void threeFingerEncompassing(const PatchFrame& f, const Ranker& rank, int patchIndex,
                             std::vector<CandidateGrasp>& out) {
  const auto& o = rank.options;
  const int starts = std::max(1, o.directions / 3);
  const double window = M_PI / o.directions * 1.5;
  for (int k = 0; k < starts; ++k) {
    const double a0 = 2.0 * M_PI / 3.0 * k / starts;
    CandidateGrasp g;
    g.type = GraspType::kS3Ega1;
    g.patch = patchIndex;
    g.approach = -f.n;
    std::vector<double> angles;
    for (int j = 0; j < 3; ++j) {
      const auto* r = outermostNear(f, a0 + 2.0 * M_PI / 3.0 * j, window, /*edgesOnly=*/false);
      if (!r || r->radius < 0.005) break;
      g.contacts.push_back(wrapContact(f, r->point, inPlane(f, r->angle), o));
      angles.push_back(r->angle);
    }
    if (g.contacts.size() != 3) continue;
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double d = (g.contacts[i].position - g.contacts[(i + 1) % 3].position).norm();
      shortest = std::min(shortest, d);
      longest = std::max(longest, d);
    }
    if (shortest < o.minSpan || longest > o.maxSpan) continue;
    const auto b = rank.base(f, g);
    if (!b) continue;
    // Regularity: 1 for contacts 120 deg apart, falling with the worst gap's deviation.
    double worst = 0.0;
    for (int i = 0; i < 3; ++i)
      worst = std::max(worst,
                       std::abs(angleBetween(angles[i], angles[(i + 1) % 3]) - 2.0 * M_PI / 3.0));
    g.score = *b + 1.0 - worst / (M_PI / 3.0) + (1.0 - longest / o.maxSpan);
    out.push_back(std::move(g));
  }
}

// Three fingers across a patch: the thumb at one end of an axis, the two fingers side by side
// at the other end, `fingerGap` apart (how the SDH holds a box across its narrow side; the
// 120-degree spread does not fit patches longer than the hand).
void threeFingerAcross(const PatchFrame& f, const Ranker& rank, int patchIndex,
                       std::vector<CandidateGrasp>& out) {
  const auto& o = rank.options;
  for (int k = 0; k < o.axes; ++k) {
    const double a = M_PI * k / o.axes;
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d u = sign * inPlane(f, a), v = f.n.cross(u);
      const auto* thumb = outermostOnLine(f, u, v, 0.0, o.lateralTolerance);
      const auto* left = outermostOnLine(f, -u, v, 0.5 * o.fingerGap, o.lateralTolerance);
      const auto* right = outermostOnLine(f, -u, v, -0.5 * o.fingerGap, o.lateralTolerance);
      if (!thumb || !left || !right) continue;
      CandidateGrasp g;
      g.type = GraspType::kS3Ega1;
      g.patch = patchIndex;
      g.approach = -f.n;
      g.contacts = {wrapContact(f, thumb->point, u, o), wrapContact(f, left->point, -u, o),
                    wrapContact(f, right->point, -u, o)};
      const double width =
          (g.contacts[0].position - 0.5 * (g.contacts[1].position + g.contacts[2].position)).dot(u);
      if (scoreEncompassing(f, rank, o, width, g)) out.push_back(std::move(g));
    }
  }
}

bool sameGrasp(const CandidateGrasp& a, const CandidateGrasp& b, double distance) {
  if (a.contacts.size() != b.contacts.size()) return false;
  if (a.approach.dot(b.approach) < std::cos(15.0 * kRadPerDeg)) return false;
  for (const auto& ca : a.contacts) {
    bool near = false;
    for (const auto& cb : b.contacts) near = near || (ca.position - cb.position).norm() < distance;
    if (!near) return false;
  }
  return true;
}

}  // namespace

const char* graspTypeName(GraspType type) {
  switch (type) {
    case GraspType::kS2Ega1:
      return "s2EGA1";
    case GraspType::kS2Ega3:
      return "s2EGA3";
    case GraspType::kS3Ega1:
      return "s3EGA1";
  }
  return "?";
}

std::optional<GraspType> graspTypeFromName(std::string_view name) {
  for (GraspType t : kGraspTypes) {
    if (name == graspTypeName(t)) return t;
  }
  return std::nullopt;
}

std::vector<CandidateGrasp> generateGrasps(const SceneSegmentation& scene,
                                           const GraspOptions& options) {
  const Ranker rank{scene.table, options, scene.table.normal};
  std::vector<CandidateGrasp> candidates;
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const PatchFrame f = frameOf(scene, scene.patches[p]);
    if (f.rim.empty()) continue;
    twoFingerEncompassing(f, rank, static_cast<int>(p), candidates);
    twoFingerPinch(f, rank, static_cast<int>(p), candidates);
    threeFingerEncompassing(f, rank, static_cast<int>(p), candidates);
    threeFingerAcross(f, rank, static_cast<int>(p), candidates);
  }
  std::vector<CandidateGrasp> result;
  for (GraspType type : kGraspTypes) {
    std::vector<const CandidateGrasp*> ofType;
    for (const auto& c : candidates) {
      if (c.type == type) ofType.push_back(&c);
    }
    std::stable_sort(ofType.begin(), ofType.end(),
                     [](const auto* a, const auto* b) { return a->score > b->score; });
    std::vector<const CandidateGrasp*> chosen;
    for (const auto* c : ofType) {
      if (static_cast<int>(chosen.size()) >= options.perType) break;
      const bool duplicate = std::any_of(chosen.begin(), chosen.end(), [&](const auto* k) {
        return sameGrasp(*c, *k, options.distinct);
      });
      if (!duplicate) chosen.push_back(c);
    }
    for (const auto* c : chosen) result.push_back(*c);
  }
  return result;
}

}  // namespace visgrab::vision
