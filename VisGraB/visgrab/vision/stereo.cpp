#include "visgrab/vision/stereo.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace visgrab::vision {
namespace {

cv::Mat toCv(const Eigen::MatrixXd& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}

bool alreadyRectified(const database::StereoCalibration& k) {
  constexpr double kTol = 1e-9;
  return k.D1.isZero(kTol) && k.D2.isZero(kTol) && k.R1.isIdentity(kTol) && k.R2.isIdentity(kTol) &&
         k.K1.isApprox(k.P1.leftCols<3>(), kTol) && k.K2.isApprox(k.P2.leftCols<3>(), kTol);
}

cv::Mat rectifyOne(const cv::Mat& image, const Eigen::Matrix3d& K, const Eigen::VectorXd& D,
                   const Eigen::Matrix3d& R, const Eigen::Matrix<double, 3, 4>& P) {
  cv::Mat map1, map2, out;
  cv::initUndistortRectifyMap(toCv(K), toCv(D.transpose()), toCv(R), toCv(P.leftCols<3>()),
                              image.size(), CV_32FC1, map1, map2);
  cv::remap(image, out, map1, map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  return out;
}

cv::Mat grey(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat out;
  cv::cvtColor(image, out, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return out;
}

}  // namespace

DisparityRange stereoDisparityRange(const database::StereoCalibration& calibration,
                                    const StereoOptions& options) {
  // Left camera (unrectified) from table: inverse of X_TL; rectified = R1 * camera.
  const Eigen::Matrix3d R_TL = calibration.X_TL.linear();
  const Eigen::Vector3d t_TL = calibration.X_TL.translation();
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  // The workspace cylinder, sampled through its volume; only points the left camera sees count.
  for (int ring = 0; ring <= 6; ++ring) {
    const double radius = options.workspaceRadius * ring / 6.0;
    for (int k = 0; k < (ring == 0 ? 1 : 24); ++k) {
      const double a = 2.0 * M_PI * k / 24.0;
      for (int level = 0; level <= 4; ++level) {
        const Eigen::Vector3d p_T(radius * std::cos(a), radius * std::sin(a),
                                  options.workspaceHeight * level / 4.0);
        const Eigen::Vector3d p_rect = calibration.R1 * (R_TL.transpose() * (p_T - t_TL));
        if (p_rect.z() <= 1e-3) {
          throw std::invalid_argument("stereo: the workspace reaches behind the left camera");
        }
        const Eigen::Vector3d u1 = calibration.P1 * p_rect.homogeneous();
        const Eigen::Vector3d u2 = calibration.P2 * p_rect.homogeneous();
        const double x = u1.x() / u1.z(), y = u1.y() / u1.z();
        if (x < 0 || y < 0 || x >= calibration.width || y >= calibration.height) continue;
        const double d = x - u2.x() / u2.z();
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    }
  }
  if (!(lo <= hi))
    throw std::invalid_argument("stereo: the left camera sees no part of the workspace");
  constexpr double kMargin = 8.0;
  DisparityRange range;
  range.minDisparity = std::max(0, static_cast<int>(std::floor(lo - kMargin)));
  const int span = static_cast<int>(std::ceil(hi + kMargin)) - range.minDisparity + 1;
  range.numDisparities = std::max(16, (span + 15) / 16 * 16);
  return range;
}

void rectifyPair(const cv::Mat& left, const cv::Mat& right,
                 const database::StereoCalibration& calibration, cv::Mat& leftRectified,
                 cv::Mat& rightRectified) {
  const cv::Size size(calibration.width, calibration.height);
  if (left.size() != size || right.size() != size) {
    throw std::invalid_argument("stereo: images are " + std::to_string(left.cols) + "x" +
                                std::to_string(left.rows) + " and " + std::to_string(right.cols) +
                                "x" + std::to_string(right.rows) + ", the calibration expects " +
                                std::to_string(size.width) + "x" + std::to_string(size.height));
  }
  if (alreadyRectified(calibration)) {
    leftRectified = left;
    rightRectified = right;
    return;
  }
  leftRectified = rectifyOne(left, calibration.K1, calibration.D1, calibration.R1, calibration.P1);
  rightRectified =
      rectifyOne(right, calibration.K2, calibration.D2, calibration.R2, calibration.P2);
}

cv::Mat computeDisparity(const cv::Mat& leftRectified, const cv::Mat& rightRectified,
                         const database::StereoCalibration& calibration,
                         const StereoOptions& options) {
  const DisparityRange range = stereoDisparityRange(calibration, options);
  const int b2 = options.blockSize * options.blockSize;
  auto sgbm = cv::StereoSGBM::create(
      range.minDisparity, range.numDisparities, options.blockSize, options.p1Factor * b2,
      options.p2Factor * b2, options.disp12MaxDiff, options.preFilterCap, options.uniquenessRatio,
      options.speckleWindowSize, options.speckleRange, cv::StereoSGBM::MODE_SGBM_3WAY);
  // SGBM leaves the first minDisparity + numDisparities columns without a result; pad both
  // images on the left by that much so that every real column gets one.
  const int pad = range.minDisparity + range.numDisparities;
  cv::Mat l, r, padded;
  cv::copyMakeBorder(grey(leftRectified), l, 0, 0, pad, 0, cv::BORDER_REPLICATE);
  cv::copyMakeBorder(grey(rightRectified), r, 0, 0, pad, 0, cv::BORDER_REPLICATE);
  sgbm->compute(l, r, padded);
  cv::Mat fixedPoint = padded.colRange(pad, padded.cols), disparity;
  // SGBM marks unknown pixels with (minDisparity - 1) * 16; make them negative.
  fixedPoint.convertTo(disparity, CV_32F, 1.0 / 16.0);
  const float unknown = static_cast<float>(range.minDisparity) - 0.5f;
  disparity.setTo(-1.0f, disparity < unknown);
  return disparity;
}

cv::Mat textureMask(const cv::Mat& leftRectified, const StereoOptions& options) {
  cv::Mat g, mean, meanSq;
  grey(leftRectified).convertTo(g, CV_32F);
  const cv::Size window(options.blockSize, options.blockSize);
  cv::boxFilter(g, mean, CV_32F, window);
  cv::boxFilter(g.mul(g), meanSq, CV_32F, window);
  const cv::Mat variance = meanSq - mean.mul(mean);
  return variance >= options.minTexture * options.minTexture;
}

OrganizedCloud reprojectToTable(const cv::Mat& disparity, const cv::Mat& textured,
                                const database::StereoCalibration& calibration,
                                const StereoOptions& options) {
  const int step = std::max(1, options.cloudStep);
  OrganizedCloud cloud;
  cloud.step = step;
  cloud.width = (disparity.cols + step - 1) / step;
  cloud.height = (disparity.rows + step - 1) / step;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points.assign(static_cast<std::size_t>(cloud.size()), Eigen::Vector3f(nan, nan, nan));
  cloud.textured.assign(static_cast<std::size_t>(cloud.size()), 0);
  // Table from rectified camera.
  const Eigen::Matrix3d R = calibration.rectifiedLeftPose().linear();
  const Eigen::Vector3d t = calibration.X_TL.translation();
  cloud.viewpoint = t;
  for (int r = 0; r < cloud.height; ++r) {
    const float* row = disparity.ptr<float>(r * step);
    for (int c = 0; c < cloud.width; ++c) {
      const float d = row[c * step];
      if (d <= 0.0f) continue;
      const Eigen::Vector4d h =
          calibration.Q * Eigen::Vector4d(c * step, r * step, static_cast<double>(d), 1.0);
      if (std::abs(h.w()) < 1e-12) continue;
      const Eigen::Vector3d p_rect = h.head<3>() / h.w();
      if (p_rect.z() <= 0.0) continue;
      const auto i = static_cast<std::size_t>(r * cloud.width + c);
      cloud.points[i] = (R * p_rect + t).cast<float>();
      cloud.textured[i] = textured.empty() || textured.at<std::uint8_t>(r * step, c * step) ? 1 : 0;
    }
  }
  return cloud;
}

OrganizedCloud stereoCloud(const cv::Mat& left, const cv::Mat& right,
                           const database::StereoCalibration& calibration,
                           const StereoOptions& options, StereoPair pair) {
  cv::Mat l, r;
  if (pair == StereoPair::kRaw) {
    rectifyPair(left, right, calibration, l, r);
  } else {
    const cv::Size size(calibration.width, calibration.height);
    if (left.size() != size || right.size() != size) {
      throw std::invalid_argument("stereo: rectified images are " + std::to_string(left.cols) +
                                  "x" + std::to_string(left.rows) + " and " +
                                  std::to_string(right.cols) + "x" + std::to_string(right.rows) +
                                  ", the calibration expects " + std::to_string(size.width) + "x" +
                                  std::to_string(size.height));
    }
    l = left;
    r = right;
  }
  return reprojectToTable(computeDisparity(l, r, calibration, options), textureMask(l, options),
                          calibration, options);
}

}  // namespace visgrab::vision
