#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "visgrab/database/stereo_calibration.hpp"

/// The baseline method's vision (paper §4): stereo images to a point cloud, the table plane,
/// object clusters, surface patches and the grasps on them. Uses only the images and the
/// calibration: no object models, no ground truth.
namespace visgrab::vision {

/// Settings of the dense stereo step (OpenCV StereoSGBM). The disparity search range is not a
/// setting: it follows from the calibration and the workspace (stereoDisparityRange).
struct StereoOptions {
  /// Radius (m) around the table frame's origin, in the table plane, in which objects can
  /// stand; together with workspaceHeight it bounds the disparities searched.
  double workspaceRadius = 0.25;
  /// Height (m) above the table up to which objects can reach.
  double workspaceHeight = 0.3;
  /// SGBM matching block side (odd, pixels). 5 keeps object edges sharp at 720x540.
  int blockSize = 5;
  /// SGBM smoothness penalties P1 = p1Factor * blockSize^2 and P2 = p2Factor * blockSize^2 (the
  /// values OpenCV's documentation suggests for one channel: 8 and 32).
  int p1Factor = 8;
  /// See p1Factor.
  int p2Factor = 32;
  /// SGBM uniqueness margin in percent: the best cost must beat the second best by this much.
  int uniquenessRatio = 10;
  /// Largest left-right check difference in pixels (-1: no check).
  int disp12MaxDiff = 1;
  /// Speckle filter: regions of fewer pixels than this whose disparity varies by at most
  /// speckleRange are removed as noise.
  int speckleWindowSize = 100;
  /// See speckleWindowSize (in disparity pixels).
  int speckleRange = 2;
  /// Pixels whose grey levels vary less than this (standard deviation over the block) are
  /// marked untextured (OrganizedCloud::textured): their disparity is a guess of SGBM's
  /// smoothness term, good enough for a large plane (the table) but not for objects (a flat
  /// wall behind the table "matches" anywhere). Just above the rendering's noise (1.2).
  double minTexture = 1.5;
  /// Cap of the x-derivative prefilter.
  int preFilterCap = 31;
  /// Pixel step of the point cloud grid (1: every pixel; 2: every other row and column).
  int cloudStep = 2;
};

/// Disparities SGBM searches: [minDisparity, minDisparity + numDisparities).
struct DisparityRange {
  /// Smallest disparity searched (pixels).
  int minDisparity = 0;
  /// Number of disparities searched (a multiple of 16).
  int numDisparities = 16;
};

/// The disparities of the points of the workspace (a cylinder of workspaceRadius and
/// workspaceHeight standing on the table frame's origin) that the left camera sees, from the
/// rectified projections P1, P2 and the left camera's pose, with a margin of 8 pixels, rounded
/// out to SGBM's multiples of 16. @throws std::invalid_argument if part of the workspace lies
/// behind the camera or the camera sees none of it.
DisparityRange stereoDisparityRange(const database::StereoCalibration& calibration,
                                    const StereoOptions& options);

/// A point cloud organised as the image it came from: grid cell (row, col) is the pixel
/// (col * step, row * step) of the rectified left image. Points are in the table (world) frame.
struct OrganizedCloud {
  /// Grid columns.
  int width = 0;
  /// Grid rows.
  int height = 0;
  /// Pixel step of the grid.
  int step = 1;
  /// Row-major points, NaN where the disparity is unknown.
  std::vector<Eigen::Vector3f> points;
  /// Per cell: 1 if the image is textured there (StereoOptions::minTexture), else 0.
  std::vector<std::uint8_t> textured;
  /// The left camera's optical centre in the table frame (for orienting normals).
  Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();

  /// Number of grid cells.
  int size() const { return width * height; }
  /// True if cell i has a point.
  bool valid(int i) const { return !std::isnan(points[static_cast<std::size_t>(i)].x()); }
  /// The point of cell i as double.
  Eigen::Vector3d point(int i) const { return points[static_cast<std::size_t>(i)].cast<double>(); }
};

/// The left and right images rectified as the calibration says. When the calibration is
/// already rectified (no distortion, R1 = R2 = I, K = P's left 3x3), the images are returned
/// as they are. @throws std::invalid_argument if the image sizes differ from the calibration's.
void rectifyPair(const cv::Mat& left, const cv::Mat& right,
                 const database::StereoCalibration& calibration, cv::Mat& leftRectified,
                 cv::Mat& rightRectified);

/// Dense disparity of a rectified pair with StereoSGBM (grey images, 3-way mode): CV_32F
/// pixels, negative where unknown.
cv::Mat computeDisparity(const cv::Mat& leftRectified, const cv::Mat& rightRectified,
                         const database::StereoCalibration& calibration,
                         const StereoOptions& options);

/// CV_8U mask of the pixels of the rectified left image with texture (StereoOptions::minTexture).
cv::Mat textureMask(const cv::Mat& leftRectified, const StereoOptions& options);

/// The disparity reprojected with Q into the rectified left camera, then into the table
/// frame (X_TL * R1^T), sampled every options.cloudStep pixels; `textured` (textureMask, or
/// empty: all textured) fills OrganizedCloud::textured.
OrganizedCloud reprojectToTable(const cv::Mat& disparity, const cv::Mat& textured,
                                const database::StereoCalibration& calibration,
                                const StereoOptions& options);

/// What a pair of images given to stereoCloud is.
enum class StereoPair {
  /// As the cameras took them (distortion, unrectified): rectified with rectifyPair first.
  kRaw,
  /// Already rectified for the calibration's P1, P2 (a database's left.png and right.png):
  /// matched as they are, whatever the calibration's distortion and R1, R2.
  kRectified,
};

/// rectifyPair (for a kRaw pair), computeDisparity and reprojectToTable in one.
OrganizedCloud stereoCloud(const cv::Mat& left, const cv::Mat& right,
                           const database::StereoCalibration& calibration,
                           const StereoOptions& options, StereoPair pair = StereoPair::kRaw);

}  // namespace visgrab::vision
