#pragma once

#include <compare>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "rw/kinematics/property_map.hpp"
#include "rw/math/types.hpp"

namespace rw::kinematics {

class State;

/// Index of a frame in its FrameTree; frames are stored in topological order (parent < child).
struct FrameId {
  /// Position in FrameTree::frames(); -1 means "no frame".
  std::int32_t index = -1;
  /// True when this names a frame.
  constexpr bool valid() const { return index >= 0; }
  /// Ids compare by index.
  friend constexpr auto operator<=>(FrameId, FrameId) = default;
};

/// How a frame's transform relative to its parent is obtained.
enum class FrameType {
  kFixed,      ///< constant transform
  kMovable,    ///< transform stored in the State (7 values: x y z qw qx qy qz)
  kRevolute,   ///< fixed transform * Rz(q)
  kPrismatic,  ///< fixed transform * Tz(q)
};

/// Limits of a joint in SI units (rad, rad/s, rad/s^2 or m, m/s, m/s^2); unlimited by default.
struct JointLimits {
  /// Lowest position.
  double lower = -std::numeric_limits<double>::infinity();
  /// Highest position.
  double upper = std::numeric_limits<double>::infinity();
  /// Largest speed.
  double velocity = std::numeric_limits<double>::infinity();
  /// Largest acceleration.
  double acceleration = std::numeric_limits<double>::infinity();
};

/// A dependent joint's coupling: q = gain * q_owner + offset.
struct JointDependency {
  /// The joint it follows (itself independent).
  FrameId owner;
  /// Gain.
  double gain = 1.0;
  /// Offset (rad or m).
  double offset = 0.0;
};

/// Everything needed to create a frame in a FrameTree.
struct FrameSpec {
  /// Full (scoped) name, unique in the tree.
  std::string name;
  /// Parent frame; must already be in the tree.
  FrameId parent;
  /// Kind of frame.
  FrameType type = FrameType::kFixed;
  /// X_parent_frame for Fixed, initial value for Movable, joint placement (q = 0) for joints.
  rw::math::Transform3D transform = rw::math::Transform3D::Identity();
  /// Joint limits (joints only).
  JointLimits limits;
  /// Set for dependent joints (Revolute or Prismatic only).
  std::optional<JointDependency> dependency;
  /// Passive joints are not part of a device's configuration.
  bool passive = false;
  /// Marks an end of a TreeDevice.
  bool endEffector = false;
  /// Dynamically attachable frame (its parent lives in the State).
  bool daf = false;
  /// Properties from the XML.
  PropertyMap properties;
};

/// A node of the kinematic tree. Immutable once in a FrameTree; values live in a State.
class Frame {
 public:
  /// Builds a frame; `id`, `stateOffset` and `stateSize` are assigned by the FrameTree.
  Frame(FrameSpec spec, FrameId id, int stateOffset, int stateSize, int ownerStateOffset);

  /// Full scoped name ("SchunkHand.f1.Joint2").
  const std::string& name() const { return spec_.name; }
  /// Own id.
  FrameId id() const { return id_; }
  /// Static parent (a DAF's current parent is in the State).
  FrameId parent() const { return spec_.parent; }
  /// Kind of frame.
  FrameType type() const { return spec_.type; }
  /// The constant part of the parent-to-frame transform (see FrameSpec::transform).
  const rw::math::Transform3D& fixedTransform() const { return spec_.transform; }
  /// True for revolute and prismatic joints (dependent ones included).
  bool isJoint() const {
    return spec_.type == FrameType::kRevolute || spec_.type == FrameType::kPrismatic;
  }
  /// True for joints coupled to another joint.
  bool isDependent() const { return spec_.dependency.has_value(); }
  /// The coupling of a dependent joint.
  const std::optional<JointDependency>& dependency() const { return spec_.dependency; }
  /// True for joints that are independent and not passive (they count as device DOF).
  bool isActiveJoint() const { return isJoint() && !isDependent() && !spec_.passive; }
  /// True for passive joints.
  bool isPassive() const { return spec_.passive; }
  /// Joint limits.
  const JointLimits& limits() const { return spec_.limits; }
  /// Marks an end of a TreeDevice.
  bool isEndEffector() const { return spec_.endEffector; }
  /// Dynamically attachable.
  bool isDaf() const { return spec_.daf; }
  /// Properties.
  const PropertyMap& properties() const { return spec_.properties; }
  /// First index of this frame's values in State::values(); -1 if it has none.
  int stateOffset() const { return stateOffset_; }
  /// Number of values in the State (1 joint, 7 movable, 0 otherwise).
  int stateSize() const { return stateSize_; }

  /// Joint value q (dependent joints: gain * q_owner + offset). Precondition: isJoint().
  double jointValue(const State& state) const;
  /// Sets an independent joint's value. Precondition: isJoint() && !isDependent().
  void setJointValue(State& state, double q) const;
  /// Transform of a Movable frame relative to its parent. Precondition: type() == kMovable.
  rw::math::Transform3D movableTransform(const State& state) const;
  /// Sets a Movable frame's transform relative to its parent. Precondition: type() == kMovable.
  void setMovableTransform(State& state, const rw::math::Transform3D& X_parent_frame) const;
  /// X_parent_frame in `state`.
  rw::math::Transform3D localTransform(const State& state) const;

 private:
  FrameSpec spec_;
  FrameId id_;
  int stateOffset_;
  int stateSize_;
  int ownerStateOffset_;
};

}  // namespace rw::kinematics
