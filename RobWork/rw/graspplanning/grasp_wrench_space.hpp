#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rw/graspplanning/contact3d.hpp"
#include "rw/math/types.hpp"

/// Grasp quality measures (RobWork's rw::graspplanning).
namespace rw::graspplanning {

/// A point of the grasp wrench space: (force; torque / r), r the object's largest radius.
using Wrench6D = Eigen::Matrix<double, 6, 1>;

/// How the friction cones of the grasp wrench space are built.
struct GwsOptions {
  /// Edges of each linearised friction cone (RobWork's GraspTaskSimulator uses 10); at least 3.
  int coneEdges = 10;
  /// Scale each cone by the contact's measured normal force instead of a unit normal force.
  bool useMeasuredNormalForce = false;
};

/// Why a grasp-wrench-space evaluation produced its epsilon.
enum class GwsStatus {
  kForceClosure,     ///< The origin is strictly inside the 6-D hull; epsilon > 0.
  kNotForceClosure,  ///< Full-dimensional hull, origin outside or on its boundary; epsilon 0.
  kTooFewPoints,     ///< Fewer than 7 distinct wrench points (no contacts, mu = 0); epsilon 0.
  kFlat,             ///< The points span fewer than 6 dimensions (one or two contacts); epsilon 0.
  kInvalidInput,     ///< NaN/inf, a zero normal, mu < 0, a negative force or r <= 0; epsilon 0.
  kQhullError,       ///< Qhull failed for another reason (see GwsResult::detail); epsilon 0.
};

/// The status's name, e.g. "ForceClosure".
std::string_view toString(GwsStatus status);

/// Result of a Ferrari-Canny L1 evaluation.
struct GwsResult {
  /// Distance from the origin to the nearest hull facet if the origin is strictly inside, else 0.
  double epsilon = 0.0;
  /// True iff status == kForceClosure (then epsilon > 0).
  bool forceClosure = false;
  /// Number of hull facets (0 when no hull was built).
  int facets = 0;
  /// Distinct wrench points handed to Qhull.
  int points = 0;
  /// Why epsilon has its value.
  GwsStatus status = GwsStatus::kTooFewPoints;
  /// The exact hull failed on nearly flat input and Qhull's joggle (fixed seed) was used; epsilon
  /// is then accurate to ~1e-10 of the largest wrench instead of to rounding.
  bool joggled = false;
  /// Why, when status is kFlat or kQhullError (then Qhull's own message), else empty.
  std::string detail;
};

/// The friction-cone edge wrenches of each contact, in contact order, `coneEdges` per contact:
/// f_k = s (n + mu (cos(2 pi k/m) t + sin(2 pi k/m) n x t)) with s = 1 (or the measured normal
/// force), t RobWork's tangent of n, and w_k = (f_k, (p - c) x f_k / r).
/// Preconditions: finite input, r > 0. No validation, deduplication or sorting.
/// @throws std::invalid_argument if options.coneEdges < 3.
std::vector<Wrench6D> contactWrenches(std::span<const Contact3D> contacts,
                                      const rw::math::Vector3D& centerOfMass, double maxRadius,
                                      const GwsOptions& options = {});

/// Ferrari-Canny L1 epsilon of a grasp (VisGraB's Q_gws, paper eq. 6-7): the convex hull of all
/// cone-edge wrenches, epsilon = distance from the origin to its nearest facet. `centerOfMass` is
/// the torque origin c and `maxRadius` the object's largest surface distance r from c.
/// Epsilon is never negative: 0 means "not force closure", including every degenerate case (see
/// GwsStatus). RobWork instead adds the origin as a hull vertex, which gives the same numbers
/// (the hull is unchanged when the origin is inside; facets through it give 0 when it is not),
/// up to its joggle noise (~1e-10). Contacts are deduplicated (position, normal, mu and force
/// within 1e-9) and put in a canonical order, so the result does not depend on contact order.
/// Thread-safe (reentrant Qhull, one qhT per call).
/// @throws std::invalid_argument if options.coneEdges < 3.
GwsResult gwsEpsilon(std::span<const Contact3D> contacts, const rw::math::Vector3D& centerOfMass,
                     double maxRadius, const GwsOptions& options = {});

/// Epsilon of the convex hull of given wrench points (sorted and deduplicated exactly first, so
/// the result does not depend on their order). Thread-safe.
GwsResult gwsEpsilonOfWrenches(std::span<const Wrench6D> wrenches);

}  // namespace rw::graspplanning
