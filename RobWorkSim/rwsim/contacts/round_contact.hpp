#pragma once

#include <vector>

#include "rwsim/contacts/convex_contact.hpp"
#include "rwsim/contacts/shapes.hpp"

/// Contacts of round shapes (cylinders, cones, frusta) with half-spaces, spheres, polytopes and
/// each other (internal to rwsim_contacts). Shape B is placed in shape A's frame by X_ab;
/// results are in A's frame with normals from A towards B.
///
/// The normal comes from GJK between the cores (a round shape's core grown by its rounding is
/// the shape with rims rounded, so the normal is exact on caps and sides and turns smoothly
/// around a rim). The points come from the support features of the true shapes in that normal:
/// a cap as kRimPoints points on its true circle when the normal is within kFeatureAngle of the
/// axis, a side line (generator) when within kFeatureAngle of the side's normal, else the
/// single farthest point; a polytope's face or edge within the same angle. A flat feature is
/// the reference (a polytope's face before a cap); the other feature is clipped against its
/// sides and each point's depth is measured to its plane, so depths are exact for the points.
namespace rwsim::contacts::detail {

/// Angle (rad) within which a normal selects a cap, a side line, a face or an edge: 3 degrees.
inline constexpr double kFeatureAngle = 3.0 * rw::math::kDeg2Rad;
/// Points on a cap's rim (equally spaced on the true circle, the first on the +x axis).
inline constexpr int kRimPoints = 16;

/// One convex piece of a pair: a polytope, a sphere about the origin or a round shape.
struct ConvexPiece {
  /// The polytope, or null.
  const Polytope* polytope = nullptr;
  /// The round shape, or null.
  const RoundShape* round = nullptr;
  /// The sphere's radius when both pointers are null.
  double sphereRadius = 0.0;
};

/// Appends the contacts of round shape R (placed by X_hr) with the half-space z <= 0 (normal
/// +z): the points of R's support feature along -z that are within the margin of the plane.
void roundOnHalfSpace(const RoundShape& r, const rw::math::Transform3D& X_hr, double margin,
                      Workspace& ws, std::vector<ContactPoint>& out);

/// Appends the contacts of two convex pieces, at least one of them round (see the namespace
/// comment). Overlaps deeper than the rounding (the cores touch) fall back to the tessellation's
/// polytope contacts.
void roundPairContacts(const ConvexPiece& a, const ConvexPiece& b,
                       const rw::math::Transform3D& X_ab, double margin, Workspace& ws,
                       std::vector<ContactPoint>& out);

}  // namespace rwsim::contacts::detail
