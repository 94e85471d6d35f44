// stereoAccuracy against depths worked by hand: an ideal rig with f = 500 px and b = 0.1 m puts a
// disparity of 50 px at z = f b / d = 1 m.
#include <gtest/gtest.h>

#include <limits>
#include <opencv2/core.hpp>
#include <stdexcept>

#include "visgrab/database/stereo_accuracy.hpp"

namespace visgrab::database {
namespace {

TEST(StereoAccuracy, CountsObjectPixelsFoundWithinTheTolerance) {
  const StereoCalibration rig =
      idealRectifiedRig(500.0, 500.0, 2.0, 1.0, 0.1, 5, 3, rw::math::Transform3D::Identity());
  cv::Mat disparity(3, 5, CV_32F, cv::Scalar(50.0f));
  cv::Mat depth(3, 5, CV_32F, cv::Scalar(1.0f));
  cv::Mat mask(3, 5, CV_8U, cv::Scalar(7));
  mask.at<std::uint8_t>(0, 0) = 0;                                      // background: not counted
  mask.at<std::uint8_t>(0, 1) = 255;                                    // table: not counted
  depth.at<float>(1, 0) = 1.004f;                                       // 4 mm off: within 5 mm
  depth.at<float>(1, 1) = 1.006f;                                       // 6 mm off: not within
  disparity.at<float>(1, 2) = 40.0f;                                    // z = 1.25 m: not within
  disparity.at<float>(1, 3) = -1.0f;                                    // no disparity
  disparity.at<float>(1, 4) = std::numeric_limits<float>::quiet_NaN();  // no disparity
  disparity.at<float>(2, 0) = 0.0f;                                     // no disparity
  const StereoAccuracy r = stereoAccuracy(disparity, depth, mask, rig, 0.005);
  EXPECT_EQ(r.objectPixels, 13);
  EXPECT_EQ(r.withDisparity, 10);
  EXPECT_EQ(r.within, 8);
  EXPECT_DOUBLE_EQ(r.shareOfObjects(), 8.0 / 13.0);
  EXPECT_DOUBLE_EQ(r.shareOfFound(), 8.0 / 10.0);
}

TEST(StereoAccuracy, RefusesImagesOfOtherTypesOrSizes) {
  const StereoCalibration rig =
      idealRectifiedRig(500.0, 500.0, 2.0, 1.0, 0.1, 5, 3, rw::math::Transform3D::Identity());
  const cv::Mat disparity(3, 5, CV_32F, cv::Scalar(50.0f));
  const cv::Mat depth(3, 5, CV_32F, cv::Scalar(1.0f));
  const cv::Mat mask(3, 5, CV_8U, cv::Scalar(7));
  EXPECT_THROW(stereoAccuracy(disparity, depth, cv::Mat(3, 4, CV_8U), rig, 0.005),
               std::invalid_argument);
  EXPECT_THROW(stereoAccuracy(cv::Mat(3, 5, CV_16U), depth, mask, rig, 0.005),
               std::invalid_argument);
}

}  // namespace
}  // namespace visgrab::database
