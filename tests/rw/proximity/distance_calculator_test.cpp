// Frame-level distances on RobWork's DistanceTest idea (reference §10), distances by hand.
#include "rw/proximity/distance_calculator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "chain_scene.hpp"
#include "support/test_support.hpp"

namespace rw::proximity {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

using test::pose;

constexpr double kDistanceTol = 1e-9;

TEST(DistanceCalculator, ChainOfFourHasThreePairs) {
  const test::ChainScene s = test::makeChainScene();
  const DistanceCalculator calc(*s.wc);
  const std::vector<FrameDistance> d = calc.distances(s.wc->defaultState());
  ASSERT_EQ(d.size(), 3U);
  EXPECT_EQ(d[0].frames, makeFramePair(s.f[0], s.f[2]));
  EXPECT_EQ(d[1].frames, makeFramePair(s.f[0], s.f[3]));
  EXPECT_EQ(d[2].frames, makeFramePair(s.f[1], s.f[3]));
  EXPECT_NEAR(d[0].distance, 2.0 - 0.2 - 0.1, kDistanceTol);  // sphere 0.2 at 0, sphere 0.1 at 2
  EXPECT_NEAR(d[1].distance, 3.0 - 0.2 - 0.1, kDistanceTol);  // sphere 0.2 at 0, box face at 2.9
  EXPECT_NEAR(d[2].distance, 2.0 - 0.2 - 0.1, kDistanceTol);  // box faces at 1.2 and 2.9
  EXPECT_VECTOR_NEAR(d[0].pointA, Vector3D(0.2, 0, 0), kDistanceTol);
  EXPECT_VECTOR_NEAR(d[0].pointB, Vector3D(1.9, 0, 0), kDistanceTol);
  EXPECT_NEAR(d[2].pointA.x(), 1.2, kDistanceTol);
  EXPECT_NEAR(d[2].pointB.x(), 2.9, kDistanceTol);
}

TEST(DistanceCalculator, TurningTheSecondFrameMovesTheRestOfTheChain) {
  // F2 turned 90 degrees about z: F3 lands at (1, 1, 0), F4 at (1, 2, 0).
  const test::ChainScene s = test::makeChainScene();
  const DistanceCalculator calc(*s.wc);
  rw::kinematics::State state = s.wc->defaultState();
  s.wc->frames().frame(s.f[1]).setMovableTransform(state, pose({1, 0, 0}, 90, 0, 0));
  const std::vector<FrameDistance> d = calc.distances(state);
  ASSERT_EQ(d.size(), 3U);
  const double r13 = std::sqrt(2.0) - 0.3;
  // F4's box is closest to the origin at its corner (0.9, 1.9, 0).
  const double r14 = std::sqrt(0.9 * 0.9 + 1.9 * 1.9) - 0.2;
  EXPECT_NEAR(d[0].distance, r13, kDistanceTol);
  EXPECT_NEAR(d[1].distance, r14, kDistanceTol);
  EXPECT_NEAR(d[2].distance, 2.0 - 0.2 - 0.1, kDistanceTol);
  const Vector3D u = Vector3D(1, 1, 0).normalized();
  EXPECT_VECTOR_NEAR(d[0].pointA, Vector3D(0.2 * u), kDistanceTol);
  EXPECT_VECTOR_NEAR(d[0].pointB, Vector3D(Vector3D(1, 1, 0) - 0.1 * u), kDistanceTol);
  EXPECT_VECTOR_NEAR(d[1].pointB, Vector3D(0.9, 1.9, 0), kDistanceTol);

  const std::optional<FrameDistance> m = calc.minimum(state);
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->frames, makeFramePair(s.f[0], s.f[2]));
  EXPECT_NEAR(m->distance, r13, kDistanceTol);
}

TEST(DistanceCalculator, MinimumAndEmptyPairList) {
  const test::ChainScene s = test::makeChainScene();
  const DistanceCalculator calc(*s.wc);
  const std::optional<FrameDistance> m = calc.minimum(s.wc->defaultState());
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->distance, 1.7, kDistanceTol);
  EXPECT_EQ(m->frames, makeFramePair(s.f[0], s.f[2]));  // the first of two equal pairs

  rw::models::ProximitySetup none;
  none.useIncludeAll = false;
  const DistanceCalculator empty(*s.wc, none);
  EXPECT_TRUE(empty.distances(s.wc->defaultState()).empty());
  EXPECT_FALSE(empty.minimum(s.wc->defaultState()).has_value());
}

TEST(DistanceCalculator, FrameWithSeveralGeometriesUsesTheClosest) {
  rw::models::WorkCell wc("Several");
  const auto world = rw::kinematics::FrameTree::kWorld;
  const auto a = test::addFrame(wc, "A", world, test::FrameType::kFixed);
  const auto b = test::addFrame(wc, "B", world, test::FrameType::kMovable, pose({3, 0, 0}));
  test::addGeometry(wc, a, rw::geometry::Geometry::sphere(0.5));
  test::addGeometry(wc, a, rw::geometry::Geometry::box(0.2, 0.2, 0.2), pose({1.5, 0, 0}));
  test::addGeometry(wc, b, rw::geometry::Geometry::sphere(0.25));
  const DistanceCalculator calc(wc);
  const std::vector<FrameDistance> d = calc.distances(wc.defaultState());
  ASSERT_EQ(d.size(), 1U);
  EXPECT_NEAR(d[0].distance, 3.0 - 1.6 - 0.25, kDistanceTol);  // box face at 1.6
  EXPECT_VECTOR_NEAR(d[0].pointA, Vector3D(1.6, 0, 0), kDistanceTol);
}

}  // namespace
}  // namespace rw::proximity
