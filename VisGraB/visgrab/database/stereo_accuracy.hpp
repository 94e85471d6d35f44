#pragma once

#include <opencv2/core/mat.hpp>
#include <string_view>

#include "visgrab/database/database.hpp"
#include "visgrab/database/stereo_calibration.hpp"

namespace visgrab::database {

/// How well a disparity map of a scene's rectified pair recovers the objects' depth.
struct StereoAccuracy {
  /// Object pixels of the ground-truth mask (ids 1..254).
  int objectPixels = 0;
  /// Object pixels with a disparity (> 0).
  int withDisparity = 0;
  /// Object pixels whose depth from the disparity (reprojected with Q) lies within the
  /// tolerance of the ground-truth depth.
  int within = 0;
  /// within / objectPixels (0 when there are none): the share of the objects found.
  double shareOfObjects() const {
    return objectPixels > 0 ? static_cast<double>(within) / objectPixels : 0.0;
  }
  /// within / withDisparity (0 when there are none): how right the disparities found are.
  double shareOfFound() const {
    return withDisparity > 0 ? static_cast<double>(within) / withDisparity : 0.0;
  }
};

/// Compares `disparity` (CV_32F, pixels; <= 0 or NaN: none) of the rectified left view with the
/// ground truth `depth` (CV_32F, metres; 0: nothing) on the object pixels of `mask` (CV_8U, ids
/// 1..254): camera z of (u, v, d) is Q's, as cv::reprojectImageTo3D computes it.
/// @throws std::invalid_argument when the three images differ in size or type.
StereoAccuracy stereoAccuracy(const cv::Mat& disparity, const cv::Mat& depth, const cv::Mat& mask,
                              const StereoCalibration& calibration, double tolerance);

/// The same for a scene of `db` from its own files (disparity.png, depth.png, mask.png and
/// calibration.yml). @throws UnknownSceneError, DatabaseError naming a missing or bad file.
StereoAccuracy stereoAccuracy(const Database& db, std::string_view id, double tolerance);

}  // namespace visgrab::database
