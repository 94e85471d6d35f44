#pragma once

#include <Eigen/Core>
#include <cstdint>
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

/// What each friction cone is centred on and how long its edges are.
enum class GwsForce {
  /// Axis the contact normal, normal force 1 (RobWork's GraspTaskSimulator, useUnitVectors).
  kUnitNormal,
  /// Axis the contact normal, scaled by Contact3D::normalForce (RobWork's GWSMeasure3D without
  /// unit vectors).
  kMeasuredNormalForce,
  /// Axis the measured contact force f = Contact3D::force, scaled by |f| (the paper, §2.4.1:
  /// "the direction of the friction cone is determined by the contact force f_i").
  kMeasuredForce,
};

/// How the hull is built (both exact; see gwsEpsilonOfWrenches).
enum class GwsHull {
  kLazy,   ///< Grown from a few support points until the facet nearest the origin is final.
  kWhole,  ///< Qhull's whole hull of all points (this project's method before kLazy).
};

/// Seed of the fixed generator that jitters the copies of GwsOptions::duplicateBelow.
inline constexpr std::uint64_t kGwsJitterSeed = 20120312;

/// How the friction cones of the grasp wrench space are built.
struct GwsOptions {
  /// Edges of each linearised friction cone (RobWork's GraspTaskSimulator uses 10); at least 3.
  int coneEdges = 10;
  /// Cone axis and scale.
  GwsForce force = GwsForce::kUnitNormal;
  /// Merge contacts that share a cluster id >= 0 into one (see gwsEpsilon); off by default.
  bool mergeClusters = false;
  /// The VisGraB-era rule (RobWork's SimTaskPlugin): with fewer than this many contacts (after
  /// validation, deduplication and merging) each contact gets a jittered copy. 0: never.
  int duplicateBelow = 0;
  /// Each copy's cone axis components move by a uniform amount in [-jitterAxis, jitterAxis],
  /// then the axis is renormalised (the plugin: 0.1).
  double jitterAxis = 0.1;
  /// Each copy's position components move by a uniform amount in [-jitterPosition,
  /// jitterPosition], m (the plugin: 2 mm).
  double jitterPosition = 0.002;
  /// Seed of the jitter generator, restarted on every call.
  std::uint64_t jitterSeed = kGwsJitterSeed;
  /// How the hull is built.
  GwsHull hull = GwsHull::kLazy;
};

/// Measured forces below this are skipped (RobWork's GWSMeasure3D), N.
inline constexpr double kGwsMinForce = 1e-4;

/// Why a grasp-wrench-space evaluation produced its epsilon.
enum class GwsStatus {
  kForceClosure,     ///< The origin is strictly inside the 6-D hull; epsilon > 0.
  kNotForceClosure,  ///< Full-dimensional hull, origin outside or on its boundary; epsilon 0.
  kTooFewPoints,     ///< Fewer than 7 distinct wrench points (no contacts, mu = 0); epsilon 0.
  kFlat,             ///< The points span fewer than 6 dimensions (one or two contacts); epsilon 0.
  kInvalidInput,     ///< NaN/inf, a zero normal, mu < 0, a negative force or r <= 0; epsilon 0.
                     ///< (A measured force is only checked when GwsOptions::force uses it.)
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
  /// Cones whose edges made the wrench points (gwsEpsilon steps 1-4; 0 for gwsEpsilonOfWrenches).
  int cones = 0;
  /// Why epsilon has its value.
  GwsStatus status = GwsStatus::kTooFewPoints;
  /// The whole hull was built: asked for (GwsHull::kWhole), or the lazily grown hull did not
  /// apply (see gwsEpsilonOfWrenches).
  bool wholeHull = false;
  /// The exact hull failed on nearly flat input and Qhull's joggle (fixed seed) was used; epsilon
  /// is then accurate to ~1e-10 of the largest wrench instead of to rounding.
  bool joggled = false;
  /// Why, when status is kFlat or kQhullError (then Qhull's own message), else empty.
  std::string detail;
};

/// The friction-cone edge wrenches of each contact, in contact order, `coneEdges` per contact:
/// f_k = s (a + mu (cos(2 pi k/m) t + sin(2 pi k/m) a x t)) and w_k = (f_k, (p - c) x f_k / r),
/// with axis a and scale s by options.force (kUnitNormal: the normal and 1; kMeasuredNormalForce:
/// the normal and normalForce; kMeasuredForce: f/|f| and |f|) and t RobWork's tangent of a.
/// Preconditions: finite input, r > 0, nonzero force with kMeasuredForce. No validation,
/// deduplication, merging, jitter or sorting.
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
/// up to its joggle noise (~1e-10).
/// Steps, each independent of the contacts' order:
///  1. Each contact becomes a cone (axis, scale; see contactWrenches). With a measured force,
///     contacts whose scale is below kGwsMinForce are skipped (RobWork's GWSMeasure3D).
///  2. Cones are put in a canonical (lexicographic) order; near-duplicates (position, axis, mu
///     and scale within 1e-9) are kept once.
///  3. mergeClusters: the cones of one cluster become one cone at their scale-weighted mean
///     position, with the scale-weighted mean axis (renormalised), the summed scale (so with
///     kMeasuredForce the merged force is close to the sum of the forces) and the scale-weighted
///     mean mu.
///  4. Fewer than duplicateBelow cones: each cone, in canonical order, gets a copy whose axis and
///     position are jittered (jitterAxis, jitterPosition) by a 64-bit Mersenne Twister seeded
///     with jitterSeed on every call (three axis draws, then three position draws per cone;
///     uniform doubles from the top 53 bits), so the result depends on the contacts only.
///  5. The hull of the cones' edge wrenches (gwsEpsilonOfWrenches with options.hull).
/// Thread-safe (reentrant Qhull, one qhT per call).
/// @throws std::invalid_argument if options.coneEdges < 3 or duplicateBelow < 0.
GwsResult gwsEpsilon(std::span<const Contact3D> contacts, const rw::math::Vector3D& centerOfMass,
                     double maxRadius, const GwsOptions& options = {});

/// Epsilon of the convex hull of given wrench points (sorted and deduplicated exactly first, so
/// the result does not depend on their order). Thread-safe.
/// The hull is grown lazily, as in EPA (expanding polytope): it starts from the support points of
/// the 12 directions +-e_i; while some point lies beyond the facet nearest to the origin, the
/// one farthest beyond it is added. When none is, that facet's hyperplane supports all points,
/// so epsilon is its distance (the partial hull lies inside the whole one and has that facet
/// nearest). This is exact like the whole hull, to 1e-12 of the largest wrench, and usually
/// builds a small part of it (5-20 times faster on real SDH contacts). If the start is flat or
/// Qhull does not take a point, the whole hull is built (wholeHull); if that fails on nearly
/// flat input, Qhull's joggle with a fixed seed (joggled).
GwsResult gwsEpsilonOfWrenches(std::span<const Wrench6D> wrenches, GwsHull hull = GwsHull::kLazy);

}  // namespace rw::graspplanning
