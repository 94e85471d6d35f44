#include "visgrab/database/stereo_accuracy.hpp"

#include <cmath>
#include <stdexcept>

namespace visgrab::database {

StereoAccuracy stereoAccuracy(const cv::Mat& disparity, const cv::Mat& depth, const cv::Mat& mask,
                              const StereoCalibration& calibration, double tolerance) {
  if (disparity.type() != CV_32FC1 || depth.type() != CV_32FC1 || mask.type() != CV_8UC1) {
    throw std::invalid_argument(
        "stereoAccuracy: expected a CV_32F disparity, a CV_32F depth and a CV_8U mask");
  }
  if (disparity.size() != depth.size() || disparity.size() != mask.size()) {
    throw std::invalid_argument("stereoAccuracy: the disparity, depth and mask differ in size");
  }
  const Eigen::Matrix4d& Q = calibration.Q;
  StereoAccuracy out;
  for (int r = 0; r < mask.rows; ++r) {
    for (int c = 0; c < mask.cols; ++c) {
      const int id = mask.at<std::uint8_t>(r, c);
      if (id == 0 || id == 255) continue;
      ++out.objectPixels;
      const double d = disparity.at<float>(r, c);
      if (!(d > 0.0)) continue;
      ++out.withDisparity;
      const Eigen::Vector4d p = Q * Eigen::Vector4d(c, r, d, 1.0);
      const double z = p.z() / p.w();
      if (std::abs(z - depth.at<float>(r, c)) < tolerance) ++out.within;
    }
  }
  return out;
}

StereoAccuracy stereoAccuracy(const Database& db, std::string_view id, double tolerance) {
  return stereoAccuracy(db.disparityImage(id), db.depthImage(id), db.instanceMask(id),
                        db.calibration(id), tolerance);
}

}  // namespace visgrab::database
