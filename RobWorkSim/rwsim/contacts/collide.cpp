// collide(): dispatch over shape kinds. Every pair is computed in a canonical order (kinds
// ascending, then by relative pose) in the first shape's frame, so that swapping the arguments
// only flips the normals and moving both shapes together only moves the points.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rw/proximity/convex_shape.hpp"
#include "rw/proximity/gjk.hpp"
#include "rw/proximity/triangle_queries.hpp"
#include "rwsim/contacts/convex_contact.hpp"
#include "rwsim/contacts/manifold.hpp"
#include "rwsim/contacts/round_contact.hpp"
#include "rwsim/contacts/shapes.hpp"

namespace rwsim::contacts {
namespace detail {
namespace {

using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;
using Kind = ContactShape::Kind;
using Index = std::int32_t;

/// Relative poses closer than this count as equal when choosing the canonical order.
constexpr double kOrderTolerance = 1e-9;
/// A direction within this of a triangle's normal (1 - cos) is its normal.
constexpr double kFrontDot = 1.0 - 1e-6;
/// A direction this close (sine) to the great circle of a convex edge's arc lies on it.
constexpr double kOnArc = 1e-3;
/// Normals pointing into a closed mesh by more than this (cosine) are dropped.
constexpr double kBackFacing = 1e-6;
/// Sphere centres closer than this (m) to a triangle take the triangle's normal.
constexpr double kTinyDistance = 1e-12;

/// Lexicographic "less" with a tolerance.
template <class V>
bool lexLess(const V& x, const V& y) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (x(i) < y(i) - kOrderTolerance) return true;
    if (x(i) > y(i) + kOrderTolerance) return false;
  }
  return false;
}

bool swapToCanonical(Kind ka, Kind kb, const Transform3D& X_ab) {
  if (ka != kb) return ka > kb;
  const Transform3D X_ba = X_ab.inverse(Eigen::Isometry);
  if (lexLess(X_ba.translation(), X_ab.translation())) return true;
  if (lexLess(X_ab.translation(), X_ba.translation())) return false;
  const Eigen::Matrix<double, 9, 1> ra =
      Eigen::Map<const Eigen::Matrix<double, 9, 1>>(Rotation3D(X_ab.linear()).data());
  const Eigen::Matrix<double, 9, 1> rb =
      Eigen::Map<const Eigen::Matrix<double, 9, 1>>(Rotation3D(X_ba.linear()).data());
  return lexLess(rb, ra);
}

/// True when unit direction `d` (triangle frame) is the triangle's normal or on the arc of one
/// of its convex edges.
bool inGaussImage(const TriangleInfo& t, const Vector3D& d) {
  if (d.dot(t.normal) >= kFrontDot) return true;
  for (const Vector3D& across : t.neighbour) {
    if (across.squaredNorm() == 0.0) continue;
    const Vector3D pole = t.normal.cross(across).normalized();
    if (std::abs(d.dot(pole)) > kOnArc) continue;
    if (t.normal.cross(d).dot(pole) >= 0.0 && d.cross(across).dot(pole) >= 0.0) return true;
  }
  return false;
}

/// Applies the one-sided rule of a closed mesh's triangle (A if `triangleIsA`, else B) to
/// `sat`: a normal in the triangle's Gauss image stays; otherwise the triangle's front face
/// takes over if it overlaps at most the margin more (a sliver across a flat or concave edge);
/// otherwise a back-facing normal is dropped (false) and any other (a vertex region) stays.
bool applyOneSided(SatResult& sat, const PolytopeView& a, const PolytopeView& b,
                   const Transform3D& X_ab, const TriangleInfo& info, bool triangleIsA,
                   double margin) {
  const Rotation3D& R = X_ab.linear();
  const Vector3D away = triangleIsA ? sat.axis : Vector3D(-(R.transpose() * sat.axis));
  if (inGaussImage(info, away)) return true;
  const Vector3D front = triangleIsA ? info.normal : Vector3D(-(R * info.normal));
  const double s = separationAlong(a, b, X_ab, front);
  if (s >= sat.separation - margin) {
    sat.kind = triangleIsA ? SatResult::Kind::kFaceA : SatResult::Kind::kFaceB;
    sat.featureA = 0;
    sat.featureB = 0;
    sat.separation = s;
    sat.axis = front;
    return s <= margin;
  }
  return away.dot(info.normal) >= -kBackFacing;
}

/// Contacts of two convex pieces in A's frame; a non-null info marks a triangle of a closed
/// mesh (see applyOneSided).
void pieceContacts(const PolytopeView& a, const TriangleInfo* infoA, const PolytopeView& b,
                   const TriangleInfo* infoB, const Transform3D& X_ab, double margin, Workspace& ws,
                   SupportHints& hints, std::vector<ContactPoint>& out,
                   double overlapBound = std::numeric_limits<double>::infinity()) {
  SatResult sat = separatingAxis(a, b, X_ab, margin, ws, hints, overlapBound);
  if (sat.kind == SatResult::Kind::kNone) return;
  if (infoA != nullptr && !applyOneSided(sat, a, b, X_ab, *infoA, true, margin)) return;
  if (infoB != nullptr && !applyOneSided(sat, a, b, X_ab, *infoB, false, margin)) return;
  manifoldFromAxis(a, b, X_ab, sat, margin, ws, out);
}

void reduceGathered(const ContactOptions& options, Workspace& ws, std::vector<ContactPoint>& out) {
  clusterAndReduce(ws.gathered, options.maxPointsPerManifold, out, ws.reduce);
}

// ---- half-space (A) against anything --------------------------------------------------------

void halfSpaceVertices(std::span<const Vector3D> vertices, const Transform3D& X_hp, double margin,
                       std::vector<ContactPoint>& out) {
  const Vector3D row = X_hp.linear().row(2).transpose();
  const double tz = X_hp.translation().z();
  for (const Vector3D& v : vertices) {
    const double z = row.dot(v) + tz;
    if (z > margin) continue;
    const Vector3D p = transformPoint(X_hp, v);
    out.push_back({Vector3D(p.x(), p.y(), 0.5 * z), Vector3D::UnitZ(), -z});
  }
}

void halfSpaceMesh(const MeshShape& m, const Transform3D& X_hm, double margin, Workspace& ws) {
  const auto& nodes = m.bvh().nodes();
  const Vector3D row = X_hm.linear().row(2).transpose();
  const double tz = X_hm.translation().z();
  ws.nodeStack.assign(1, {0, 0});
  while (!ws.nodeStack.empty()) {
    const auto& node = nodes[static_cast<std::size_t>(ws.nodeStack.back().first)];
    const auto index = ws.nodeStack.back().first;
    ws.nodeStack.pop_back();
    const double extent = (row.transpose() * node.box.axes).cwiseAbs().dot(node.box.halfExtents);
    if (row.dot(node.box.center) + tz - extent > margin) continue;
    if (!node.isLeaf()) {
      ws.nodeStack.emplace_back(node.second, 0);
      ws.nodeStack.emplace_back(index + 1, 0);
      continue;
    }
    for (Index t = node.first; t < node.first + node.count; ++t) {
      halfSpaceVertices(m.bvh().triangles()[static_cast<std::size_t>(t)].v, X_hm, margin,
                        ws.gathered);
    }
  }
}

void halfSpaceAgainst(const ContactShape& b, const Transform3D& X_hb, const ContactOptions& options,
                      Workspace& ws, std::vector<ContactPoint>& out) {
  const double margin = options.margin;
  ws.gathered.clear();
  switch (b.kind()) {
    case Kind::kHalfSpace:
      return;
    case Kind::kSphere: {
      const double r = static_cast<const SphereShape&>(b).radius();
      const Vector3D c = X_hb.translation();
      const double h = c.z() - r;
      if (h <= margin) out.push_back({Vector3D(c.x(), c.y(), 0.5 * h), Vector3D::UnitZ(), -h});
      return;
    }
    case Kind::kConvex:
      for (const Polytope& p : static_cast<const PolytopeShape&>(b).pieces()) {
        halfSpaceVertices(p.vertices(), X_hb, margin, ws.gathered);
      }
      break;
    case Kind::kRound:
      roundOnHalfSpace(static_cast<const RoundShape&>(b), X_hb, margin, ws, ws.gathered);
      break;
    case Kind::kMesh:
      halfSpaceMesh(static_cast<const MeshShape&>(b), X_hb, margin, ws);
      break;
  }
  reduceManifold(ws.gathered, Vector3D::UnitZ(), options.maxPointsPerManifold, out, ws.reduce);
}

// ---- sphere (A) against spheres, polytopes, meshes -------------------------------------------

void sphereMesh(double r, const MeshShape& m, const Transform3D& X_sm, double margin,
                Workspace& ws) {
  const Transform3D X_ms = X_sm.inverse(Eigen::Isometry);
  const Vector3D c = X_ms.translation();
  Obb box;
  box.center = c;
  box.halfExtents = Vector3D::Constant(r);
  const auto& nodes = m.bvh().nodes();
  ws.nodeStack.assign(1, {0, 0});
  while (!ws.nodeStack.empty()) {
    const Index index = ws.nodeStack.back().first;
    ws.nodeStack.pop_back();
    const auto& node = nodes[static_cast<std::size_t>(index)];
    if (rw::proximity::obbDisjoint(node.box, box, Rotation3D::Identity(), Vector3D::Zero(),
                                   margin)) {
      continue;
    }
    if (!node.isLeaf()) {
      ws.nodeStack.emplace_back(node.second, 0);
      ws.nodeStack.emplace_back(index + 1, 0);
      continue;
    }
    for (Index t = node.first; t < node.first + node.count; ++t) {
      const auto& tri = m.bvh().triangles()[static_cast<std::size_t>(t)];
      const TriangleInfo& info = m.info()[static_cast<std::size_t>(t)];
      if (info.normal.squaredNorm() == 0.0) continue;
      if (m.oneSided() && info.normal.dot(c - tri.v[0]) < 0.0) continue;
      const Vector3D q = rw::proximity::closestPointOnTriangle(c, tri);
      const double d = (c - q).norm();
      if (d > r + margin) continue;
      const Vector3D n = d > kTinyDistance ? Vector3D((c - q) / d) : info.normal;
      const Vector3D p = 0.5 * (q + c - r * n);
      ws.gathered.push_back({transformPoint(X_sm, p), -(X_sm.linear() * n), r - d});
    }
  }
}

void sphereAgainst(double r, const ContactShape& b, const Transform3D& X_sb,
                   const ContactOptions& options, Workspace& ws, std::vector<ContactPoint>& out) {
  const double margin = options.margin;
  ws.gathered.clear();
  switch (b.kind()) {
    case Kind::kHalfSpace:
      return;
    case Kind::kSphere: {
      const double rb = static_cast<const SphereShape&>(b).radius();
      const Vector3D c = X_sb.translation();
      const double d = c.norm();
      if (d - r - rb > margin) return;
      const Vector3D n = d > kTinyDistance ? Vector3D(c / d) : Vector3D(Vector3D::UnitZ());
      out.push_back({0.5 * (r * n + c - rb * n), n, r + rb - d});
      return;
    }
    case Kind::kConvex: {
      const Vector3D c = X_sb.inverse(Eigen::Isometry).translation();
      for (const Polytope& p : static_cast<const PolytopeShape&>(b).pieces()) {
        if (auto contact = sphereOnPolytope(p.view(), c, r, margin)) {
          ws.gathered.push_back({transformPoint(X_sb, contact->position),
                                 -(X_sb.linear() * contact->normal), contact->depth});
        }
      }
      break;
    }
    case Kind::kRound:
      roundPairContacts({.sphereRadius = r}, {.round = &static_cast<const RoundShape&>(b)}, X_sb,
                        margin, ws, ws.gathered);
      break;
    case Kind::kMesh:
      sphereMesh(r, static_cast<const MeshShape&>(b), X_sb, margin, ws);
      break;
  }
  reduceGathered(options, ws, out);
}

// ---- polytopes (A) against polytopes and meshes ---------------------------------------------

/// Contacts of polytope piece `p` (A's frame) with the triangles of mesh `m` (placed by X_pm).
void polytopeMesh(const Polytope& p, const MeshShape& m, const Transform3D& X_pm, double margin,
                  Workspace& ws) {
  const PolytopeView pv = p.view();
  const Transform3D X_mp = X_pm.inverse(Eigen::Isometry);
  Obb box = p.obb();
  box.center = transformPoint(X_mp, box.center);
  box.axes = X_mp.linear() * box.axes;
  const bool large = !pv.adjacencyOffsets.empty();
  const rw::proximity::ConvexShape hull =
      large ? rw::proximity::ConvexShape::hull(pv.vertices,
                                               {pv.adjacencyOffsets, pv.adjacency, pv.anchors})
            : rw::proximity::ConvexShape::hull(pv.vertices);
  const auto& nodes = m.bvh().nodes();
  std::vector<std::pair<Index, Index>>& stack = ws.nodeStack;
  SupportHints hints;
  stack.assign(1, {0, 0});
  while (!stack.empty()) {
    const Index index = stack.back().first;
    stack.pop_back();
    const auto& node = nodes[static_cast<std::size_t>(index)];
    if (rw::proximity::obbDisjoint(node.box, box, Rotation3D::Identity(), Vector3D::Zero(),
                                   margin)) {
      continue;
    }
    if (!node.isLeaf()) {
      stack.emplace_back(node.second, 0);
      stack.emplace_back(index + 1, 0);
      continue;
    }
    for (Index t = node.first; t < node.first + node.count; ++t) {
      const TriangleInfo& info = m.info()[static_cast<std::size_t>(t)];
      if (info.normal.squaredNorm() == 0.0) continue;
      const auto& triangle = m.bvh().triangles()[static_cast<std::size_t>(t)];
      double overlapBound = std::numeric_limits<double>::infinity();
      if (large) {
        // A large polytope's box holds many triangles it does not touch: GJK settles those,
        // and for the others bounds the overlap (0 when apart) so that the SAT culls tightly.
        const auto g = rw::proximity::gjkDistance(
            hull, rw::proximity::ConvexShape::hull(triangle.v), X_pm, 0.0, margin);
        if (g.exceeded) continue;
        if (g.distance > 0.0) overlapBound = 0.0;
      }
      const TrianglePiece piece(triangle, info.normal);
      hints.b = -1;
      pieceContacts(pv, nullptr, piece.view(), m.oneSided() ? &info : nullptr, X_pm, margin, ws,
                    hints, ws.gathered, overlapBound);
    }
  }
}

/// Contacts of the triangles of meshes `a` and `b` (b placed in a's frame by X_ab).
void meshMesh(const MeshShape& a, const MeshShape& b, const Transform3D& X_ab, double margin,
              Workspace& ws) {
  const auto& na = a.bvh().nodes();
  const auto& nb = b.bvh().nodes();
  const Rotation3D R = X_ab.linear();
  const Vector3D t = X_ab.translation();
  std::vector<std::pair<Index, Index>>& stack = ws.nodeStack;
  stack.assign(1, {0, 0});
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const auto& nodeA = na[static_cast<std::size_t>(i)];
    const auto& nodeB = nb[static_cast<std::size_t>(j)];
    if (rw::proximity::obbDisjoint(nodeA.box, nodeB.box, R, t, margin)) continue;
    const bool splitA = !nodeA.isLeaf() && (nodeB.isLeaf() || nodeA.box.halfExtents.prod() >=
                                                                  nodeB.box.halfExtents.prod());
    if (splitA) {
      stack.emplace_back(nodeA.second, j);
      stack.emplace_back(i + 1, j);
      continue;
    }
    if (!nodeB.isLeaf()) {
      stack.emplace_back(i, nodeB.second);
      stack.emplace_back(i, j + 1);
      continue;
    }
    for (Index ta = nodeA.first; ta < nodeA.first + nodeA.count; ++ta) {
      const TriangleInfo& ia = a.info()[static_cast<std::size_t>(ta)];
      if (ia.normal.squaredNorm() == 0.0) continue;
      const TrianglePiece pa(a.bvh().triangles()[static_cast<std::size_t>(ta)], ia.normal);
      for (Index tb = nodeB.first; tb < nodeB.first + nodeB.count; ++tb) {
        const TriangleInfo& ib = b.info()[static_cast<std::size_t>(tb)];
        if (ib.normal.squaredNorm() == 0.0) continue;
        const TrianglePiece pb(b.bvh().triangles()[static_cast<std::size_t>(tb)], ib.normal);
        SupportHints hints;
        pieceContacts(pa.view(), a.oneSided() ? &ia : nullptr, pb.view(),
                      b.oneSided() ? &ib : nullptr, X_ab, margin, ws, hints, ws.gathered);
      }
    }
  }
}

