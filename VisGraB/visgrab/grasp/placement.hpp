#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rw/math/types.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/contact_ik.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/request/grasp_request.hpp"

namespace visgrab::grasp {

/// Whether the hand, placed with these parameters in a scene, penetrates it; e.g.
/// GraspTrial::checkPlacement with the scene's initial state (the trial's own test).
using PlacementTest =
    std::function<rwsim::simulator::PlacementCheck(const rwsim::simulator::GraspParameters&)>;

/// How far the placement search may move the hand from the contact IK's own solution.
struct PlacementOptions {
  /// A candidate's fingertips may be this much farther from their contacts (the largest
  /// fingertip deviation) than the contact IK's solution it comes from, m.
  double contactSlack = 0.005;
  /// Distinct contact IK solutions tried (contactIkSolutions), best first.
  int maxSolutions = 3;
  /// Moves of the hand's base back along the approach (fingers solved again to reach), m;
  /// the first must be 0.
  std::vector<double> approachBackoffs{0.0, 0.01, 0.02};
  /// Extra opening: fingertips this much farther short of their contacts at q_open than the
  /// description's backoff, m; the first must be 0. Up to 6 cm: a pinch whose far contact was
  /// guessed inside the object (its back unseen) opens round the object's real thickness.
  std::vector<double> extraOpenings{0.0, 0.01, 0.02, 0.04, 0.06};
  /// Two-contact grasps: turns of the hand about the line through the two contacts (which
  /// keeps the fingertips on them and tilts the approach), rad; the first must be 0.
  std::vector<double> rolls{0.0, 20.0 * rw::math::kDeg2Rad, -20.0 * rw::math::kDeg2Rad,
                            40.0 * rw::math::kDeg2Rad, -40.0 * rw::math::kDeg2Rad};
};

/// The outcome of a placement search.
struct Placement {
  /// True when `ik` is a collision-free placement.
  bool found = false;
  /// The placement chosen (found), else the candidate that penetrated least.
  ContactIkResult ik;
  /// The scene test of `ik` (collides false when found).
  rwsim::simulator::PlacementCheck check;
  /// Candidates within the description's limits and the contact slack.
  int candidates = 0;
  /// Scene tests made.
  int tests = 0;
  /// The moves of the chosen candidate: solution rank (0 = the contact IK's choice), approach
  /// back-off (m), roll (rad), extra opening (m).
  int solution = 0;
  /// See solution.
  double approachBackoff = 0.0;
  /// See solution.
  double roll = 0.0;
  /// See solution.
  double extraOpening = 0.0;

  /// One line for trial details, e.g. "placement: IK solution 2, backed off 10 mm along the
  /// approach, rolled 20 deg, opened 10 mm more (3 scene tests)".
  std::string describe() const;
};

/// Collision-aware placement of a contact grasp (paper Fig. 1 d: "the hand pose and
/// configuration are determined by the provided software"). `solutions` are the contact IK's
/// (contactIkSolutions for these contacts, first the IK's own choice, which must be valid).
/// The rule:
///  1. The contact IK's own choice is taken when `test` finds it collision-free.
///  2. Otherwise candidates are made from each of the first options.maxSolutions solutions:
///     every combination of a roll (two-contact grasps only), an approach back-off (base moved
///     back along the requested approach, fingers solved again: refitContactIk) and an extra
///     opening. A candidate counts when it is within the description's limits and its
///     fingertip deviation is at most its solution's plus options.contactSlack.
///  3. Candidates are ordered by their fingertip deviation rounded up to whole millimetres
///     (meeting the contacts best first), then by the number of moves made (each list's index
///     summed: fewest and smallest first), then by solution, roll, back-off and opening index.
///     The first that `test` finds collision-free is chosen.
///  4. When none is, the result is not found: the candidate with the smallest penetration
///     (ties: the earlier in that order) with its test, so the trial reports that penetration.
/// Worst case per grasp: maxSolutions x rolls x approachBackoffs finger solves (45 with the
/// defaults for two contacts, 9 for three) and that many x extraOpenings scene tests (225 and
/// 45). Deterministic: no randomness, fixed order; thread-safe when `test` is.
/// @throws std::invalid_argument for empty or invalid `solutions`, or option lists that do not
/// start with 0.
Placement placeContactGrasp(const HandGraspSetup& setup,
                            const std::vector<DesiredContact>& contacts,
                            const rw::math::Vector3D& approach,
                            const std::vector<ContactIkResult>& solutions,
                            const PlacementTest& test, const PlacementOptions& options = {});

}  // namespace visgrab::grasp
