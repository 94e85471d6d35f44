#pragma once

#include <vector>

#include "rw/kinematics/frame.hpp"

namespace rw::kinematics {

/// Everything that changes: joint values, movable-frame transforms and the parents of
/// dynamically attachable frames. A plain value; copy it freely, one per thread or trial.
class State {
 public:
  /// An empty state (no frames).
  State() = default;
  /// A state with `size` values (zero) and the given parents (one per frame).
  State(std::size_t size, std::vector<FrameId> parents)
      : values_(size, 0.0), parents_(std::move(parents)) {}

  /// The raw values, laid out by Frame::stateOffset().
  std::vector<double>& values() { return values_; }
  /// The raw values.
  const std::vector<double>& values() const { return values_; }
  /// Current parent of a frame (differs from Frame::parent() only for attached DAFs).
  FrameId parentOf(FrameId frame) const { return parents_[static_cast<std::size_t>(frame.index)]; }
  /// Number of frames the state was made for.
  std::size_t parentCount() const { return parents_.size(); }
  /// Re-attaches a frame. Precondition: the frame is a DAF and `parent` is not below it.
  void setParent(FrameId frame, FrameId parent) {
    parents_[static_cast<std::size_t>(frame.index)] = parent;
  }

 private:
  std::vector<double> values_;
  std::vector<FrameId> parents_;
};

}  // namespace rw::kinematics
