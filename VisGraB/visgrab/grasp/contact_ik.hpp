#pragma once

#include <string>
#include <vector>

#include "rw/math/types.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/request/grasp_request.hpp"

namespace visgrab::grasp {

/// What the contact IK found: the best attempt, valid or not.
struct ContactIkResult {
  /// True if the best attempt is within all of the description's limits.
  bool valid = false;
  /// Why not valid (empty when valid).
  std::string reason;
  /// Pose of the hand's base frame.
  rw::math::Transform3D X_W_base = rw::math::Transform3D::Identity();
  /// Pose of the hand's TCP frame (X_W_base * X_base_tcp).
  rw::math::Transform3D X_W_tcp = rw::math::Transform3D::Identity();
  /// Configuration with the fingertips at the contacts.
  rw::math::Q qContact;
  /// qContact backed off: the fingertips `backoff` short of the contacts (same base pose).
  rw::math::Q qOpen;
  /// qOpen + the closing offsets of the grasp used.
  rw::math::Q qClosed;
  /// The torque rule at qOpen.
  rw::math::Q tauMax;
  /// Largest fingertip distance from its contact at qContact, m.
  double positionError = 0.0;
  /// Largest angle between a fingertip's push direction and its contact's direction, rad.
  double directionError = 0.0;
  /// Angle between the hand's approach axis and the requested approach, rad.
  double approachError = 0.0;
  /// Index of the ContactIkSettings::grasps entry used (-1 if none could be tried).
  int grasp = -1;
  /// For each contact (in request order), the fingertip index it was given.
  std::vector<int> fingerOfContact;
  /// Number of solver runs made.
  int attempts = 0;

  /// The grasp to simulate: X_W_tcp, qOpen, qClosed and tauMax.
  rwsim::simulator::GraspParameters parameters() const { return {X_W_tcp, qOpen, qClosed, tauMax}; }
};

/// Contact inverse kinematics (paper §2.3.1), this project's own design:
///  - Unknowns: the hand base pose (6) and the joints the description's <Grasp> allows; the
///    other joints stay at the seed's values; joint limits are enforced by clamping each step.
///  - For each <Grasp> with as many fingers as there are contacts, each assignment of contacts
///    to its fingers (all permutations) and each of its seeds: the base is seeded so that its
///    approach axis is along `approach` and, at the seed configuration, the fingertips'
///    centroid is on the contacts' centroid, turned about the approach (a 1-D least-squares
///    fit) so that each fingertip lies towards its contact.
///  - Levenberg-Marquardt, twice: first with the direction weight 10 x directionWeight (to
///    land in the basin of the right finger posture), then as described, on the residuals:
///    fingertip pad point - contact (3 per finger), directionWeight * (pad push direction - contact
///    direction) (3 per finger), approachWeight * (hand approach axis - approach) (3) and 1e-3
///    m/rad * (q - seed) to keep redundant joints near the seed. Analytic Jacobian (base twist and
///    joints, dependent joints through their gains).
///  - An attempt is valid if every fingertip is within maxPositionError of its contact, every
///    push direction within maxDirectionError and the approach within maxApproachError. The
///    result is the best valid attempt (below), else the attempt with the smallest
///    position error (invalid, with the reason). Among valid attempts the one whose base is
///    farthest behind the contacts' centroid along the approach (less 10 m per m of position
///    error) is chosen: it keeps the palm away from the object (the solver ignores collisions).
///  - Back-off: with the base fixed, the allowed joints are solved again for targets
///    `backoff` metres short of each contact (against its direction), giving qOpen; qClosed =
///    qOpen + the closing offsets; tauMax by the torque rule at qOpen.
/// Contacts are not checked for collisions with the hand (the simulator reports them).
/// Deterministic: no randomness, fixed order of attempts; const on `setup`, thread-safe.
/// @throws std::invalid_argument if the hand has no contact IK or is a parallel device (closed
/// loops are not supported yet), no <Grasp> takes contacts.size() contacts, a direction or the
/// approach is (near) zero.
ContactIkResult solveContactIk(const HandGraspSetup& setup,
                               const std::vector<DesiredContact>& contacts,
                               const rw::math::Vector3D& approach);

/// The contact IK's distinct valid solutions, best first by solveContactIk's rule, at most
/// `maxSolutions` (>= 1); when none is valid, only the best invalid attempt (so the first entry
/// is always solveContactIk's result). Two attempts are the same solution when their contact
/// assignment is the same, their bases lie within 1 mm and 1 degree and their joints within
/// 0.01 rad (or 1 mm). Deterministic, thread-safe.
/// @throws std::invalid_argument as solveContactIk.
std::vector<ContactIkResult> contactIkSolutions(const HandGraspSetup& setup,
                                                const std::vector<DesiredContact>& contacts,
                                                const rw::math::Vector3D& approach,
                                                int maxSolutions);

/// `solution` (one of contactIkSolutions' for the same contacts) with its base moved to
/// X_W_base: the solution's <Grasp> joints are solved again from its qContact towards the same
/// fingertip assignment (base fixed), the errors measured against the description's limits
/// (`valid`), and qOpen solved with the fingertips `backoff` short of the contacts; qClosed and
/// tauMax follow as in solveContactIk. Deterministic, thread-safe.
/// @throws std::invalid_argument as solveContactIk, or if `solution` has another contact count.
ContactIkResult refitContactIk(const HandGraspSetup& setup,
                               const std::vector<DesiredContact>& contacts,
                               const rw::math::Vector3D& approach, const ContactIkResult& solution,
                               const rw::math::Transform3D& X_W_base, double backoff);

/// `refitted` (a refitContactIk result) with qOpen solved again for another `backoff`: its base
/// and qContact kept, the errors measured at them. Equal, double for double, to
/// refitContactIk(setup, contacts, approach, solution, X_W_base, backoff) for the `solution`
/// and X_W_base that gave `refitted`, without solving the fingers again. Deterministic,
/// thread-safe. @throws std::invalid_argument as refitContactIk.
ContactIkResult reopenContactIk(const HandGraspSetup& setup,
                                const std::vector<DesiredContact>& contacts,
                                const rw::math::Vector3D& approach, const ContactIkResult& refitted,
                                double backoff);

}  // namespace visgrab::grasp
