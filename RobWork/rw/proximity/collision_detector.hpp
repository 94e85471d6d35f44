#pragma once

#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/kinematics/state.hpp"
#include "rw/models/setups.hpp"
#include "rw/models/workcell.hpp"
#include "rw/proximity/frame_models.hpp"
#include "rw/proximity/proximity_filter.hpp"

namespace rw::proximity {

/// Answers "does anything collide in this state?" for a workcell: checks the frame pairs of a
/// ProximityFilter whose frames both carry collision geometry. Built once; all queries are const
/// and may run concurrently from many threads.
class CollisionDetector {
 public:
  /// A detector for `workcell` under its own proximity setup. The workcell must outlive it.
  /// @throws std::invalid_argument for a bad REGEX pattern or a mesh without triangles.
  explicit CollisionDetector(const rw::models::WorkCell& workcell);
  /// A detector for `workcell` under `setup`. The workcell must outlive it.
  /// @throws std::invalid_argument for a bad REGEX pattern or a mesh without triangles.
  CollisionDetector(const rw::models::WorkCell& workcell, const rw::models::ProximitySetup& setup);

  /// True when some checked pair collides in `state`. Precondition: a state of this workcell.
  bool inCollision(const rw::kinematics::State& state) const;
  /// True when some checked pair collides with the world poses `fk`.
  bool inCollision(const rw::kinematics::FKTable& fk) const;
  /// All checked pairs that collide in `state`, in pair order.
  std::vector<FramePair> collidingPairs(const rw::kinematics::State& state) const;
  /// All checked pairs that collide with the world poses `fk`, in pair order.
  std::vector<FramePair> collidingPairs(const rw::kinematics::FKTable& fk) const;
  /// True when the geometries of the two frames collide (whether or not the filter checks them).
  bool inCollision(const FramePair& pair, const rw::kinematics::FKTable& fk) const;

  /// The filter the detector was built with.
  const ProximityFilter& filter() const { return filter_; }
  /// The pairs actually checked: the filter's pairs whose frames both have geometry.
  const std::vector<FramePair>& checkedPairs() const { return pairs_; }
  /// The models of the frames' geometry.
  const FrameModels& models() const { return models_; }

 private:
  const rw::kinematics::FrameTree* tree_;
  ProximityFilter filter_;
  FrameModels models_;
  std::vector<FramePair> pairs_;
};

}  // namespace rw::proximity
