#pragma once

#include <cstddef>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"

namespace rwsim::dynamics {

/// How the simulator closes one leg of a parallel device's junction against the junction's
/// first leg. The links of every leg are simulated as a tree (one body per link, a hinge or
/// slider per joint); each junction then adds, per leg after the first, one joint between the
/// bodies that carry the leg ends (a project extension: RobWorkSim has no dwc syntax for
/// parallel devices).
struct LoopClosure {
  /// Index of the junction in ParallelKinematics::junctions().
  std::size_t junction = 0;
  /// Index of the leg closed against leg 0.
  std::size_t leg = 0;
  /// The joint that closes the loop: a joint on the way from a leg end up to the body carrying
  /// it that has no link body of its own (RobWork's models end a leg with such a joint, e.g.
  /// the Robotiq's LinkConnection). It becomes a hinge or slider between `parent` and `child`.
  /// None when both leg ends sit rigidly on their bodies: the two bodies are then welded.
  rw::kinematics::FrameId joint;
  /// The body above `joint` (for a weld: the body carrying leg 0's end).
  BodyId parent;
  /// The body carrying the other leg's end, which moves with `joint` (for a weld: the body
  /// carrying this leg's end).
  BodyId child;
};

/// The closures of a rigid device over a parallel device (empty for serial and tree devices),
/// junction by junction, leg by leg. The device's bodies must be in `dwc` (it may be added yet
/// or not).
/// @throws std::invalid_argument naming the junction and leg if a leg end hangs on no body of
/// the device, more than one joint without a link body lies between the two leg ends' bodies
/// (give all but one a <Link>), such a joint is dependent, or both leg ends sit on one body.
std::vector<LoopClosure> loopClosures(const DynamicWorkCell& dwc, const RigidDevice& device);

}  // namespace rwsim::dynamics
