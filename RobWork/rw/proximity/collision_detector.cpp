#include "rw/proximity/collision_detector.hpp"

namespace rw::proximity {

using rw::kinematics::FKTable;
using rw::kinematics::State;

CollisionDetector::CollisionDetector(const rw::models::WorkCell& workcell)
    : CollisionDetector(workcell, workcell.proximitySetup()) {}

CollisionDetector::CollisionDetector(const rw::models::WorkCell& workcell,
                                     const rw::models::ProximitySetup& setup)
    : tree_(&workcell.frames()),
      filter_(workcell, setup),
      models_(workcell),
      pairs_(pairsWithGeometry(filter_, models_)) {}

bool CollisionDetector::inCollision(const State& state) const {
  return inCollision(FKTable(*tree_, state));
}

bool CollisionDetector::inCollision(const FKTable& fk) const {
  for (const FramePair& p : pairs_) {
    if (inCollision(p, fk)) return true;
  }
  return false;
}

std::vector<FramePair> CollisionDetector::collidingPairs(const State& state) const {
  return collidingPairs(FKTable(*tree_, state));
}

std::vector<FramePair> CollisionDetector::collidingPairs(const FKTable& fk) const {
  std::vector<FramePair> colliding;
  for (const FramePair& p : pairs_) {
    if (inCollision(p, fk)) colliding.push_back(p);
  }
  return colliding;
}

bool CollisionDetector::inCollision(const FramePair& pair, const FKTable& fk) const {
  return models_.collides(pair.first, fk.worldTransform(pair.first), pair.second,
                          fk.worldTransform(pair.second));
}

}  // namespace rw::proximity
