#pragma once

#include <optional>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/kinematics/state.hpp"
#include "rw/models/setups.hpp"
#include "rw/models/workcell.hpp"
#include "rw/proximity/frame_models.hpp"
#include "rw/proximity/proximity_filter.hpp"

namespace rw::proximity {

/// The distance between the geometries of two frames.
struct FrameDistance {
  /// The frames.
  FramePair frames;
  /// Distance in metres; 0 when they overlap.
  double distance = 0.0;
  /// Closest point on frames.first's geometry, world coordinates.
  rw::math::Vector3D pointA = rw::math::Vector3D::Zero();
  /// Closest point on frames.second's geometry, world coordinates.
  rw::math::Vector3D pointB = rw::math::Vector3D::Zero();
};

/// Distances between the frame pairs of a ProximityFilter whose frames both carry collision
/// geometry. Built once; all queries are const and may run concurrently from many threads.
class DistanceCalculator {
 public:
  /// A calculator for `workcell` under its own proximity setup. The workcell must outlive it.
  /// @throws std::invalid_argument for a bad REGEX pattern or a mesh without triangles.
  explicit DistanceCalculator(const rw::models::WorkCell& workcell);
  /// A calculator for `workcell` under `setup`. The workcell must outlive it.
  /// @throws std::invalid_argument for a bad REGEX pattern or a mesh without triangles.
  DistanceCalculator(const rw::models::WorkCell& workcell, const rw::models::ProximitySetup& setup);

  /// One result per checked pair, in pair order. Precondition: a state of this workcell.
  std::vector<FrameDistance> distances(const rw::kinematics::State& state) const;
  /// One result per checked pair, in pair order, for the world poses `fk`.
  std::vector<FrameDistance> distances(const rw::kinematics::FKTable& fk) const;
  /// The smallest distance over the checked pairs (the first such pair on ties); nullopt when
  /// no pair is checked.
  std::optional<FrameDistance> minimum(const rw::kinematics::State& state) const;
  /// The smallest distance for the world poses `fk`.
  std::optional<FrameDistance> minimum(const rw::kinematics::FKTable& fk) const;

  /// The filter the calculator was built with.
  const ProximityFilter& filter() const { return filter_; }
  /// The pairs actually measured: the filter's pairs whose frames both have geometry.
  const std::vector<FramePair>& checkedPairs() const { return pairs_; }

 private:
  const rw::kinematics::FrameTree* tree_;
  ProximityFilter filter_;
  FrameModels models_;
  std::vector<FramePair> pairs_;
};

}  // namespace rw::proximity
