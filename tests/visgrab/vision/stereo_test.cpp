// Stereo to table-frame points, against a rig worked by hand: a camera 1 m above the table
// looking straight down, f = 500 px, baseline 10 cm, so a point at height h has disparity
// f B / (1 - h) = 50 / (1 - h) px.
#include "visgrab/vision/stereo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace visgrab::vision {
namespace {

database::StereoCalibration downwardRig() {
  rw::math::Transform3D X_TL = rw::math::Transform3D::Identity();
  X_TL.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);
  // Camera x = table x, camera y = table -y, camera z (forward) = table -z.
  X_TL.linear() << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  return database::idealRectifiedRig(500.0, 500.0, 319.5, 239.5, 0.1, 640, 480, X_TL);
}

TEST(Stereo, DisparityRangeCoversTheWorkspaceWithItsMargin) {
  // Table (h = 0): 50 px; top of the 30 cm workspace: 50 / 0.7 = 71.43 px. With 8 px margins:
  // min floor(42) = 42, span ceil(79.43) - 42 + 1 = 39 -> 48 (multiple of 16).
  const auto range = stereoDisparityRange(downwardRig(), StereoOptions{});
  EXPECT_EQ(range.minDisparity, 42);
  EXPECT_EQ(range.numDisparities, 48);
}

TEST(Stereo, WorkspaceBehindTheCameraIsAnError) {
  auto rig = downwardRig();
  rig.X_TL.translation() = Eigen::Vector3d(0.0, 0.0, 0.2);  // below the workspace's top
  EXPECT_THROW(stereoDisparityRange(rig, StereoOptions{}), std::invalid_argument);
}

TEST(Stereo, ReprojectionPutsAConstantDisparityOnTheTable) {
  const auto rig = downwardRig();
  cv::Mat disparity(480, 640, CV_32F, cv::Scalar(50.0f));
  disparity.at<float>(200, 400) = -1.0f;  // unknown
  StereoOptions options;
  options.cloudStep = 2;
  const OrganizedCloud cloud = reprojectToTable(disparity, cv::Mat(), rig, options);
  ASSERT_EQ(cloud.width, 320);
  ASSERT_EQ(cloud.height, 240);
  EXPECT_FALSE(cloud.valid(100 * 320 + 200));  // pixel (400, 200)
  // Pixel (402, 200): camera (82.5, -39.5) / 500 m at Z = 1 -> table (0.165, 0.079, 0).
  const int i = 100 * 320 + 201;
  ASSERT_TRUE(cloud.valid(i));
  EXPECT_NEAR(cloud.point(i).x(), 82.5 / 500.0, 1e-6);
  EXPECT_NEAR(cloud.point(i).y(), 39.5 / 500.0, 1e-6);
  EXPECT_NEAR(cloud.point(i).z(), 0.0, 1e-6);
  EXPECT_EQ(cloud.textured[static_cast<std::size_t>(i)], 1);
  EXPECT_TRUE(cloud.viewpoint.isApprox(Eigen::Vector3d(0, 0, 1)));
}

TEST(Stereo, SgbmOnAShiftedTextureGivesItsDisparity) {
  // A random texture, and in the right image the same 60 px further left: a plane at
  // Z = 50 / 60 m, i.e. 1/6 m above the table. The left image's first 60 columns have no match.
  const auto rig = downwardRig();
  cv::Mat texture(480, 700, CV_8U);
  cv::RNG rng(11);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(3, 3), 0.8);
  const cv::Mat left = texture.colRange(0, 640).clone();
  const cv::Mat right = texture.colRange(60, 700).clone();
  const OrganizedCloud cloud = stereoCloud(left, right, rig, StereoOptions{});
  int valid = 0, onPlane = 0;
  for (int i = 0; i < cloud.size(); ++i) {
    if (!cloud.valid(i)) continue;
    ++valid;
    if (std::abs(cloud.point(i).z() - (1.0 - 50.0 / 60.0)) < 0.002) ++onPlane;
  }
  EXPECT_GT(valid, cloud.size() * 8 / 10);  // the padding gives the left columns a result
  EXPECT_GT(onPlane, valid * 95 / 100);
}

