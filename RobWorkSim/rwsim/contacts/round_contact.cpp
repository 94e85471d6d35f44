#include "rwsim/contacts/round_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "rw/proximity/gjk.hpp"

namespace rwsim::contacts::detail {
namespace {

using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rw::proximity::ConvexShape;

/// cos and sin of kFeatureAngle (3 degrees).
constexpr double kCosFeature = 0.99862953475457387;
constexpr double kSinFeature = 0.05233595624294383;
/// Cores closer than this (m) touch: the shapes overlap by about their roundings or more.
constexpr double kCoreTouch = 1e-9;
/// Clipped segments shorter than this (m) give one point.
constexpr double kShortSegment = 1e-9;

/// A support feature: the points of a piece farthest along a direction.
struct Feature {
  /// 0 a point, 1 a segment, 2 a flat convex polygon (points in loop order).
  int dim = 0;
  /// For dim 2: outward normal of its plane.
  Vector3D normal = Vector3D::UnitZ();
  /// For dim 2: a polytope's face (an exact plane), preferred as the reference.
  bool face = false;
};

const std::array<Eigen::Vector2d, kRimPoints>& rimDirections() {
  static const std::array<Eigen::Vector2d, kRimPoints> directions = [] {
    std::array<Eigen::Vector2d, kRimPoints> d{};
    for (int k = 0; k < kRimPoints; ++k) {
      const double angle = 2.0 * std::numbers::pi * k / kRimPoints;
      d[static_cast<std::size_t>(k)] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    }
    return d;
  }();
  return directions;
}

/// The feature of round shape `r` along unit `d` (r's frame): a cap as rim points, a side line
/// or the farthest point.
Feature roundFeature(const RoundShape& r, const Vector3D& d, std::vector<Vector3D>& points) {
  points.clear();
  Feature f;
  const double h = r.halfHeight();
  for (const double side : {1.0, -1.0}) {
    const double radius = side > 0.0 ? r.topRadius() : r.bottomRadius();
    if (radius > 0.0 && side * d.z() >= kCosFeature) {
      for (const Eigen::Vector2d& u : rimDirections()) {
        points.emplace_back(radius * u.x(), radius * u.y(), side * h);
      }
      f.dim = 2;
      f.normal = Vector3D(0.0, 0.0, side);
      return f;
    }
  }
  const double planar = std::hypot(d.x(), d.y());
  if (planar > 0.0) {
    const double flare = r.bottomRadius() - r.topRadius();
    const double cosSide = (planar * 2.0 * h + d.z() * flare) / std::hypot(2.0 * h, flare);
    if (cosSide >= kCosFeature) {
      const Vector3D radial(d.x() / planar, d.y() / planar, 0.0);
      points.push_back(r.bottomRadius() * radial - h * Vector3D::UnitZ());
      points.push_back(r.topRadius() * radial + h * Vector3D::UnitZ());
      f.dim = 1;
      return f;
    }
  }
  points.push_back(r.support(d));
  return f;
}

/// The feature of polytope `p` along unit `d`: a face, an edge or a vertex.
Feature polytopeFeature(const PolytopeView& p, const Vector3D& d, std::vector<Vector3D>& points) {
  points.clear();
  Feature f;
  std::int32_t hint = -1;
  const std::int32_t v = supportVertex(p, d, hint);
  const Face& face = p.faces[static_cast<std::size_t>(mostAlignedFace(p, d, v))];
  if (face.normal.dot(d) >= kCosFeature && face.count >= 2) {
    for (std::int32_t k = 0; k < face.count; ++k) {
      points.push_back(p.vertices[static_cast<std::size_t>(
          p.faceVertices[static_cast<std::size_t>(face.first + k)])]);
    }
    f.dim = face.count >= 3 ? 2 : 1;
    f.normal = face.normal;
    f.face = true;
    return f;
  }
  const Vector3D& pv = p.vertices[static_cast<std::size_t>(v)];
  double best = kSinFeature;
  std::int32_t bestOther = -1;
  for (const Edge& e : p.edges) {
    if (e.v0 != v && e.v1 != v) continue;
    const std::int32_t other = e.v0 == v ? e.v1 : e.v0;
    const Vector3D along = p.vertices[static_cast<std::size_t>(other)] - pv;
    const double length = along.norm();
    if (length <= 0.0) continue;
    const double s = std::abs(along.dot(d)) / length;
    if (s <= best) {
      best = s;
      bestOther = other;
    }
  }
  points.push_back(pv);
  if (bestOther >= 0) {
    points.push_back(p.vertices[static_cast<std::size_t>(bestOther)]);
    f.dim = 1;
  }
  return f;
}

Feature featureOf(const ConvexPiece& piece, const Vector3D& d, std::vector<Vector3D>& points) {
  if (piece.round != nullptr) return roundFeature(*piece.round, d, points);
  if (piece.polytope != nullptr) return polytopeFeature(piece.polytope->view(), d, points);
  points.assign(1, piece.sphereRadius * d);
  return {};
}

/// Clips `in` (a point, a segment or a convex polygon) to the prism over convex polygon `ref`
/// along its normal `n`; the result is left in `in` (`out` is scratch).
void clipToPrism(std::span<const Vector3D> ref, const Vector3D& n, std::vector<Vector3D>& in,
                 std::vector<Vector3D>& out) {
  Vector3D centre = Vector3D::Zero();
  for (const Vector3D& p : ref) centre += p;
  centre /= static_cast<double>(ref.size());
  for (std::size_t i = 0; i < ref.size() && !in.empty(); ++i) {
    const Vector3D& a = ref[i];
    Vector3D side = (ref[(i + 1) % ref.size()] - a).cross(n);
    if (side.squaredNorm() == 0.0) continue;
    if (side.dot(centre - a) > 0.0) side = -side;
    out.clear();
    const std::size_t m = in.size();
    const std::size_t edges = m == 1 ? 0 : (m == 2 ? 1 : m);
    if (m == 1 && side.dot(in[0] - a) <= 0.0) out.push_back(in[0]);
    for (std::size_t k = 0; k < edges; ++k) {
      const Vector3D& p = in[k];
      const Vector3D& q = in[(k + 1) % m];
      const double dp = side.dot(p - a);
      const double dq = side.dot(q - a);
      if (dp <= 0.0) out.push_back(p);
      if ((dp <= 0.0) != (dq <= 0.0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
      if (m == 2 && dq <= 0.0) out.push_back(q);
    }
    std::swap(in, out);
  }
}

/// Contacts from the features of A and B (both in A's frame, B's feature along -n); false when
/// they give none (then the caller takes the single deepest point).
bool featureContacts(const Feature& fa, const std::vector<Vector3D>& pa, const Feature& fb,
                     const std::vector<Vector3D>& pb, const Vector3D& n, double margin,
                     Workspace& ws, std::vector<ContactPoint>& out) {
  bool added = false;
  if (fa.dim == 2 || fb.dim == 2) {
    bool refIsA = fa.dim == 2;
    if (fa.dim == fb.dim) {
      refIsA = fa.face != fb.face ? fa.face : fa.normal.dot(n) >= -fb.normal.dot(n);
    }
    const Feature& ref = refIsA ? fa : fb;
    const std::vector<Vector3D>& refPoints = refIsA ? pa : pb;
    const std::vector<Vector3D>& incident = refIsA ? pb : pa;
    ws.clipIn.assign(incident.begin(), incident.end());
    clipToPrism(refPoints, ref.normal, ws.clipIn, ws.clipOut);
    const double offset = ref.normal.dot(refPoints[0]);
    const Vector3D normal = refIsA ? ref.normal : Vector3D(-ref.normal);
    for (const Vector3D& q : ws.clipIn) {
      const double depth = offset - ref.normal.dot(q);
      if (depth < -margin) continue;
      out.push_back({q + 0.5 * depth * ref.normal, normal, depth});
      added = true;
    }
    return added;
  }
  if (fa.dim != 1 || fb.dim != 1) return false;
  const double lengthA = (pa[1] - pa[0]).norm();
  const Vector3D da = (pa[1] - pa[0]) / lengthA;
  const Vector3D db = (pb[1] - pb[0]).normalized();
  if (std::abs(da.dot(db)) < kCosFeature) return false;
  const double tb0 = da.dot(pb[0] - pa[0]);
  const double tb1 = da.dot(pb[1] - pa[0]);
  const double lo = std::max(0.0, std::min(tb0, tb1));
  const double hi = std::min(lengthA, std::max(tb0, tb1));
  if (hi < lo) return false;
  for (const double t : {lo, hi}) {
    const Vector3D onA = pa[0] + t * da;
    const Vector3D onB = pb[0] + (pb[1] - pb[0]) * ((t - tb0) / (tb1 - tb0));
    const double depth = n.dot(onA - onB);
    if (depth >= -margin) {
      out.push_back({0.5 * (onA + onB), n, depth});
      added = true;
    }
    if (hi - lo < kShortSegment) break;
  }
  return added;
}

/// A piece's GJK core: the shape, where its centre is in the piece's frame, how far it is
/// grown to give the (rounded) piece, and how far the piece reaches beyond it at most.
struct Core {
  ConvexShape shape;
  Vector3D offset;
  double rounding;
  double reach;
};

Core coreOf(const ConvexPiece& piece) {
  if (piece.round != nullptr) {
    return {piece.round->core(), Vector3D(0.0, 0.0, piece.round->coreOffset()),
            piece.round->rounding(), piece.round->reach()};
  }
  if (piece.polytope != nullptr) {
    const PolytopeView v = piece.polytope->view();
    return {v.adjacencyOffsets.empty()
                ? ConvexShape::hull(v.vertices)
                : ConvexShape::hull(v.vertices, {v.adjacencyOffsets, v.adjacency, v.anchors}),
            Vector3D::Zero(), 0.0, 0.0};
  }
  return {ConvexShape::sphere(0.0), Vector3D::Zero(), piece.sphereRadius, piece.sphereRadius};
}

const Polytope* polytopeOf(const ConvexPiece& piece) {
  if (piece.round != nullptr) return &piece.round->polytope();
  return piece.polytope;
}

/// Contacts of overlaps deeper than the roundings: the tessellations' polytope contacts.
void deepContacts(const ConvexPiece& a, const ConvexPiece& b, const Transform3D& X_ab,
                  double margin, Workspace& ws, std::vector<ContactPoint>& out) {
  const Polytope* pa = polytopeOf(a);
  const Polytope* pb = polytopeOf(b);
  if (pa == nullptr) {
    const Transform3D X_ba = X_ab.inverse(Eigen::Isometry);
    if (auto c = sphereOnPolytope(pb->view(), X_ba.translation(), a.sphereRadius, margin)) {
      out.push_back({transformPoint(X_ab, c->position), -(X_ab.linear() * c->normal), c->depth});
    }
    return;
  }
  if (pb == nullptr) {
    if (auto c = sphereOnPolytope(pa->view(), X_ab.translation(), b.sphereRadius, margin)) {
      out.push_back(*c);
    }
    return;
  }
  SupportHints hints;
  const SatResult sat = separatingAxis(pa->view(), pb->view(), X_ab, margin, ws, hints);
  if (sat.kind == SatResult::Kind::kNone) return;
  manifoldFromAxis(pa->view(), pb->view(), X_ab, sat, margin, ws, out);
}

}  // namespace

void roundOnHalfSpace(const RoundShape& r, const Transform3D& X_hr, double margin, Workspace& ws,
                      std::vector<ContactPoint>& out) {
  const Vector3D down = -X_hr.linear().row(2).transpose();
  roundFeature(r, down, ws.featureA);
  for (const Vector3D& p : ws.featureA) {
    const Vector3D w = transformPoint(X_hr, p);
    if (w.z() <= margin)
      out.push_back({Vector3D(w.x(), w.y(), 0.5 * w.z()), Vector3D::UnitZ(), -w.z()});
  }
}

void roundPairContacts(const ConvexPiece& a, const ConvexPiece& b, const Transform3D& X_ab,
                       double margin, Workspace& ws, std::vector<ContactPoint>& out) {
  const Core ca = coreOf(a);
  const Core cb = coreOf(b);
  const Rotation3D R = X_ab.linear();
  Transform3D X_core = X_ab;
  X_core.translation() = R * cb.offset + X_ab.translation() - ca.offset;
  // Cores farther apart than the margin plus both reaches leave the shapes apart.
  const rw::proximity::GjkResult g =
      rw::proximity::gjkDistance(ca.shape, cb.shape, X_core, 0.0, margin + ca.reach + cb.reach);
  if (g.exceeded) return;
  if (g.distance <= kCoreTouch) {
    deepContacts(a, b, X_ab, margin, ws, out);
    return;
  }
  const Vector3D n = (g.pointB - g.pointA) / g.distance;
  const Feature fa = featureOf(a, n, ws.featureA);
  Feature fb = featureOf(b, R.transpose() * -n, ws.featureB);
  for (Vector3D& p : ws.featureB) p = transformPoint(X_ab, p);
  fb.normal = R * fb.normal;
  if (featureContacts(fa, ws.featureA, fb, ws.featureB, n, margin, ws, out)) return;
  double topA = -std::numeric_limits<double>::infinity();
  for (const Vector3D& p : ws.featureA) topA = std::max(topA, n.dot(p));
  double bottomB = std::numeric_limits<double>::infinity();
  for (const Vector3D& p : ws.featureB) bottomB = std::min(bottomB, n.dot(p));
  const double depth = topA - bottomB;
  if (depth < -margin) return;
  const Vector3D onA = g.pointA + ca.offset + ca.rounding * n;
  const Vector3D onB = g.pointB + ca.offset - cb.rounding * n;
  out.push_back({0.5 * (onA + onB), n, depth});
}

}  // namespace rwsim::contacts::detail
