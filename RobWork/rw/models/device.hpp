#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/types.hpp"
#include "rw/models/parallel_kinematics.hpp"

namespace rw::models {

/// A serial, tree-shaped or parallel device: a named set of joints with RobWork's joint order.
class Device {
 public:
  /// Shape of the device.
  enum class Kind { kSerial, kTree, kParallel };

  /// Everything needed to build a device over frames already in a FrameTree.
  struct Spec {
    /// Device name (also the scope prefix of its frames).
    std::string name;
    /// Serial or tree.
    Kind kind = Kind::kSerial;
    /// First frame of the device.
    rw::kinematics::FrameId base;
    /// End frames (Serial: the last frame; Tree: the EndEffector frames in document order;
    /// Parallel: the end of the first leg of the first junction).
    std::vector<rw::kinematics::FrameId> ends;
    /// Named configurations (`<Q name=...>`), raw values.
    std::map<std::string, rw::math::Q> configurations;
    /// Device-level properties.
    rw::kinematics::PropertyMap properties;
  };

  /// Builds the joint lists from the tree: for each end in order, the joints on the path
  /// base -> end not yet listed. @throws std::invalid_argument if an end is not below the base
  /// or spec.kind is kParallel.
  Device(Spec spec, const rw::kinematics::FrameTree& tree);
  /// A parallel device (spec.kind == kParallel): all joints in the document order of
  /// `structure.frames`, q = the active independent ones. @throws std::invalid_argument as
  /// ParallelKinematics does, or if spec.kind is not kParallel.
  Device(Spec spec, const rw::kinematics::FrameTree& tree, ParallelStructure structure);

  /// Device name.
  const std::string& name() const { return spec_.name; }
  /// Serial or tree.
  Kind kind() const { return spec_.kind; }
  /// Base frame.
  rw::kinematics::FrameId base() const { return spec_.base; }
  /// End frames.
  const std::vector<rw::kinematics::FrameId>& ends() const { return spec_.ends; }
  /// All joints in RobWork's getJoints() order, dependent and passive ones included.
  const std::vector<rw::kinematics::FrameId>& joints() const { return joints_; }
  /// The joints that make up q, in order (active, independent).
  const std::vector<rw::kinematics::FrameId>& activeJoints() const { return active_; }
  /// Degrees of freedom (= activeJoints().size()).
  int dof() const { return static_cast<int>(active_.size()); }
  /// Current configuration.
  rw::math::Q getQ(const rw::kinematics::State& state) const;
  /// Sets the configuration; a parallel device then moves its passive joints until every
  /// junction closes, following the active joints from their values in `state` to q in steps
  /// of at most ClosureSolver::kMaxActiveStep (so the closure stays on one assembly mode). @throws
  /// std::invalid_argument if q.size() != dof(); ClosureError if a junction cannot be closed (the
  /// state is then unchanged).
  void setQ(const rw::math::Q& q, rw::kinematics::State& state) const;
  /// The closed-loop part of a parallel device; nullptr for serial and tree devices.
  const ParallelKinematics* parallel() const { return parallel_ ? &*parallel_ : nullptr; }
  /// Lower position limits of the active joints.
  rw::math::Q lowerLimits() const;
  /// Upper position limits of the active joints.
  rw::math::Q upperLimits() const;
  /// Velocity limits of the active joints.
  rw::math::Q velocityLimits() const;
  /// Acceleration limits of the active joints.
  rw::math::Q accelerationLimits() const;
  /// Named configurations.
  const std::map<std::string, rw::math::Q>& configurations() const { return spec_.configurations; }
  /// Device properties.
  const rw::kinematics::PropertyMap& properties() const { return spec_.properties; }
  /// True if `frame` is the base or lies below it up to (and including) the device's frames.
  bool contains(rw::kinematics::FrameId frame) const;
  /// All frames of the device (base first, id order).
  const std::vector<rw::kinematics::FrameId>& frames() const { return frames_; }

 private:
  Spec spec_;
  const rw::kinematics::FrameTree* tree_;
  std::vector<rw::kinematics::FrameId> joints_;
  std::vector<rw::kinematics::FrameId> active_;
  std::vector<rw::kinematics::FrameId> frames_;
  std::optional<ParallelKinematics> parallel_;

  void collectFrames();
  void setActive(const rw::math::Q& q, rw::kinematics::State& state) const;
};

}  // namespace rw::models
