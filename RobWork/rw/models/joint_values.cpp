#include "rw/models/joint_values.hpp"

namespace rw::models {

rw::math::Q jointValues(const rw::kinematics::FrameTree& tree,
                        const std::vector<rw::kinematics::FrameId>& joints,
                        const rw::kinematics::State& state) {
  rw::math::Q q(static_cast<Eigen::Index>(joints.size()));
  for (std::size_t i = 0; i < joints.size(); ++i) {
    q[static_cast<Eigen::Index>(i)] = tree.frame(joints[i]).jointValue(state);
  }
  return q;
}

void setJointValues(const rw::kinematics::FrameTree& tree,
                    const std::vector<rw::kinematics::FrameId>& joints, const rw::math::Q& q,
                    rw::kinematics::State& state) {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    tree.frame(joints[i]).setJointValue(state, q[static_cast<Eigen::Index>(i)]);
  }
}

}  // namespace rw::models