TEST(Stereo, RectificationMovesAPointWhereP1R1SayIt) {
  // Unrectified left camera K1 (cx 320); rectified with R1 = 5 deg about y and P1 with cx 330.
  database::StereoCalibration k = downwardRig();
  k.K1 << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  k.K2 = k.K1;
  k.R1 = Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  k.R2 = k.R1;
  k.P1.leftCols<3>() << 500, 0, 330, 0, 500, 240, 0, 0, 1;
  const Eigen::Vector3d X(0.05, -0.03, 1.0);  // a point in the left camera frame
  const Eigen::Vector3d raw = k.K1 * X;
  cv::Mat left(480, 640, CV_8U, cv::Scalar(0));
  cv::circle(left, cv::Point2d(raw.x() / raw.z(), raw.y() / raw.z()), 4, cv::Scalar(255), -1);
  cv::Mat l, r;
  rectifyPair(left, left, k, l, r);
  const cv::Moments m = cv::moments(l, true);
  ASSERT_GT(m.m00, 10.0);
  const Eigen::Vector3d expected = k.P1.leftCols<3>() * (k.R1 * X);
  EXPECT_NEAR(m.m10 / m.m00, expected.x() / expected.z(), 1.0);
  EXPECT_NEAR(m.m01 / m.m00, expected.y() / expected.z(), 1.0);
}

TEST(Stereo, ARectifiedPairIsMatchedAsItIsWhateverTheCalibrationsDistortion) {
  // The shifted texture of SgbmOnAShiftedTextureGivesItsDisparity, with a calibration whose raw
  // cameras have distortion and R1 = R2 = 3 degrees about y (P1, P2 unchanged): as a rectified
  // pair (a database's left.png, right.png) the plane is found as before; rectified again it
  // is not.
  database::StereoCalibration k = downwardRig();
  k.D1 << -0.2, 0.05, 0, 0, 0;
  k.D2 = k.D1;
  k.R1 = Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  k.R2 = k.R1;
  cv::Mat texture(480, 700, CV_8U);
  cv::RNG rng(11);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(3, 3), 0.8);
  const cv::Mat left = texture.colRange(0, 640).clone();
  const cv::Mat right = texture.colRange(60, 700).clone();
  // The plane Z = 50/60 m in the rectified camera, i.e. at X_TL R1^T (0, 0, Z) in the table.
  auto onPlane = [&](const OrganizedCloud& cloud) {
    const Eigen::Matrix3d R_TC = k.X_TL.linear() * k.R1.transpose();
    int valid = 0, on = 0;
    for (int i = 0; i < cloud.size(); ++i) {
      if (!cloud.valid(i)) continue;
      ++valid;
      const Eigen::Vector3d p_C = R_TC.transpose() * (cloud.point(i) - k.X_TL.translation());
      if (std::abs(p_C.z() - 50.0 / 60.0) < 0.002) ++on;
    }
    return std::pair{valid, on};
  };
  const auto [valid, on] =
      onPlane(stereoCloud(left, right, k, StereoOptions{}, StereoPair::kRectified));
  EXPECT_GT(valid, 640 * 480 / 4 * 8 / 10);
  EXPECT_GT(on, valid * 95 / 100);
  const auto [rawValid, rawOn] = onPlane(stereoCloud(left, right, k, StereoOptions{}));
  EXPECT_LT(rawOn, valid * 80 / 100) << rawValid;  // the default treats them as raw: remapped
  // Rectified images of the wrong size are an error too.
  const cv::Mat small(100, 100, CV_8U, cv::Scalar(0));
  EXPECT_THROW(stereoCloud(small, small, k, StereoOptions{}, StereoPair::kRectified),
               std::invalid_argument);
}

TEST(Stereo, ImagesOfTheWrongSizeAreAnError) {
  const cv::Mat small(100, 100, CV_8U, cv::Scalar(0));
  cv::Mat l, r;
  try {
    rectifyPair(small, small, downwardRig(), l, r);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("640x480"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace visgrab::vision
