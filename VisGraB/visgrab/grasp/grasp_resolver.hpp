#pragma once

#include <string>

#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/contact_ik.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/grasp/placement.hpp"
#include "visgrab/request/grasp_request.hpp"

namespace visgrab::grasp {

/// How resolving a request ended.
enum class ResolveStatus {
  kOk,               ///< `parameters` are ready to simulate
  kInvalidContacts,  ///< the contact IK found no configuration (outcome "invalid contacts")
  kInputError,       ///< the request itself is wrong (unknown pre-shape, wrong q length, ...)
  kInCollision,      ///< a contact grasp with no collision-free placement (outcome "in collision")
};

/// A request turned into simulator parameters (paper eq. 2-4), or why not.
struct ResolvedGrasp {
  /// Ok, invalid contacts or input error.
  ResolveStatus status = ResolveStatus::kInputError;
  /// The grasp to simulate (kOk; for kInvalidContacts the IK's best attempt and for
  /// kInCollision the least penetrating placement, for display only).
  rwsim::simulator::GraspParameters parameters;
  /// Empty when ok; else "FILE:LINE: grasp ID: what is wrong" (FILE:LINE omitted if unknown).
  std::string message;
  /// What is wrong, without the FILE:LINE and grasp id of `message` (for messages that give
  /// those themselves, e.g. a rw::common::Diagnostic).
  std::string reason;
  /// Details of the contact IK (kContacts requests only).
  std::optional<ContactIkResult> ik;
  /// The placement search (kContacts requests resolved in a scene, when the IK was valid).
  std::optional<Placement> placement;

  /// True when status is kOk.
  bool ok() const { return status == ResolveStatus::kOk; }
  /// True when `parameters` place the hand (kOk, or kInCollision: the least penetrating
  /// placement, which a trial reports as in collision).
  bool placed() const {
    return status == ResolveStatus::kOk || status == ResolveStatus::kInCollision;
  }
};

/// Turns a grasp request into simulator parameters with the hand's rules:
///  - kRaw: the given values; an empty tauMax becomes the torque rule at qOpen;
///  - kPreshape: the named pre-shape (name or alias) at X_W_tcp (converted from the pre-shape's
///    own TCP frame if it names one);
///  - kPoseAndQ: qOpen = q, qClosed = q + the closing offsets, tauMax by the rule at q;
///  - kContacts: solveContactIk; kInvalidContacts if its best solution is out of the limits.
///    With a `scene`, the placement search (placeContactGrasp) then chooses a collision-free
///    placement, or gives kInCollision with the smallest penetration found in the message.
/// Wrong lengths, unknown pre-shapes, non-finite values, unsuitable contact counts or zero
/// directions give kInputError with a message naming request.sourceFile:sourceLine and id.
/// Never throws for bad requests; const on `setup`, safe from many threads.
ResolvedGrasp resolve(const GraspRequest& request, const HandGraspSetup& setup);

/// resolve() with contact grasps placed in a scene: `scene` tests placements (e.g.
/// GraspTrial::checkPlacement at the scene's initial state); other kinds stay as given (the
/// user chose them). Thread-safe when `scene` is.
ResolvedGrasp resolve(const GraspRequest& request, const HandGraspSetup& setup,
                      const PlacementTest& scene, const PlacementOptions& options = {});

/// "ok", "invalid_contacts", "input_error" or "in_collision".
const char* resolveStatusName(ResolveStatus status);

}  // namespace visgrab::grasp