void polytopesAgainst(const PolytopeShape& a, const ContactShape& b, const Transform3D& X_ab,
                      const ContactOptions& options, Workspace& ws,
                      std::vector<ContactPoint>& out) {
  const double margin = options.margin;
  ws.gathered.clear();
  if (b.kind() == Kind::kMesh) {
    for (const Polytope& p : a.pieces()) {
      polytopeMesh(p, static_cast<const MeshShape&>(b), X_ab, margin, ws);
    }
    reduceGathered(options, ws, out);
    return;
  }
  if (b.kind() == Kind::kRound) {
    const ConvexPiece round{.round = &static_cast<const RoundShape&>(b)};
    for (const Polytope& p : a.pieces()) {
      roundPairContacts({.polytope = &p}, round, X_ab, margin, ws, ws.gathered);
    }
    reduceGathered(options, ws, out);
    return;
  }
  const auto& piecesB = static_cast<const PolytopeShape&>(b).pieces();
  if (a.pieces().size() == 1 && piecesB.size() == 1) {
    const PolytopeView va = a.pieces()[0].view();
    const PolytopeView vb = piecesB[0].view();
    SupportHints hints;
    const SatResult sat = separatingAxis(va, vb, X_ab, margin, ws, hints);
    ws.candidates.clear();
    manifoldFromAxis(va, vb, X_ab, sat, margin, ws, ws.candidates);
    reduceManifold(ws.candidates, sat.axis, options.maxPointsPerManifold, out, ws.reduce);
    return;
  }
  for (const Polytope& pa : a.pieces()) {
    for (const Polytope& pb : piecesB) {
      SupportHints hints;
      pieceContacts(pa.view(), nullptr, pb.view(), nullptr, X_ab, margin, ws, hints, ws.gathered);
    }
  }
  reduceGathered(options, ws, out);
}

