#pragma once

#include <cstddef>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"

namespace rwsim::dynamics {

/// The closures of a rigid device over a parallel device (empty for serial and tree devices),
/// junction by junction, leg by leg (LoopClosure, dynamic_workcell.hpp). The device's bodies
/// must be in `dwc` (it may be added yet or not). DynamicWorkCell::addDevice stores the result
/// in RigidDevice::loopClosures; the simulator reads it from there.
/// @throws std::invalid_argument naming the junction and leg if a leg end hangs on no body of
/// the device, more than one joint without a link body lies between the two leg ends' bodies
/// (give all but one a <Link>), such a joint is dependent, or both leg ends sit on one body.
std::vector<LoopClosure> loopClosures(const DynamicWorkCell& dwc, const RigidDevice& device);

}  // namespace rwsim::dynamics
