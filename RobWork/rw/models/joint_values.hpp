#pragma once

#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/types.hpp"

namespace rw::models {

/// The values of `joints` in `state`, in order. Precondition: every id is a joint of `tree`.
rw::math::Q jointValues(const rw::kinematics::FrameTree& tree,
                        const std::vector<rw::kinematics::FrameId>& joints,
                        const rw::kinematics::State& state);

/// Sets independent `joints` to `q`, in order. Precondition: q.size() == joints.size().
void setJointValues(const rw::kinematics::FrameTree& tree,
                    const std::vector<rw::kinematics::FrameId>& joints, const rw::math::Q& q,
                    rw::kinematics::State& state);

/// One limit of each joint, picked from its JointLimits by `get`, in order.
template <typename Get>
rw::math::Q jointLimits(const rw::kinematics::FrameTree& tree,
                        const std::vector<rw::kinematics::FrameId>& joints, Get get) {
  rw::math::Q q(static_cast<Eigen::Index>(joints.size()));
  for (std::size_t i = 0; i < joints.size(); ++i) {
    q[static_cast<Eigen::Index>(i)] = get(tree.frame(joints[i]).limits());
  }
  return q;
}

}  // namespace rw::models
