// Frame-level collision checks: the chain scene, planes, DAFs and concurrent queries.
#include "rw/proximity/collision_detector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "chain_scene.hpp"
#include "rw/proximity/distance_calculator.hpp"

namespace rw::proximity {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

using rw::geometry::Geometry;
using rw::kinematics::State;
using test::pose;

TEST(CollisionDetector, ChainFoldedBackOntoItself) {
  const test::ChainScene s = test::makeChainScene();
  const CollisionDetector detector(*s.wc);
  EXPECT_EQ(detector.checkedPairs().size(), 3U);
  State state = s.wc->defaultState();
  EXPECT_FALSE(detector.inCollision(state));
  EXPECT_TRUE(detector.collidingPairs(state).empty());
  // F2 turned 180 degrees: F3 comes back onto F1 at the origin, F4 lands at (-1, 0, 0).
  s.wc->frames().frame(s.f[1]).setMovableTransform(state, pose({1, 0, 0}, 180, 0, 0));
  EXPECT_TRUE(detector.inCollision(state));
  const std::vector<FramePair> pairs = detector.collidingPairs(state);
  ASSERT_EQ(pairs.size(), 1U);
  EXPECT_EQ(pairs[0], makeFramePair(s.f[0], s.f[2]));
  EXPECT_EQ(s.wc->frames().frame(pairs[0].first).name(), "F1");
  EXPECT_EQ(s.wc->frames().frame(pairs[0].second).name(), "F3");
}

TEST(CollisionDetector, ExcludedPairsAreNotReported) {
  const test::ChainScene s = test::makeChainScene();
  const CollisionDetector detector(*s.wc);
  State state = s.wc->defaultState();
  // F2 pulled onto F1: the pair is excluded, so nothing collides.
  s.wc->frames().frame(s.f[1]).setMovableTransform(state, pose({0.1, 0, 0}));
  EXPECT_FALSE(detector.inCollision(state));
  const rw::kinematics::FKTable fk(s.wc->frames(), state);
  EXPECT_TRUE(detector.inCollision(makeFramePair(s.f[0], s.f[1]), fk));
}

TEST(CollisionDetector, BoxOnATableAndAReattachedDaf) {
  rw::models::WorkCell wc("Table");
  const auto world = rw::kinematics::FrameTree::kWorld;
  const auto table = test::addFrame(wc, "Table", world, test::FrameType::kFixed, pose({0, 0, 0.7}));
  const auto box =
      test::addFrame(wc, "Box", table, test::FrameType::kMovable, pose({0, 0, 0.05}), true);
  const auto hand = test::addFrame(wc, "Hand", world, test::FrameType::kMovable, pose({0, 0, 1.5}));
  test::addGeometry(wc, table, Geometry::plane());
  test::addGeometry(wc, box, Geometry::box(0.1, 0.1, 0.1));
  test::addGeometry(wc, hand, Geometry::sphere(0.05), pose({0, 0, -0.1}));
  const CollisionDetector detector(wc);
  State state = wc.defaultState();
  EXPECT_EQ(detector.collidingPairs(state), std::vector<FramePair>{makeFramePair(table, box)});
  // Lifted 1 mm: free. Then attached to the hand below its sphere (centre 1.4, radius 0.05).
  wc.frames().frame(box).setMovableTransform(state, pose({0, 0, 0.051}));
  EXPECT_FALSE(detector.inCollision(state));
  state.setParent(box, hand);
  wc.frames().frame(box).setMovableTransform(state, pose({0, 0, -0.21}));
  EXPECT_FALSE(detector.inCollision(state));  // box top at 1.34, sphere bottom at 1.35
  wc.frames().frame(box).setMovableTransform(state, pose({0, 0, -0.19}));
  EXPECT_EQ(detector.collidingPairs(state), std::vector<FramePair>{makeFramePair(box, hand)});
}

// A busier scene for the concurrency test: the chain, two L-shaped meshes, a tube and a floor.
test::ChainScene busyScene() {
  test::ChainScene s = test::makeChainScene();
  rw::models::WorkCell& wc = *s.wc;
  const auto world = rw::kinematics::FrameTree::kWorld;
  const auto l1 = test::addFrame(wc, "L1", world, test::FrameType::kMovable, pose({0, 1, 0}));
  const auto l2 = test::addFrame(wc, "L2", s.f[2], test::FrameType::kFixed, pose({0, 0.5, 0}));
  const auto tube = test::addFrame(wc, "Tube", s.f[3], test::FrameType::kFixed);
  const auto floor = test::addFrame(wc, "Floor", world, test::FrameType::kFixed, pose({0, 0, -1}));
  test::addGeometry(wc, l1, test::lShape());
  test::addGeometry(wc, l2, test::lShape(), pose({0, 0, 0}, 0, 0, 90));
  test::addGeometry(wc, tube, Geometry::tube(0.3, 0.05, 0.5));
  test::addGeometry(wc, floor, Geometry::plane());
  return s;
}

std::vector<State> sampleStates(const test::ChainScene& s, int count) {
  std::vector<State> states;
  for (int i = 0; i < count; ++i) {
    State state = s.wc->defaultState();
    const double angle = 360.0 * i / count;
    s.wc->frames().frame(s.f[1]).setMovableTransform(state, pose({1, 0, 0}, angle, 0, angle / 3));
    s.wc->frames().frame(s.f[0]).setMovableTransform(state, pose({0.01 * i, 0, -0.5 + 0.02 * i}));
    states.push_back(std::move(state));
  }
  return states;
}

struct Snapshot {
  std::vector<std::vector<FramePair>> colliding;
  std::vector<std::vector<FrameDistance>> distances;
};

Snapshot evaluate(const CollisionDetector& detector, const DistanceCalculator& calc,
                  const std::vector<State>& states) {
  Snapshot snap;
  for (const State& state : states) {
    snap.colliding.push_back(detector.collidingPairs(state));
    snap.distances.push_back(calc.distances(state));
  }
  return snap;
}

TEST(CollisionDetector, FourThreadsGetIdenticalResults) {
  const test::ChainScene s = busyScene();
  const CollisionDetector detector(*s.wc);
  const DistanceCalculator calc(*s.wc);
  const std::vector<State> states = sampleStates(s, 8);
  const Snapshot reference = evaluate(detector, calc, states);
  std::size_t collisions = 0;
  for (const auto& c : reference.colliding) collisions += c.size();
  EXPECT_GT(collisions, 0U) << "the sample should contain collisions";

  std::vector<Snapshot> results(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < results.size(); ++t) {
    threads.emplace_back([&, t] { results[t] = evaluate(detector, calc, states); });
  }
  for (std::thread& thread : threads) thread.join();
  for (const Snapshot& r : results) {
    EXPECT_EQ(r.colliding, reference.colliding);
    ASSERT_EQ(r.distances.size(), reference.distances.size());
    for (std::size_t i = 0; i < r.distances.size(); ++i) {
      ASSERT_EQ(r.distances[i].size(), reference.distances[i].size());
      for (std::size_t k = 0; k < r.distances[i].size(); ++k) {
        EXPECT_EQ(r.distances[i][k].frames, reference.distances[i][k].frames);
        EXPECT_EQ(r.distances[i][k].distance, reference.distances[i][k].distance);
        EXPECT_EQ(r.distances[i][k].pointA, reference.distances[i][k].pointA);
        EXPECT_EQ(r.distances[i][k].pointB, reference.distances[i][k].pointB);
      }
    }
  }
}

TEST(CollisionDetector, CollisionAgreesWithDistance) {
  const test::ChainScene s = busyScene();
  const CollisionDetector detector(*s.wc);
  const DistanceCalculator calc(*s.wc);
  ASSERT_EQ(detector.checkedPairs(), calc.checkedPairs());
  for (const State& state : sampleStates(s, 12)) {
    const std::vector<FramePair> colliding = detector.collidingPairs(state);
    for (const FrameDistance& d : calc.distances(state)) {
      const bool collides =
          std::find(colliding.begin(), colliding.end(), d.frames) != colliding.end();
      EXPECT_EQ(collides, d.distance <= kContactTolerance)
          << "pair " << d.frames.first.index << "-" << d.frames.second.index << " distance "
          << d.distance;
    }
  }
}

}  // namespace
}  // namespace rw::proximity
