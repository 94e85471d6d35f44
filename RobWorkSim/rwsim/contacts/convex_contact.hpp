#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "rwsim/contacts/contact_detector.hpp"
#include "rwsim/contacts/manifold.hpp"
#include "rwsim/contacts/polytope.hpp"

/// Contacts between convex pieces (internal to rwsim_contacts). Shape B is placed in shape A's
/// frame by X_ab; results are in A's frame with normals from A towards B.
namespace rwsim::contacts::detail {

/// An edge of B moved into A's frame, with its negated Gauss arc, for the edge-edge tests.
struct MovedEdge {
  /// First end.
  rw::math::Vector3D p0;
  /// Second end.
  rw::math::Vector3D p1;
  /// Negated arc start.
  rw::math::Vector3D c;
  /// Negated arc end.
  rw::math::Vector3D d;
  /// d x c.
  rw::math::Vector3D dc;
  /// Index in B's edge list.
  std::int32_t index = 0;
};

/// Reusable buffers of one thread (grown once, then no allocation).
struct Workspace {
  /// Features of A near B.
  std::vector<std::int32_t> nearA;
  /// Features of B near A.
  std::vector<std::int32_t> nearB;
  /// B's edges near A, in A's frame.
  std::vector<MovedEdge> movedEdges;
  /// Polygon being clipped.
  std::vector<rw::math::Vector3D> clipIn;
  /// Clipped polygon.
  std::vector<rw::math::Vector3D> clipOut;
  /// Support feature of A (round-shape pairs).
  std::vector<rw::math::Vector3D> featureA;
  /// Support feature of B (round-shape pairs), moved into A's frame.
  std::vector<rw::math::Vector3D> featureB;
  /// Candidates of one convex pair.
  std::vector<ContactPoint> candidates;
  /// Candidates of a multi-piece pair (world frame).
  std::vector<ContactPoint> gathered;
  /// Pairs of hierarchy nodes still to visit.
  std::vector<std::pair<std::int32_t, std::int32_t>> nodeStack;
  /// Reduction buffers.
  ReduceScratch reduce;
};

/// The workspace of the calling thread.
Workspace& threadWorkspace();

/// collide() for a caller that keeps each shape's world pose and its inverse
/// (X_a_W = X_W_a.inverse(Eigen::Isometry)) and the thread's workspace: the same contacts, bit
/// for bit, without recomputing the inverses or looking the workspace up per pair.
void collidePlaced(const ContactShape& a, const rw::math::Transform3D& X_W_a,
                   const rw::math::Transform3D& X_a_W, const ContactShape& b,
                   const rw::math::Transform3D& X_W_b, const rw::math::Transform3D& X_b_W,
                   const ContactOptions& options, Workspace& ws, std::vector<ContactPoint>& out);

/// The feature whose axis separates A and B least (or overlaps them least).
struct SatResult {
  /// What the axis is.
  enum class Kind { kNone, kFaceA, kFaceB, kEdges };
  /// kNone: separated by more than the margin (no contact).
  Kind kind = Kind::kNone;
  /// Face (kFaceA) or edge (kEdges) of A.
  std::int32_t featureA = -1;
  /// Face (kFaceB) or edge (kEdges) of B.
  std::int32_t featureB = -1;
  /// Signed separation along the axis (negative: overlap depth).
  double separation = -std::numeric_limits<double>::infinity();
  /// The axis in A's frame, unit, from A towards B.
  rw::math::Vector3D axis = rw::math::Vector3D::UnitZ();
};

/// Where the support searches of A and B start (vertex indices, -1 for none); kept across
/// calls with the same shapes in slowly changing poses (triangles of one mesh against one
/// polytope), they shorten the hill climbs.
struct SupportHints {
  /// Hint into A's vertices.
  std::int32_t a = -1;
  /// Hint into B's vertices.
  std::int32_t b = -1;
};

/// Separating-axis test over the face normals of both and the edge pairs whose Gauss arcs
/// cross; features farther from the other shape's box than the overlap bound are skipped.
/// Faces are preferred over edges, and A's faces over B's, unless clearly worse; between
/// nearly equal faces the one with fewer vertices is the reference. Overlaps deeper than
/// max(5 mm, 10 margins) along every face axis with possibly more than 4096 edge pairs to try
/// keep the best face axis (large polytopes overlapping by design, such as links at a joint).
/// `overlapBound`, if known, bounds the overlap depth from above (0 for shapes known apart).
SatResult separatingAxis(const PolytopeView& a, const PolytopeView& b,
                         const rw::math::Transform3D& X_ab, double margin, Workspace& ws,
                         SupportHints& hints,
                         double overlapBound = std::numeric_limits<double>::infinity());

/// Separation of A and B along unit axis `u` (A's frame, from A to B), from their supports.
double separationAlong(const PolytopeView& a, const PolytopeView& b,
                       const rw::math::Transform3D& X_ab, const rw::math::Vector3D& u);

/// Appends the contact candidates of `sat` to `out`: the incident face clipped against the
/// reference face (Sutherland-Hodgman), points within the margin, positions midway; or the
/// closest points of two edges.
void manifoldFromAxis(const PolytopeView& a, const PolytopeView& b,
                      const rw::math::Transform3D& X_ab, const SatResult& sat, double margin,
                      Workspace& ws, std::vector<ContactPoint>& out);

/// Contact of a sphere (centre `center` in P's frame) with polytope P, normal from P to the
/// sphere; nullopt when farther apart than the margin.
std::optional<ContactPoint> sphereOnPolytope(const PolytopeView& p,
                                             const rw::math::Vector3D& center, double radius,
                                             double margin);

}  // namespace rwsim::contacts::detail
