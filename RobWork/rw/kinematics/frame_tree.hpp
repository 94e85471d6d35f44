#pragma once

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "rw/kinematics/frame.hpp"
#include "rw/kinematics/state.hpp"

namespace rw::kinematics {

/// The frames of a workcell in topological order; frame 0 is "WORLD".
/// Built by adding frames parent-first, then used const.
class FrameTree {
 public:
  /// A tree holding only WORLD.
  FrameTree();

  /// Name of the root frame.
  static constexpr std::string_view kWorldName = "WORLD";
  /// Id of the root frame.
  static constexpr FrameId kWorld{0};

  /// Adds a frame and returns its id.
  /// @throws std::invalid_argument if the name is taken or empty, the parent is unknown, a
  /// dependency names a non-joint or dependent owner, or a dependent joint is not
  /// revolute/prismatic.
  FrameId add(FrameSpec spec);

  /// All frames, parents before children.
  const std::vector<Frame>& frames() const { return frames_; }
  /// Number of frames.
  std::size_t size() const { return frames_.size(); }
  /// The frame with this id. Precondition: id is valid for this tree.
  const Frame& frame(FrameId id) const { return frames_[static_cast<std::size_t>(id.index)]; }
  /// Looks a frame up by full name; invalid id if absent.
  FrameId find(std::string_view name) const;
  /// Children of a frame in their static parent relation, in id order.
  const std::vector<FrameId>& children(FrameId id) const {
    return children_[static_cast<std::size_t>(id.index)];
  }
  /// Number of values a State of this tree holds.
  int stateSize() const { return stateSize_; }
  /// A state with all joints at 0, movable frames at their initial transform, DAFs at their parent.
  State makeState() const;

 private:
  std::vector<Frame> frames_;
  std::vector<std::vector<FrameId>> children_;
  std::unordered_map<std::string, FrameId> byName_;
  int stateSize_ = 0;
};

/// World poses of all frames for one State, computed once (handles re-attached DAFs).
class FKTable {
 public:
  /// Computes X_W_f for every frame f.
  FKTable(const FrameTree& tree, const State& state);
  /// X_W_f.
  const rw::math::Transform3D& worldTransform(FrameId id) const {
    return world_[static_cast<std::size_t>(id.index)];
  }

 private:
  std::vector<rw::math::Transform3D> world_;
};

/// X_W_f of one frame in `state` (walks up to WORLD).
rw::math::Transform3D worldTransform(const FrameTree& tree, const State& state, FrameId frame);

/// X_from_to: pose of frame `to` in frame `from`.
rw::math::Transform3D relativeTransform(const FrameTree& tree, const State& state, FrameId from,
                                        FrameId to);

}  // namespace rw::kinematics