/// Contacts of round shape A with a round shape or (through A's tessellation) a mesh.
void roundAgainst(const RoundShape& a, const ContactShape& b, const Transform3D& X_ab,
                  const ContactOptions& options, Workspace& ws, std::vector<ContactPoint>& out) {
  ws.gathered.clear();
  if (b.kind() == Kind::kRound) {
    roundPairContacts({.round = &a}, {.round = &static_cast<const RoundShape&>(b)}, X_ab,
                      options.margin, ws, ws.gathered);
  } else if (b.kind() == Kind::kMesh) {
    polytopeMesh(a.polytope(), static_cast<const MeshShape&>(b), X_ab, options.margin, ws);
  }
  reduceGathered(options, ws, out);
}

/// Contacts of a canonically ordered pair, in A's frame.
void collideLocal(const ContactShape& a, const ContactShape& b, const Transform3D& X_ab,
                  const ContactOptions& options, Workspace& ws, std::vector<ContactPoint>& out) {
  switch (a.kind()) {
    case Kind::kHalfSpace:
      halfSpaceAgainst(b, X_ab, options, ws, out);
      return;
    case Kind::kSphere:
      sphereAgainst(static_cast<const SphereShape&>(a).radius(), b, X_ab, options, ws, out);
      return;
    case Kind::kConvex:
      polytopesAgainst(static_cast<const PolytopeShape&>(a), b, X_ab, options, ws, out);
      return;
    case Kind::kRound:
      roundAgainst(static_cast<const RoundShape&>(a), b, X_ab, options, ws, out);
      return;
    case Kind::kMesh:
      ws.gathered.clear();
      meshMesh(static_cast<const MeshShape&>(a), static_cast<const MeshShape&>(b), X_ab,
               options.margin, ws);
      reduceGathered(options, ws, out);
      return;
  }
}

}  // namespace

