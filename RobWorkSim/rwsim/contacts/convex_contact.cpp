#include "rwsim/contacts/convex_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "rw/proximity/convex_shape.hpp"
#include "rw/proximity/gjk.hpp"
#include "rw/proximity/triangle_queries.hpp"

namespace rwsim::contacts::detail {
namespace {

using rw::geometry::Aabb;
using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;
using Index = std::int32_t;

/// Edge pairs whose squared sine of angle is below this are parallel (face axes cover them).
constexpr double kParallelSine2 = 1e-12;
/// Below this many faces a shape's own face axes bound the overlap; above, for both shapes,
/// the axis between their centres is tried first.
constexpr std::size_t kFewFaces = 8;
/// A sphere centre closer than this (m) to a polytope counts as inside it.
constexpr double kInsideDistance = 1e-12;

/// B's faces replace A's only when they separate by this much more (m): keeps the reference
/// face from flipping between two parallel faces.
double faceTolerance(double margin) { return 1e-7 + 0.02 * margin; }
/// An edge pair replaces the best face only when it separates by this much more (m): resting
/// contacts keep their face manifold.
double edgeTolerance(double margin) { return 1e-7 + 0.05 * margin; }
/// Overlaps deeper than this (m) skip the edge-edge axes if there may be more than
/// kDeepEdgePairs pairs to try.
double deepOverlap(double margin) { return std::max(0.005, 10.0 * margin); }
constexpr std::size_t kDeepEdgePairs = 4096;

Obb boundsInFrame(const Aabb& box, const Transform3D& X) {
  Obb o;
  o.center = transformPoint(X, 0.5 * (box.min + box.max));
  o.axes = X.linear();
  o.halfExtents = 0.5 * (box.max - box.min);
  return o;
}

/// All indices of `features`, or those in tree leaves overlapping `query`.
template <class Feature>
void candidates(std::span<const Feature> features, const FeatureTree* tree, const QueryBox& query,
                std::vector<Index>& out) {
  out.clear();
  if (tree != nullptr) {
    tree->query(query, out);
    return;
  }
  for (std::size_t i = 0; i < features.size(); ++i) out.push_back(static_cast<Index>(i));
}

/// Indices of the faces of P whose box and plane come within `grow` of the other shape's box
/// `otherBounds` (X_po places the other shape in P's frame).
void nearFaces(const PolytopeView& p, const Aabb& otherBounds, const Transform3D& X_po, double grow,
               std::vector<Index>& out) {
  const QueryBox query(boundsInFrame(otherBounds, X_po), grow);
  candidates(p.faces, p.faceTree, query, out);
  std::erase_if(out, [&](Index i) {
    const Face& f = p.faces[static_cast<std::size_t>(i)];
    return !query.overlaps(f.box.min, f.box.max) || !query.nearPlane(f.normal, f.offset);
  });
}

/// True when segment [p0, p1] comes within `grow` (per axis) of `box`: slab test against the
/// box grown by `grow`.
bool segmentNearBox(const Vector3D& p0, const Vector3D& p1, const Aabb& box, double grow) {
  const Vector3D lo = box.min - Vector3D::Constant(grow);
  const Vector3D hi = box.max + Vector3D::Constant(grow);
  const Vector3D d = p1 - p0;
  double t0 = 0.0;
  double t1 = 1.0;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-300) {
      if (p0[i] < lo[i] || p0[i] > hi[i]) return false;
      continue;
    }
    double ta = (lo[i] - p0[i]) / d[i];
    double tb = (hi[i] - p0[i]) / d[i];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

/// Indices of the edges of P that come within `grow` of the other shape's box (X_po places the
/// other shape in P's frame, X_op the reverse).
void nearEdges(const PolytopeView& p, const Aabb& otherBounds, const Transform3D& X_po,
               const Transform3D& X_op, double grow, std::vector<Index>& out) {
  const QueryBox query(boundsInFrame(otherBounds, X_po), grow);
  candidates(p.edges, p.edgeTree, query, out);
  std::erase_if(out, [&](Index i) {
    const Edge& e = p.edges[static_cast<std::size_t>(i)];
    return !query.overlaps(e.box.min, e.box.max) ||
           !segmentNearBox(transformPoint(X_op, p.vertices[static_cast<std::size_t>(e.v0)]),
                           transformPoint(X_op, p.vertices[static_cast<std::size_t>(e.v1)]),
                           otherBounds, grow);
  });
}

/// Best face axis of P against Q (Q placed in P's frame by X_pq); updates the overlap bound.
/// Faces that cannot separate more than `floor` are skipped without a support query: any
/// vertex of Q (the last support found, Q's extreme vertices along the axes) bounds the
/// separation from above.
SatResult bestFaceAxis(const PolytopeView& p, const PolytopeView& q, const Transform3D& X_pq,
                       const Transform3D& X_qp, double margin, double floor, double& grow,
                       std::vector<Index>& near, Index& hint, bool& separated) {
  SatResult best;
  nearFaces(p, q.bounds, X_pq, grow, near);
  const Rotation3D R_qp = X_qp.linear();
  for (const Index f : near) {
    const Face& face = p.faces[static_cast<std::size_t>(f)];
    const Vector3D nq = R_qp * face.normal;
    const double offset = face.offset - face.normal.dot(X_pq.translation());
    double bound = nq.dot(q.vertices[static_cast<std::size_t>(std::max(hint, Index{0}))]);
    for (const Index k : q.anchors) {
      bound = std::min(bound, nq.dot(q.vertices[static_cast<std::size_t>(k)]));
    }
    if (bound - offset <= std::max(floor, best.separation)) continue;
    const Index v = supportVertex(q, R_qp * (-face.normal), hint);
    const double s =
        face.normal.dot(transformPoint(X_pq, q.vertices[static_cast<std::size_t>(v)])) -
        face.offset;
    if (s > margin) {
      separated = true;
      return best;
    }
    if (s > best.separation) {
      best.kind = SatResult::Kind::kFaceA;
      best.featureA = f;
      best.separation = s;
      best.axis = face.normal;
    }
    grow = std::max(margin, std::min(grow, -s));
  }
  return best;
}

/// Best edge-edge axis (A's frame); only pairs whose Gauss arcs cross are tried.
SatResult bestEdgeAxis(const PolytopeView& a, const PolytopeView& b, const Transform3D& X_ab,
                       const Transform3D& X_ba, double margin, double grow, bool deep,
                       Workspace& ws, bool& separated) {
  SatResult best;
  // The shape with fewer edges first: often none of them is near, and the other is skipped.
  // Deep overlaps with too many edge pairs to try are left to the faces.
  const auto tooMany = [&](std::size_t nearCount, std::size_t otherEdges) {
    return deep && nearCount * otherEdges > kDeepEdgePairs;
  };
  if (b.edges.size() < a.edges.size()) {
    nearEdges(b, a.bounds, X_ba, X_ab, grow, ws.nearB);
    if (ws.nearB.empty() || tooMany(ws.nearB.size(), a.edges.size())) return best;
    nearEdges(a, b.bounds, X_ab, X_ba, grow, ws.nearA);
  } else {
    nearEdges(a, b.bounds, X_ab, X_ba, grow, ws.nearA);
    if (ws.nearA.empty() || tooMany(ws.nearA.size(), b.edges.size())) return best;
    nearEdges(b, a.bounds, X_ba, X_ab, grow, ws.nearB);
  }
  const Rotation3D& R = X_ab.linear();
  ws.movedEdges.clear();
  for (const Index j : ws.nearB) {
    const Edge& e = b.edges[static_cast<std::size_t>(j)];
    MovedEdge m;
    m.p0 = transformPoint(X_ab, b.vertices[static_cast<std::size_t>(e.v0)]);
    m.p1 = transformPoint(X_ab, b.vertices[static_cast<std::size_t>(e.v1)]);
    m.c = -(R * e.na);
    m.d = -(R * e.nb);
    m.dc = m.d.cross(m.c);
    m.index = j;
    ws.movedEdges.push_back(m);
  }
  for (const Index i : ws.nearA) {
    const Edge& e = a.edges[static_cast<std::size_t>(i)];
    const Vector3D ba = e.nb.cross(e.na);
    const Vector3D& pa = a.vertices[static_cast<std::size_t>(e.v0)];
    const Vector3D dirA = a.vertices[static_cast<std::size_t>(e.v1)] - pa;
    const Vector3D outward = e.na + e.nb;
    for (const MovedEdge& m : ws.movedEdges) {
      const double cba = m.c.dot(ba);
      const double dba = m.d.dot(ba);
      const double adc = e.na.dot(m.dc);
      const double bdc = e.nb.dot(m.dc);
      if (!(cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0)) continue;
      const Vector3D dirB = m.p1 - m.p0;
      Vector3D axis = dirA.cross(dirB);
      const double length2 = axis.squaredNorm();
      if (length2 <= kParallelSine2 * dirA.squaredNorm() * dirB.squaredNorm()) continue;
      if (axis.dot(outward) < 0.0) axis = -axis;
      axis /= std::sqrt(length2);
      const double s = axis.dot(m.p0 - pa);
      if (s > margin) {
        separated = true;
        return best;
      }
      if (s > best.separation) {
        best.kind = SatResult::Kind::kEdges;
        best.featureA = i;
        best.featureB = m.index;
        best.separation = s;
        best.axis = axis;
      }
    }
  }
  return best;
}

/// The part of the incident polygon (ws.clipIn, reference frame) on the reference face's side:
/// Sutherland-Hodgman against the side planes of the face loop. Result in ws.clipIn.
void clipPolygon(const PolytopeView& ref, const Face& rf, Workspace& ws) {
  for (Index k = 0; k < rf.count && !ws.clipIn.empty(); ++k) {
    const Vector3D& p0 = ref.vertices[static_cast<std::size_t>(ref.faceVertices[rf.first + k])];
    const Vector3D& p1 =
        ref.vertices[static_cast<std::size_t>(ref.faceVertices[rf.first + (k + 1) % rf.count])];
    const Vector3D side = (p1 - p0).cross(rf.normal);
    const double offset = side.dot(p0);
    ws.clipOut.clear();
    for (std::size_t i = 0; i < ws.clipIn.size(); ++i) {
      const Vector3D& from = ws.clipIn[i];
      const Vector3D& to = ws.clipIn[(i + 1) % ws.clipIn.size()];
      const double dFrom = side.dot(from) - offset;
      const double dTo = side.dot(to) - offset;
      if (dFrom <= 0.0) ws.clipOut.push_back(from);
      if ((dFrom < 0.0 && dTo > 0.0) || (dFrom > 0.0 && dTo < 0.0)) {
        ws.clipOut.emplace_back(from + (to - from) * (dFrom / (dFrom - dTo)));
      }
    }
    std::swap(ws.clipIn, ws.clipOut);
  }
}

/// For a two-vertex reference face (the edge of a thin piece): where the incident polygon
/// (ws.clipIn) crosses the piece's plane, cut to the edge's extent. Result in ws.clipIn.
void clipToEdge(const PolytopeView& ref, const Face& rf, Workspace& ws) {
  const Vector3D& v0 = ref.vertices[static_cast<std::size_t>(ref.faceVertices[rf.first])];
  const Vector3D& v1 = ref.vertices[static_cast<std::size_t>(ref.faceVertices[rf.first + 1])];
  const Vector3D e = v1 - v0;
  const Vector3D plane = e.cross(rf.normal);
  const double c = plane.dot(v0);
  double tMin = std::numeric_limits<double>::infinity();
  double tMax = -tMin;
  Vector3D pMin = v0;
  Vector3D pMax = v0;
  const auto consider = [&](const Vector3D& q) {
    const double t = e.dot(q - v0);
    if (t < tMin) std::tie(tMin, pMin) = std::pair(t, q);
    if (t > tMax) std::tie(tMax, pMax) = std::pair(t, q);
  };
  const double onPlane = 1e-12 * plane.norm() * (1.0 + std::abs(c));
  for (std::size_t i = 0; i < ws.clipIn.size(); ++i) {
    const Vector3D& from = ws.clipIn[i];
    const Vector3D& to = ws.clipIn[(i + 1) % ws.clipIn.size()];
    const double dFrom = plane.dot(from) - c;
    const double dTo = plane.dot(to) - c;
    if (std::abs(dFrom) <= onPlane) consider(from);
    if ((dFrom < -onPlane && dTo > onPlane) || (dFrom > onPlane && dTo < -onPlane)) {
      consider(from + (to - from) * (dFrom / (dFrom - dTo)));
    }
  }
  ws.clipIn.clear();
  const double length2 = e.squaredNorm();
  if (tMax < 0.0 || tMin > length2) return;
  const auto at = [&](double t) {
    return tMax > tMin ? Vector3D(pMin + (pMax - pMin) * ((t - tMin) / (tMax - tMin))) : pMin;
  };
  ws.clipIn.push_back(at(std::max(tMin, 0.0)));
  if (tMax > tMin) ws.clipIn.push_back(at(std::min(tMax, length2)));
}

/// Clips the face of `inc` most opposed to reference face `refFace` of `ref` against that
/// face; appends points within the margin, mapped by X_out, normals times sign.
void clipAgainstFace(const PolytopeView& ref, Index refFace, const PolytopeView& inc,
                     const Transform3D& X_ri, double margin, const Transform3D& X_out,
                     double normalSign, Workspace& ws, std::vector<ContactPoint>& out) {
  const Face& rf = ref.faces[static_cast<std::size_t>(refFace)];
  const Vector3D towardRef = X_ri.linear().transpose() * (-rf.normal);
  Index hint = -1;
  const Index deepest = supportVertex(inc, towardRef, hint);
  const Face& incFace =
      inc.faces[static_cast<std::size_t>(mostAlignedFace(inc, towardRef, deepest))];
  ws.clipIn.clear();
  for (Index k = 0; k < incFace.count; ++k) {
    const auto v = static_cast<std::size_t>(inc.faceVertices[incFace.first + k]);
    ws.clipIn.push_back(transformPoint(X_ri, inc.vertices[v]));
  }
  if (rf.count == 2) {
    clipToEdge(ref, rf, ws);
  } else {
    clipPolygon(ref, rf, ws);
  }
  const Vector3D normalOut = normalSign * (X_out.linear() * rf.normal);
  const std::size_t before = out.size();
  const auto emit = [&](const Vector3D& p) {
    const double h = rf.normal.dot(p) - rf.offset;
    if (h <= margin) out.push_back({transformPoint(X_out, p - 0.5 * h * rf.normal), normalOut, -h});
  };
  for (const Vector3D& p : ws.clipIn) emit(p);
  if (out.size() > before) return;
  // Nothing clipped within the margin: the deepest vertex, if it lies over the face.
  ws.clipIn.assign(1, transformPoint(X_ri, inc.vertices[static_cast<std::size_t>(deepest)]));
  if (rf.count == 2) return;
  clipPolygon(ref, rf, ws);
  for (const Vector3D& p : ws.clipIn) emit(p);
}

}  // namespace

Workspace& threadWorkspace() {
  thread_local Workspace workspace;
  return workspace;
}

double separationAlong(const PolytopeView& a, const PolytopeView& b, const Transform3D& X_ab,
                       const Vector3D& u) {
  Index hintA = -1;
  Index hintB = -1;
  const Index va = supportVertex(a, u, hintA);
  const Index vb = supportVertex(b, X_ab.linear().transpose() * (-u), hintB);
  return u.dot(transformPoint(X_ab, b.vertices[static_cast<std::size_t>(vb)])) -
         u.dot(a.vertices[static_cast<std::size_t>(va)]);
}

SatResult separatingAxis(const PolytopeView& a, const PolytopeView& b, const Transform3D& X_ab,
                         double margin, Workspace& ws, SupportHints& hints, double overlapBound) {
  const Transform3D X_ba = X_ab.inverse(Eigen::Isometry);
  double grow = std::max(margin, overlapBound);
  if (std::isinf(grow) && a.faces.size() > kFewFaces && b.faces.size() > kFewFaces) {
    const Vector3D between = transformPoint(X_ab, 0.5 * (b.bounds.min + b.bounds.max)) -
                             0.5 * (a.bounds.min + a.bounds.max);
    if (between.squaredNorm() > 1e-30) {
      const double s = separationAlong(a, b, X_ab, between.normalized());
      if (s > margin) return {};
      grow = std::max(margin, -s);
    }
  }
  // The shape with fewer faces goes first: its axes bound the overlap, so fewer features of
  // the other one survive the culling, and their support queries can be skipped.
  const double tolerance = faceTolerance(margin);
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  bool separated = false;
  SatResult best;
  SatResult faceB;
  if (b.faces.size() < a.faces.size()) {
    faceB = bestFaceAxis(b, a, X_ba, X_ab, margin, kNone, grow, ws.nearB, hints.a, separated);
    if (!separated) {
      best = bestFaceAxis(a, b, X_ab, X_ba, margin, faceB.separation - tolerance, grow, ws.nearA,
                          hints.b, separated);
    }
  } else {
    best = bestFaceAxis(a, b, X_ab, X_ba, margin, kNone, grow, ws.nearA, hints.b, separated);
    if (!separated) {
      faceB = bestFaceAxis(b, a, X_ba, X_ab, margin, best.separation - tolerance, grow, ws.nearB,
                           hints.a, separated);
    }
  }
  if (separated) return {};
  // On a tie the face with fewer vertices is the reference: fewer planes to clip against.
  const auto vertexCount = [](const PolytopeView& p, Index f) {
    return p.faces[static_cast<std::size_t>(f)].count;
  };
  if (faceB.kind != SatResult::Kind::kNone &&
      (best.kind == SatResult::Kind::kNone || faceB.separation > best.separation + tolerance ||
       (faceB.separation >= best.separation - tolerance &&
        vertexCount(b, faceB.featureA) < vertexCount(a, best.featureA)))) {
    best.kind = SatResult::Kind::kFaceB;
    best.featureA = -1;
    best.featureB = faceB.featureA;
    best.separation = faceB.separation;
    best.axis = -(X_ab.linear() * faceB.axis);
  }
  // Deep overlaps of large polytopes (model geometry overlapping by design, e.g. links at a
  // joint) keep the best face axis: the edge pairs within that depth are many, and such a
  // contact is no resting or grasp contact to be precise about.
  const bool deep = best.kind != SatResult::Kind::kNone && -best.separation > deepOverlap(margin);
  const SatResult edges = bestEdgeAxis(a, b, X_ab, X_ba, margin, grow, deep, ws, separated);
  if (separated) return {};
  if (edges.kind != SatResult::Kind::kNone &&
      (best.kind == SatResult::Kind::kNone ||
       edges.separation > best.separation + edgeTolerance(margin))) {
    best = edges;
  }
  return best;
}

void manifoldFromAxis(const PolytopeView& a, const PolytopeView& b, const Transform3D& X_ab,
                      const SatResult& sat, double margin, Workspace& ws,
                      std::vector<ContactPoint>& out) {
  switch (sat.kind) {
    case SatResult::Kind::kNone:
      return;
    case SatResult::Kind::kFaceA:
      clipAgainstFace(a, sat.featureA, b, X_ab, margin, Transform3D::Identity(), 1.0, ws, out);
      return;
    case SatResult::Kind::kFaceB:
      clipAgainstFace(b, sat.featureB, a, X_ab.inverse(Eigen::Isometry), margin, X_ab, -1.0, ws,
                      out);
      return;
    case SatResult::Kind::kEdges: {
      const Edge& ea = a.edges[static_cast<std::size_t>(sat.featureA)];
      const Edge& eb = b.edges[static_cast<std::size_t>(sat.featureB)];
      Vector3D ca;
      Vector3D cb;
      rw::proximity::closestPointsOnSegments(
          a.vertices[static_cast<std::size_t>(ea.v0)], a.vertices[static_cast<std::size_t>(ea.v1)],
          transformPoint(X_ab, b.vertices[static_cast<std::size_t>(eb.v0)]),
          transformPoint(X_ab, b.vertices[static_cast<std::size_t>(eb.v1)]), ca, cb);
      // The closest points of the edges must be as close as the axis says; they are not when
      // a separating feature was culled (then there is no contact).
      const double gap = (cb - ca).norm();
      if (sat.separation <= margin && gap <= std::max(margin, -sat.separation) * (1 + 1e-9)) {
        out.push_back({0.5 * (ca + cb), sat.axis, -sat.separation});
      }
      return;
    }
  }
}

std::optional<ContactPoint> sphereOnPolytope(const PolytopeView& p, const Vector3D& center,
                                             double radius, double margin) {
  using rw::proximity::ConvexShape;
  const ConvexShape hull =
      p.adjacencyOffsets.empty()
          ? ConvexShape::hull(p.vertices)
          : ConvexShape::hull(p.vertices, {p.adjacencyOffsets, p.adjacency, p.anchors});
  const rw::proximity::GjkResult g = rw::proximity::gjkDistance(
      hull, ConvexShape::sphere(0.0), rw::math::makeTranslation(center), 0.0, radius + margin);
  if (g.exceeded || g.distance > radius + margin) return std::nullopt;
  Vector3D normal = Vector3D::UnitZ();
  double separation = 0.0;
  if (g.distance > kInsideDistance) {
    normal = (center - g.pointA) / g.distance;
    separation = g.distance;
  } else {
    separation = -std::numeric_limits<double>::infinity();
    for (const Face& f : p.faces) {
      const double s = f.normal.dot(center) - f.offset;
      if (s > separation) {
        separation = s;
        normal = f.normal;
      }
    }
  }
  const Vector3D onPolytope = center - separation * normal;
  const Vector3D onSphere = center - radius * normal;
  return ContactPoint{0.5 * (onPolytope + onSphere), normal, radius - separation};
}

}  // namespace rwsim::contacts::detail
