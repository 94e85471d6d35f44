#include "rw/proximity/distance_calculator.hpp"

#include <algorithm>
#include <limits>

namespace rw::proximity {

using rw::kinematics::FKTable;
using rw::kinematics::State;

DistanceCalculator::DistanceCalculator(const rw::models::WorkCell& workcell)
    : DistanceCalculator(workcell, workcell.proximitySetup()) {}

DistanceCalculator::DistanceCalculator(const rw::models::WorkCell& workcell,
                                       const rw::models::ProximitySetup& setup)
    : tree_(&workcell.frames()),
      filter_(workcell, setup),
      models_(workcell),
      pairs_(pairsWithGeometry(filter_, models_)) {}

std::vector<FrameDistance> DistanceCalculator::distances(const State& state) const {
  return distances(FKTable(*tree_, state));
}

std::vector<FrameDistance> DistanceCalculator::distances(const FKTable& fk) const {
  std::vector<FrameDistance> result;
  result.reserve(pairs_.size());
  for (const FramePair& p : pairs_) {
    const DistanceResult d = models_.distance(p.first, fk.worldTransform(p.first), p.second,
                                              fk.worldTransform(p.second));
    result.push_back(FrameDistance{p, d.distance, d.pointA, d.pointB});
  }
  return result;
}

std::optional<FrameDistance> DistanceCalculator::minimum(const State& state) const {
  return minimum(FKTable(*tree_, state));
}

std::optional<FrameDistance> DistanceCalculator::minimum(const FKTable& fk) const {
  std::optional<FrameDistance> best;
  double bound = std::numeric_limits<double>::infinity();
  for (const FramePair& p : pairs_) {
    const DistanceResult d = models_.distance(p.first, fk.worldTransform(p.first), p.second,
                                              fk.worldTransform(p.second), bound);
    if (!best || d.distance < bound) {
      best = FrameDistance{p, d.distance, d.pointA, d.pointB};
      bound = std::min(bound, d.distance);
    }
  }
  return best;
}

}  // namespace rw::proximity
