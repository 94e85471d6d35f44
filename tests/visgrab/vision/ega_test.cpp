// The grasp types on a box whose visible faces are known exactly (synthetic_scene.hpp): the
// contacts of the encompassing grasps must sit on the box's sides, wrapDepth below its top, and
// the pinch must put one finger on a face and the other behind it.
#include "visgrab/vision/ega.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_scene.hpp"

namespace visgrab::vision {
namespace {

using test::rayCast;
using test::SyntheticScene;

// A 6 x 4 x 10 cm box standing at the origin, seen from the rig's left camera.
SceneSegmentation boxScene() {
  SyntheticScene s;
  s.boxes.push_back({{-0.03, -0.02, 0.0}, {0.03, 0.02, 0.10}});
  return segmentScene(rayCast(s), SegmentationOptions{});
}

std::vector<CandidateGrasp> ofType(const std::vector<CandidateGrasp>& all, GraspType type) {
  std::vector<CandidateGrasp> out;
  for (const auto& g : all) {
    if (g.type == type) out.push_back(g);
  }
  return out;
}

// True if p lies on the box's surface (within tol) and not inside it by more than tol.
bool onBoxSurface(const Eigen::Vector3d& p, double tol) {
  const Eigen::Vector3d lo(-0.03, -0.02, 0.0), hi(0.03, 0.02, 0.10);
  double outside = 0.0, inside = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    outside = std::max({outside, lo[k] - p[k], p[k] - hi[k]});
    inside = std::min({inside, p[k] - lo[k], hi[k] - p[k]});
  }
  return outside <= tol && (outside > 0.0 || inside <= tol);
}

TEST(GraspTypes, NamesRoundTrip) {
  for (GraspType t : kGraspTypes) EXPECT_EQ(graspTypeFromName(graspTypeName(t)), t);
  EXPECT_STREQ(graspTypeName(GraspType::kS3Ega1), "s3EGA1");
  EXPECT_FALSE(graspTypeFromName("s2EGA2").has_value());
}

TEST(GraspTypes, TwoFingerEncompassingGraspsHoldTheTopFromOppositeSides) {
  const SceneSegmentation scene = boxScene();
  GraspOptions options;
  const auto grasps = ofType(generateGrasps(scene, options), GraspType::kS2Ega1);
  ASSERT_FALSE(grasps.empty());
  bool acrossShortSide = false, acrossLongSide = false;
  for (const auto& g : grasps) {
    ASSERT_EQ(g.contacts.size(), 2u);
    const auto& a = g.contacts[0];
    const auto& b = g.contacts[1];
    if (g.approach.z() > -0.99) continue;  // the front face's grasps are checked below
    // From above, wrapDepth (1.5 cm) below the top, on the box's sides, pushing at each other.
    EXPECT_NEAR(a.position.z(), 0.10 - options.wrapDepth, 0.003);
    EXPECT_NEAR(b.position.z(), 0.10 - options.wrapDepth, 0.003);
    EXPECT_TRUE(onBoxSurface(a.position, 0.004)) << a.position.transpose();
    EXPECT_TRUE(onBoxSurface(b.position, 0.004)) << b.position.transpose();
    EXPECT_LT(a.direction.normalized().dot(b.direction.normalized()), -0.999);
    EXPECT_GT(a.direction.dot(b.position - a.position), 0.0);
    const double width = (a.position - b.position).norm();
    acrossShortSide = acrossShortSide || std::abs(width - 0.04) < 0.004;
    acrossLongSide = acrossLongSide || std::abs(width - 0.06) < 0.004;
  }
  EXPECT_TRUE(acrossShortSide);
  EXPECT_TRUE(acrossLongSide);
  // Ranked: best first, the approach from above preferred.
  for (std::size_t i = 1; i < grasps.size(); ++i) EXPECT_GE(grasps[i - 1].score, grasps[i].score);
  EXPECT_LT(grasps.front().approach.z(), -0.99);
}

TEST(GraspTypes, ThreeFingerEncompassingGraspsSurroundTheTop) {
  const SceneSegmentation scene = boxScene();
  GraspOptions options;
  const auto grasps = ofType(generateGrasps(scene, options), GraspType::kS3Ega1);
  ASSERT_FALSE(grasps.empty());
  const auto& g = grasps.front();
  ASSERT_EQ(g.contacts.size(), 3u);
  EXPECT_LT(g.approach.z(), -0.99);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& c : g.contacts) {
    EXPECT_NEAR(c.position.z(), 0.10 - options.wrapDepth, 0.003);
    EXPECT_TRUE(onBoxSurface(c.position, 0.004)) << c.position.transpose();
    centre += c.position / 3.0;
  }
  // Each pushes towards the box's vertical axis (in the top's plane).
  for (const auto& c : g.contacts) {
    const Eigen::Vector3d inward = Eigen::Vector3d(-c.position.x(), -c.position.y(), 0.0);
    EXPECT_GT(c.direction.normalized().dot(inward.normalized()), 0.5);
  }
  for (int i = 0; i < 3; ++i) {
    const double d = (g.contacts[i].position - g.contacts[(i + 1) % 3].position).norm();
    EXPECT_GE(d, options.minSpan);
    EXPECT_LE(d, options.maxSpan);
  }
}

TEST(GraspTypes, PinchPutsOneFingerOnTheFaceAndOneBehindIt) {
  const SceneSegmentation scene = boxScene();
  GraspOptions options;
  const auto grasps = ofType(generateGrasps(scene, options), GraspType::kS2Ega3);
  ASSERT_FALSE(grasps.empty());
  for (const auto& g : grasps) {
    ASSERT_EQ(g.contacts.size(), 2u);
    const auto& front = g.contacts[0];
    const auto& back = g.contacts[1];
    // Opposite pushes along one axis, the back finger behind the front one.
    EXPECT_LT(front.direction.normalized().dot(back.direction.normalized()), -0.999);
    const double thickness = (back.position - front.position).dot(front.direction.normalized());
    EXPECT_GE(thickness, options.pinchThickness - 1e-9);
    EXPECT_LE(thickness, options.maxWidth + 1e-9);
    // The hand comes in across the boundary, perpendicular to the pinch.
    EXPECT_NEAR(g.approach.dot(front.direction.normalized()), 0.0, 1e-9);
    EXPECT_TRUE(onBoxSurface(front.position, 0.004)) << front.position.transpose();
    EXPECT_GE(back.position.z(), options.minContactHeight);
  }
}

TEST(GraspTypes, AtMostPerTypeAndNoTwoAlike) {
  const SceneSegmentation scene = boxScene();
  GraspOptions options;
  options.perType = 3;
  const auto grasps = generateGrasps(scene, options);
  for (GraspType t : kGraspTypes) EXPECT_LE(ofType(grasps, t).size(), 3u);
  // Types in kGraspTypes order.
  for (std::size_t i = 1; i < grasps.size(); ++i)
    EXPECT_LE(static_cast<int>(grasps[i - 1].type), static_cast<int>(grasps[i].type));
  // The same input gives the same grasps.
  const auto again = generateGrasps(scene, options);
  ASSERT_EQ(again.size(), grasps.size());
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    for (std::size_t k = 0; k < grasps[i].contacts.size(); ++k)
      EXPECT_EQ(grasps[i].contacts[k].position, again[i].contacts[k].position);
  }
}

TEST(GraspTypes, NoGraspsWithoutObjects) {
  SyntheticScene s;
  EXPECT_TRUE(
      generateGrasps(segmentScene(rayCast(s), SegmentationOptions{}), GraspOptions{}).empty());
}

}  // namespace
}  // namespace visgrab::vision