void collidePlaced(const ContactShape& a, const Transform3D& X_W_a, const Transform3D& X_a_W,
                   const ContactShape& b, const Transform3D& X_W_b, const Transform3D& X_b_W,
                   const ContactOptions& options, Workspace& ws, std::vector<ContactPoint>& out) {
  const Transform3D X_ab = X_a_W * X_W_b;
  const bool swapped = swapToCanonical(a.kind(), b.kind(), X_ab);
  const ContactShape& first = swapped ? b : a;
  const ContactShape& second = swapped ? a : b;
  const Transform3D& X_W_first = swapped ? X_W_b : X_W_a;
  // The pose of the second shape in the first's frame: X_ab itself unless swapped.
  const Transform3D X_fs = swapped ? Transform3D(X_b_W * X_W_a) : X_ab;
  const std::size_t begin = out.size();
  collideLocal(first, second, X_fs, options, ws, out);
  const double sign = swapped ? -1.0 : 1.0;
  for (std::size_t i = begin; i < out.size(); ++i) {
    out[i].position = transformPoint(X_W_first, out[i].position);
    out[i].normal = sign * (X_W_first.linear() * out[i].normal);
  }
}

}  // namespace detail

void collide(const ContactShape& a, const rw::math::Transform3D& X_W_a, const ContactShape& b,
             const rw::math::Transform3D& X_W_b, const ContactOptions& options,
             std::vector<ContactPoint>& out) {
  detail::collidePlaced(a, X_W_a, X_W_a.inverse(Eigen::Isometry), b, X_W_b,
                        X_W_b.inverse(Eigen::Isometry), options, detail::threadWorkspace(), out);
}

}  // namespace rwsim::contacts
