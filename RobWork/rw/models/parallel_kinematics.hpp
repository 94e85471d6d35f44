#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/types.hpp"

namespace rw::models {

/// One leg of a junction: the frames from `start` down to `end` (each the parent of the next).
struct ParallelLeg {
  /// The SerialChain names the leg was written as (`<Chains>LeftPassive Distance</Chains>`).
  std::vector<std::string> chains;
  /// First frame; every leg of a junction starts here.
  rw::kinematics::FrameId start;
  /// Last frame; a closed junction holds the ends of all its legs at one pose.
  rw::kinematics::FrameId end;
};

/// A closed loop of a parallel device: legs from one start frame whose end frames must meet in
/// position and orientation. A simulator asks legs[i].end for the frames that meet.
struct Junction {
  /// Two or more legs.
  std::vector<ParallelLeg> legs;
};

/// The structure of a parallel device, given to Device beside its Spec.
struct ParallelStructure {
  /// Every frame of the device in document order (its joints, in this order, are all joints).
  std::vector<rw::kinematics::FrameId> frames;
  /// The junctions, in document order.
  std::vector<Junction> junctions;
};

/// How far a junction is from closed, measured from leg 0's end to every other leg's end.
struct JunctionResidual {
  /// Largest distance between leg ends (m).
  double position = 0.0;
  /// Largest angle between leg-end orientations (rad).
  double angle = 0.0;
};

/// The passive joints could not close a junction; the state is left unchanged.
class ClosureError : public std::runtime_error {
 public:
  /// An error about junction `junction` (index) with its residual at the best pose found.
  ClosureError(const std::string& what, std::size_t junction, JunctionResidual residual)
      : std::runtime_error(what), junction_(junction), residual_(residual) {}
  /// Index of the junction that stays open (the worst one).
  std::size_t junction() const { return junction_; }
  /// Its residual at the best pose found.
  JunctionResidual residual() const { return residual_; }

 private:
  std::size_t junction_;
  JunctionResidual residual_;
};

/// Closure solver: Gauss-Newton on the junction residuals (position in m, orientation as a
/// rotation vector in rad, leg i against leg 0 in the junction's start frame), steps by the
/// minimum-norm least-squares solution (complete orthogonal decomposition, so redundant
/// constraints of planar loops do no harm), halved until the residual norm decreases.
struct ClosureSolver {
  /// Converged when the residual norm is at most this (m and rad).
  static constexpr double kTolerance = 1e-12;
  /// When the iteration stops short of kTolerance (no step reduces the residual, or
  /// kMaxIterations is reached), a norm up to this is accepted as closed; above it, an error.
  static constexpr double kStallTolerance = 1e-9;
  /// Largest number of Gauss-Newton iterations.
  static constexpr int kMaxIterations = 100;
  /// Largest number of step halvings in one iteration.
  static constexpr int kMaxHalvings = 40;
  /// Device::setQ moves the active joints towards their targets in steps of at most this
  /// (rad or m), closing the loops after each, so that a large move follows its closure
  /// instead of jumping into another assembly mode (a parallelogram's crossed one).
  static constexpr double kMaxActiveStep = 0.1;
};

/// Joint bookkeeping and closed-loop kinematics of a parallel device (RobWork's ParallelDevice
/// with junctions): which joints are actuated, passive or dependent, the full configuration,
/// and the solver that moves the passive joints until every junction closes.
class ParallelKinematics {
 public:
  /// Builds the joint lists from `structure` over `tree`. `name` names the device in messages.
  /// @throws std::invalid_argument if a junction has fewer than two legs, a leg's end is not
  /// below its start, the legs of a junction do not start at one frame or two end at one frame,
  /// or a passive joint lies on no leg.
  ParallelKinematics(const rw::kinematics::FrameTree& tree, ParallelStructure structure,
                     std::string name);

  /// The junctions.
  const std::vector<Junction>& junctions() const { return structure_.junctions; }
  /// Every frame of the device in document order.
  const std::vector<rw::kinematics::FrameId>& frames() const { return structure_.frames; }
  /// Every joint in document order (RobWork's getAllJoints()).
  const std::vector<rw::kinematics::FrameId>& allJoints() const { return all_; }
  /// Joints that move with q (RobWork's getActiveJoints()): active independent joints and the
  /// active dependent joints whose owner is active.
  const std::vector<rw::kinematics::FrameId>& actuatedJoints() const { return actuated_; }
  /// Independent passive joints: the unknowns of the closure solver, in document order.
  const std::vector<rw::kinematics::FrameId>& passiveJoints() const { return passive_; }
  /// Dependent joints (no DOF of their own).
  const std::vector<rw::kinematics::FrameId>& dependentJoints() const { return dependent_; }
  /// Independent joints in document order: the layout of the full configuration.
  const std::vector<rw::kinematics::FrameId>& fullJoints() const { return full_; }
  /// Active plus passive degrees of freedom (RobWork's getFullDOF()).
  int fullDof() const { return static_cast<int>(full_.size()); }

  /// The full configuration (one value per fullJoints() entry).
  rw::math::Q getFullQ(const rw::kinematics::State& state) const;
  /// Sets every independent joint; solves nothing. @throws std::invalid_argument on a size
  /// other than fullDof().
  void setFullQ(const rw::math::Q& q, rw::kinematics::State& state) const;
  /// Lower position limits in full-configuration order.
  rw::math::Q fullLowerLimits() const;
  /// Upper position limits in full-configuration order.
  rw::math::Q fullUpperLimits() const;

  /// How far junction `junction` is from closed in `state`. Precondition: index in range.
  JunctionResidual residual(std::size_t junction, const rw::kinematics::State& state) const;
  /// Moves the passive joints, starting from their values in `state`, until every junction
  /// closes (ClosureSolver). Returns the number of iterations used. @throws ClosureError
  /// naming the worst junction and its residual if they cannot be closed; `state` is then
  /// unchanged.
  int close(rw::kinematics::State& state) const;
  /// As close(), but returns false instead of throwing (and leaves `state` unchanged then).
  bool tryClose(rw::kinematics::State& state) const;

 private:
  struct Column {
    rw::kinematics::FrameId joint;
    int position = 0;  // index in LegPath::frames
    int unknown = -1;
    double gain = 1.0;
  };
  struct LegPath {
    std::vector<rw::kinematics::FrameId> frames;  // below start, down to end
    std::vector<Column> columns;                  // joints on the path that move with x
  };
  struct Evaluation;

  // The iteration of close(): `state` ends at the best configuration found; returns the
  // number of iterations and sets `norm` to its residual norm.
  int iterate(rw::kinematics::State& state, double& norm) const;
  void classifyJoints();
  void buildPaths();
  LegPath makePath(const ParallelLeg& leg, const std::string& what,
                   const std::vector<int>& unknownOf) const;
  void evaluate(const rw::kinematics::State& state, bool withJacobian, Evaluation& out) const;
  void setUnknowns(const rw::math::Q& x, rw::kinematics::State& state) const;
  [[noreturn]] void fail(const rw::kinematics::State& best, int iterations) const;

  const rw::kinematics::FrameTree* tree_;
  ParallelStructure structure_;
  std::string name_;
  std::vector<rw::kinematics::FrameId> all_;
  std::vector<rw::kinematics::FrameId> actuated_;
  std::vector<rw::kinematics::FrameId> passive_;
  std::vector<rw::kinematics::FrameId> dependent_;
  std::vector<rw::kinematics::FrameId> full_;
  std::vector<std::vector<LegPath>> paths_;  // per junction, per leg
};

}  // namespace rw::models
