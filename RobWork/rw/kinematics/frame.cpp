#include "rw/kinematics/frame.hpp"

#include <utility>

#include "rw/kinematics/state.hpp"

namespace rw::kinematics {

using rw::math::Transform3D;

Frame::Frame(FrameSpec spec, FrameId id, int stateOffset, int stateSize, int ownerStateOffset)
    : spec_(std::move(spec)),
      id_(id),
      stateOffset_(stateOffset),
      stateSize_(stateSize),
      ownerStateOffset_(ownerStateOffset) {}

double Frame::jointValue(const State& state) const {
  const auto& v = state.values();
  if (spec_.dependency) {
    return spec_.dependency->gain * v[static_cast<std::size_t>(ownerStateOffset_)] +
           spec_.dependency->offset;
  }
  return v[static_cast<std::size_t>(stateOffset_)];
}

void Frame::setJointValue(State& state, double q) const {
  state.values()[static_cast<std::size_t>(stateOffset_)] = q;
}

Transform3D Frame::movableTransform(const State& state) const {
  const double* v = state.values().data() + stateOffset_;
  Transform3D X = Transform3D::Identity();
  X.translation() = rw::math::Vector3D(v[0], v[1], v[2]);
  X.linear() = Eigen::Quaterniond(v[3], v[4], v[5], v[6]).normalized().toRotationMatrix();
  return X;
}

void Frame::setMovableTransform(State& state, const Transform3D& X_parent_frame) const {
  double* v = state.values().data() + stateOffset_;
  const Eigen::Quaterniond quat(X_parent_frame.linear());
  const auto& p = X_parent_frame.translation();
  v[0] = p.x();
  v[1] = p.y();
  v[2] = p.z();
  v[3] = quat.w();
  v[4] = quat.x();
  v[5] = quat.y();
  v[6] = quat.z();
}

Transform3D Frame::localTransform(const State& state) const {
  switch (spec_.type) {
    case FrameType::kFixed:
      return spec_.transform;
    case FrameType::kMovable:
      return movableTransform(state);
    case FrameType::kRevolute: {
      Transform3D X = spec_.transform;
      X.rotate(Eigen::AngleAxisd(jointValue(state), rw::math::Vector3D::UnitZ()));
      return X;
    }
    case FrameType::kPrismatic: {
      Transform3D X = spec_.transform;
      X.translate(rw::math::Vector3D(0, 0, jointValue(state)));
      return X;
    }
  }
  return spec_.transform;
}

}  // namespace rw::kinematics
