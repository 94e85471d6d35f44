#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rw/math/types.hpp"

/// Grasp hypotheses as users give them, and their turning into simulator parameters (paper §2.3).
namespace visgrab::grasp {

/// The four ways a user can state a grasp (paper §2.3, Figure 1c).
enum class GraspKind {
  kRaw,       ///< X_hand, q_open, q_closed, tau_max
  kPreshape,  ///< a named pre-shape of the hand + X_hand
  kPoseAndQ,  ///< X_hand + one configuration q (q_open = q, q_closed and tau_max by the hand's
              ///< rule)
  kContacts,  ///< 2 or 3 desired contacts (position, push direction) + approach, solved by IK
  kJaw,       ///< a parallel-jaw grasp: the jaw frame's pose + the opening it needs, placed
              ///< through the hand's declared jaw frame (any parallel-jaw hand)
};

/// A desired finger contact, in the scene's world (table) frame.
struct DesiredContact {
  /// Where the finger should touch, m.
  rw::math::Vector3D position = rw::math::Vector3D::Zero();
  /// Direction in which the finger should push (into the object); need not be unit.
  rw::math::Vector3D direction = rw::math::Vector3D::UnitX();
};

/// One grasp hypothesis for one scene, before the grasp utilities resolve it.
struct GraspRequest {
  /// Scene id (ours or the original database's spelling).
  std::string sceneId;
  /// The grasp's id, unique within its scene and method (e.g. "g1", or a line number).
  std::string id;
  /// What the analyses group by: the grasp type ("s3EGA1") or, if none, the file's name.
  std::string method;
  /// Which fields below are meaningful.
  GraspKind kind = GraspKind::kRaw;
  /// Pose of the hand's TCP frame in the world (kRaw, kPreshape, kPoseAndQ).
  rw::math::Transform3D X_W_tcp = rw::math::Transform3D::Identity();
  /// kRaw: configuration when placed; kPoseAndQ: the configuration q.
  rw::math::Q qOpen;
  /// kRaw: configuration the fingers close towards.
  rw::math::Q qClosed;
  /// kRaw: joint torque limits (empty: the hand's default rule).
  rw::math::Q tauMax;
  /// kPreshape: the pre-shape's name as the hand's grasp description defines it.
  std::string preshape;
  /// kContacts: 2 or 3 contacts, in any order.
  std::vector<DesiredContact> contacts;
  /// kContacts: desired direction of travel of the hand towards the object (its approach
  /// axis), world frame; need not be unit.
  rw::math::Vector3D approach = -rw::math::Vector3D::UnitZ();
  /// kJaw: pose of the jaw frame in the world: origin at the centre between the two finger
  /// pads, z the approach (direction of travel towards the object), x the closing axis (from
  /// one jaw towards the other), y = z x x (docs/grasp-format.md, "Parallel-jaw grasps").
  rw::math::Transform3D X_W_jaw = rw::math::Transform3D::Identity();
  /// kJaw: the opening between the pads the grasp needs, m (at most the hand's stroke).
  double width = 0.0;
  /// The method's score of the grasp, when it gave one (imported grasps keep it).
  std::optional<double> score;
  /// Where the request was read from (for messages), and its line (0 if unknown).
  std::string sourceFile;
  /// See sourceFile.
  int sourceLine = 0;
};

/// Name used in files: "raw", "preshape", "pose_q", "contacts", "jaw".
const char* kindName(GraspKind kind);

/// A two-contact grasp as a pre-shape grasp for any two-finger hand: the TCP midway between the
/// contacts, its z axis along the approach (the direction of travel), its x axis along the line
/// from the first contact to the second made perpendicular to z (the closing direction of the
/// PG70, the 2F-85 and the SDH's two-finger pre-shapes, scenes/hands/README.md), y = z x x; the
/// pre-shape `preshape`. Scene, method and id are kept. nullopt unless `contacts` is a kContacts
/// grasp with exactly two contacts, a non-zero approach and contacts not along the approach.
std::optional<GraspRequest> preshapeFromContacts(const GraspRequest& contacts,
                                                 const std::string& preshape);

}  // namespace visgrab::grasp
