#include "rw/models/device.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "rw/models/joint_values.hpp"

namespace rw::models {

using rw::kinematics::Frame;
using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;
using rw::kinematics::State;
using rw::math::Q;

namespace {

// Frames from base (exclusive) down to end (inclusive), in order from the base.
std::vector<FrameId> pathFromBase(const FrameTree& tree, FrameId base, FrameId end,
                                  const std::string& deviceName) {
  std::vector<FrameId> path;
  FrameId f = end;
  while (f != base) {
    if (!f.valid() || f == FrameTree::kWorld) {
      throw std::invalid_argument("device \"" + deviceName + "\": end frame \"" +
                                  tree.frame(end).name() + "\" is not below its base \"" +
                                  tree.frame(base).name() + "\"");
    }
    path.push_back(f);
    f = tree.frame(f).parent();
  }
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

Device::Device(Spec spec, const FrameTree& tree) : spec_(std::move(spec)), tree_(&tree) {
  if (!spec_.base.valid()) throw std::invalid_argument("device \"" + spec_.name + "\" has no base");
  if (spec_.kind == Kind::kParallel) {
    throw std::invalid_argument("device \"" + spec_.name +
                                "\": a parallel device needs its ParallelStructure");
  }
  for (const FrameId end : spec_.ends) {
    for (const FrameId f : pathFromBase(tree, spec_.base, end, spec_.name)) {
      const Frame& frame = tree.frame(f);
      if (!frame.isJoint() || std::find(joints_.begin(), joints_.end(), f) != joints_.end()) {
        continue;
      }
      joints_.push_back(f);
      if (frame.isActiveJoint()) active_.push_back(f);
    }
  }
  collectFrames();
}

Device::Device(Spec spec, const FrameTree& tree, ParallelStructure structure)
    : spec_(std::move(spec)), tree_(&tree) {
  if (spec_.kind != Kind::kParallel) {
    throw std::invalid_argument("device \"" + spec_.name +
                                "\": a parallel structure needs Kind::kParallel");
  }
  if (!spec_.base.valid()) throw std::invalid_argument("device \"" + spec_.name + "\" has no base");
  parallel_.emplace(tree, std::move(structure), spec_.name);
  joints_ = parallel_->allJoints();
  for (const FrameId f : joints_) {
    if (tree.frame(f).isActiveJoint()) active_.push_back(f);
  }
  collectFrames();
}

// The device's frames: the base and everything below it that lives in the device's scope.
void Device::collectFrames() {
  const FrameTree& tree = *tree_;
  const std::string prefix = spec_.name + ".";
  std::vector<FrameId> stack{spec_.base};
  while (!stack.empty()) {
    const FrameId f = stack.back();
    stack.pop_back();
    frames_.push_back(f);
    for (const FrameId c : tree.children(f)) {
      if (tree.frame(c).name().rfind(prefix, 0) == 0) stack.push_back(c);
    }
  }
  std::sort(frames_.begin(), frames_.end());
}

Q Device::getQ(const State& state) const { return jointValues(*tree_, active_, state); }

void Device::setActive(const Q& q, State& state) const {
  if (q.size() != dof()) {
    throw std::invalid_argument("device \"" + spec_.name + "\" has " + std::to_string(dof()) +
                                " DOF, got a configuration of " + std::to_string(q.size()));
  }
  setJointValues(*tree_, active_, q, state);
}

void Device::setQ(const Q& q, State& state) const {
  if (!parallel_) {
    setActive(q, state);
    return;
  }
  State closed = state;
  setActive(q, closed);  // checks q's size
  // Continuation: the active joints move from their values in `state` to q in steps of at most
  // ClosureSolver::kMaxActiveStep, the loops closed after each (from the previous closure), so
  // the passive joints follow q's path on one assembly mode. Where a step cannot be closed the
  // path is left, and q itself is closed from the last closure reached; if that fails too, q is
  // closed from `state` directly (which throws the error if it cannot be closed at all).
  const Q from = getQ(state);
  const Q delta = q - from;
  const double longest = delta.size() > 0 ? delta.cwiseAbs().maxCoeff() : 0.0;
  if (std::isfinite(longest) && longest > ClosureSolver::kMaxActiveStep) {
    State path = state;
    const int steps = static_cast<int>(std::ceil(longest / ClosureSolver::kMaxActiveStep));
    for (int k = 1; k < steps; ++k) {
      State next = path;
      setActive(from + delta * (static_cast<double>(k) / steps), next);
      if (!parallel_->tryClose(next)) break;
      path = std::move(next);
    }
    setActive(q, path);
    if (parallel_->tryClose(path)) {
      state = std::move(path);
      return;
    }
  }
  parallel_->close(closed);
  state = std::move(closed);
}

Q Device::lowerLimits() const {
  return jointLimits(*tree_, active_, [](const auto& l) { return l.lower; });
}
Q Device::upperLimits() const {
  return jointLimits(*tree_, active_, [](const auto& l) { return l.upper; });
}
Q Device::velocityLimits() const {
  return jointLimits(*tree_, active_, [](const auto& l) { return l.velocity; });
}
Q Device::accelerationLimits() const {
  return jointLimits(*tree_, active_, [](const auto& l) { return l.acceleration; });
}

bool Device::contains(FrameId frame) const {
  return std::binary_search(frames_.begin(), frames_.end(), frame);
}

}  // namespace rw::models
