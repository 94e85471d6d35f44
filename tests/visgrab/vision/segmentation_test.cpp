// Table plane, clusters and patches on ray-cast clouds whose geometry is known exactly
// (synthetic_scene.hpp): the numbers expected are the scene's own dimensions.
#include "visgrab/vision/segmentation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_scene.hpp"

namespace visgrab::vision {
namespace {

using test::Box;
using test::rayCast;
using test::SyntheticScene;

constexpr double kDeg = M_PI / 180.0;

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / kDeg;
}

// A 6 x 4 x 10 cm box standing at the origin.
SyntheticScene standingBox() {
  SyntheticScene s;
  s.boxes.push_back({{-0.03, -0.02, 0.0}, {0.03, 0.02, 0.10}});
  return s;
}

TEST(TablePlane, TiltedTableIsFoundWithinATenthOfADegreeAndAMillimetre) {
  SyntheticScene s;
  // Tilted by 3 deg about x and lowered 1 cm: RANSAC must find it, not the calibrated z = 0.
  s.tableNormal = Eigen::Vector3d(0.0, -std::sin(3 * kDeg), std::cos(3 * kDeg));
  s.tableOffset = -0.01;
  s.noise = 0.001;
  const TablePlane plane = fitTablePlane(rayCast(s), SegmentationOptions{});
  EXPECT_FALSE(plane.fromCalibration);
  EXPECT_LT(angleDeg(plane.normal, s.tableNormal), 0.1);
  EXPECT_NEAR(plane.offset, s.tableOffset, 0.001);
  EXPECT_GT(plane.inliers, 40000);  // most of the 360 x 270 cells see the table
}

TEST(TablePlane, TheTableWinsOverALargeBoxTopBecauseNothingIsBelowIt) {
  // A 40 x 30 cm slab 8 cm high covers much of the view; its top is a plane with many points,
  // but the table's points are below it and count against it.
  SyntheticScene s;
  s.boxes.push_back({{-0.2, -0.15, 0.0}, {0.2, 0.15, 0.08}});
  const TablePlane plane = fitTablePlane(rayCast(s), SegmentationOptions{});
  EXPECT_NEAR(plane.offset, 0.0, 0.001);
  EXPECT_LT(angleDeg(plane.normal, Eigen::Vector3d::UnitZ()), 0.1);
}

TEST(TablePlane, TooFewTablePointsFallBackToTheCalibratedTable) {
  OrganizedCloud cloud = rayCast(standingBox());
  // Keep only the box's points: no table is seen.
  for (auto& p : cloud.points) {
    if (p.z() < 0.005f) p.setConstant(std::numeric_limits<float>::quiet_NaN());
  }
  const TablePlane plane = fitTablePlane(cloud, SegmentationOptions{});
  EXPECT_TRUE(plane.fromCalibration);
  EXPECT_EQ(plane.normal, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(plane.offset, 0.0);
}

TEST(Segmentation, OneBoxIsOneClusterCentredOnTheBox) {
  const SceneSegmentation s = segmentScene(rayCast(standingBox()), SegmentationOptions{});
  ASSERT_EQ(s.clusters.size(), 1u);
  const Cluster& c = s.clusters[0];
  // The top face is seen whole, so the footprint is the box's: 6 x 4 cm around the origin.
  EXPECT_NEAR(c.centre.x(), 0.0, 0.003);
  EXPECT_NEAR(c.centre.y(), 0.0, 0.003);
  EXPECT_NEAR(c.centre.z(), 0.05, 0.003);
  EXPECT_NEAR(c.top, 0.10, 0.002);
  EXPECT_NEAR(c.footprint.x(), 0.06, 0.004);
  EXPECT_NEAR(c.footprint.y(), 0.04, 0.004);
  // Only the front and the top are seen: the centroid lies in front of the centre.
  EXPECT_LT(c.centroid.y(), c.centre.y() - 0.005);
}

TEST(Segmentation, TwoBoxesApartAreTwoClusters) {
  SyntheticScene s = standingBox();
  s.boxes.push_back({{0.08, -0.02, 0.0}, {0.12, 0.03, 0.06}});
  const SceneSegmentation seg = segmentScene(rayCast(s), SegmentationOptions{});
  ASSERT_EQ(seg.clusters.size(), 2u);
  // Largest first: the tall box has more points.
  EXPECT_NEAR(seg.clusters[0].centre.x(), 0.0, 0.003);
  EXPECT_NEAR(seg.clusters[1].centre.x(), 0.10, 0.003);
  EXPECT_NEAR(seg.clusters[1].centre.y(), 0.005, 0.003);
  EXPECT_NEAR(seg.clusters[1].top, 0.06, 0.002);
}

TEST(Segmentation, TheBoxHasATopAndAFrontPatchWithTheirNormalsAndEdges) {
  SyntheticScene scene = standingBox();
  scene.noise = 0.0005;
  const SceneSegmentation s = segmentScene(rayCast(scene), SegmentationOptions{});
  const SurfacePatch* top = nullptr;
  const SurfacePatch* front = nullptr;
  for (const auto& p : s.patches) {
    if (angleDeg(p.normal, Eigen::Vector3d::UnitZ()) < 3.0) top = &p;
    if (angleDeg(p.normal, -Eigen::Vector3d::UnitY()) < 3.0) front = &p;
  }
  ASSERT_NE(top, nullptr);
  ASSERT_NE(front, nullptr);
  EXPECT_NEAR(top->centroid.z(), 0.10, 0.002);
  EXPECT_NEAR(top->centroid.x(), 0.0, 0.003);
  EXPECT_NEAR(front->centroid.y(), -0.02, 0.002);
  // The top's principal axis is the box's long side (x).
  EXPECT_GT(std::abs(top->axis1.x()), 0.95);
  // The top's far edge ends the object (table behind it); its near edge is a crease with the
  // front face.
  int farEdges = 0, nearCreases = 0;
  for (std::size_t k = 0; k < top->boundary.size(); ++k) {
    const Eigen::Vector3d p = s.cloud.point(top->boundary[k]);
    if (p.y() > 0.015 && top->edge[k]) ++farEdges;
    if (p.y() < -0.015 && !top->edge[k]) ++nearCreases;
  }
  EXPECT_GT(farEdges, 10);
  EXPECT_GT(nearCreases, 10);
  for (int i : top->cells) EXPECT_EQ(s.patchOf[static_cast<std::size_t>(i)], &*top - &s.patches[0]);
}

TEST(Segmentation, PointsOutsideTheWorkspaceOrUntexturedAreNotObjects) {
  SyntheticScene scene;
  scene.boxes.push_back({{0.30, 0.0, 0.0}, {0.36, 0.04, 0.10}});  // beyond the 25 cm radius
  OrganizedCloud cloud = rayCast(scene);
  EXPECT_TRUE(segmentScene(cloud, SegmentationOptions{}).clusters.empty());

  scene.boxes = {{{-0.03, -0.02, 0.0}, {0.03, 0.02, 0.10}}};
  cloud = rayCast(scene);
  std::fill(cloud.textured.begin(), cloud.textured.end(), 0);
  EXPECT_TRUE(segmentScene(cloud, SegmentationOptions{}).clusters.empty());
}

}  // namespace
}  // namespace visgrab::vision
