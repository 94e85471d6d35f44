#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "rw/math/types.hpp"

namespace visgrab::database {

/// A calibration file that cannot be read; what() names the file and the node.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A calibrated stereo rig, as OpenCV's stereoCalibrate/stereoRectify describe it, plus the
/// pose of the left camera in the table (world) frame.
///
/// Conventions (OpenCV's): x_right = R x_left + T; P1, P2 project rectified left/right camera
/// coordinates to rectified pixels; Q maps (u, v, disparity, 1) to homogeneous 3-D points in the
/// rectified left camera frame. Lengths in metres.
struct StereoCalibration {
  /// Image width and height in pixels.
  int width = 0;
  /// Image height in pixels.
  int height = 0;
  /// Left camera matrix.
  Eigen::Matrix3d K1 = Eigen::Matrix3d::Identity();
  /// Left distortion coefficients (4, 5, 8, 12 or 14 values, OpenCV order).
  Eigen::VectorXd D1 = Eigen::VectorXd::Zero(5);
  /// Right camera matrix.
  Eigen::Matrix3d K2 = Eigen::Matrix3d::Identity();
  /// Right distortion coefficients.
  Eigen::VectorXd D2 = Eigen::VectorXd::Zero(5);
  /// Rotation from the left to the right camera frame.
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  /// Translation from the left to the right camera frame (metres).
  Eigen::Vector3d T = Eigen::Vector3d::Zero();
  /// Rectifying rotation of the left camera.
  Eigen::Matrix3d R1 = Eigen::Matrix3d::Identity();
  /// Rectifying rotation of the right camera.
  Eigen::Matrix3d R2 = Eigen::Matrix3d::Identity();
  /// Rectified left projection matrix.
  Eigen::Matrix<double, 3, 4> P1 = Eigen::Matrix<double, 3, 4>::Zero();
  /// Rectified right projection matrix.
  Eigen::Matrix<double, 3, 4> P2 = Eigen::Matrix<double, 3, 4>::Zero();
  /// Disparity-to-depth matrix.
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  /// Pose of the left camera (OpenCV axes: x right, y down, z forward) in the table frame.
  rw::math::Transform3D X_TL = rw::math::Transform3D::Identity();

  /// Baseline of the rectified rig in metres (|P2's Tx| / f).
  double baseline() const;
  /// Pose of the rectified left camera (the frame of P1, Q, depth and point clouds) in the
  /// table frame: the raw left camera X_TL turned by R1, X_TL * R1^T.
  rw::math::Transform3D rectifiedLeftPose() const;
  /// Why the calibration is inconsistent (empty string if it is consistent): matrix shapes,
  /// finite values, positive focal lengths, rotations, and P1/P2/Q agreeing as stereoRectify
  /// makes them. Messages start with the node name ("Q: ...").
  std::string check() const;
};

/// An ideal rectified rig: both cameras with K = [fx 0 cx; 0 fy cy; 0 0 1], no distortion,
/// R = I, T = (-baseline, 0, 0) (the right camera `baseline` metres along the left camera's x),
/// and R1, R2, P1, P2, Q exactly as cv::stereoRectify computes them for these inputs (default
/// flags CALIB_ZERO_DISPARITY, alpha -1), including its single-precision corner arithmetic.
/// @throws std::invalid_argument for non-positive or non-finite inputs.
StereoCalibration idealRectifiedRig(double fx, double fy, double cx, double cy, double baseline,
                                    int width, int height, const rw::math::Transform3D& X_TL);

/// Reads an OpenCV FileStorage YAML file with nodes image_size, K1, D1, K2, D2, R, T, R1, R2,
/// P1, P2, Q and X_table_left (4x4) and checks it (StereoCalibration::check). The YAML is read
/// by the project's own parser of what cv::FileStorage writes (detail/opencv_yaml.hpp), never by
/// OpenCV's, which does not return on some malformed files.
/// @throws CalibrationError naming the file, the line and the node.
StereoCalibration readCalibration(const std::filesystem::path& file);

/// Same as readCalibration, from YAML text; `displayPath` names it in messages.
/// @throws CalibrationError.
StereoCalibration parseCalibration(std::string_view yaml, const std::string& displayPath);

/// The calibration as OpenCV FileStorage YAML text (full double precision).
std::string calibrationToYaml(const StereoCalibration& calibration);

/// Writes the calibration atomically (temporary file, then rename).
/// @throws std::runtime_error if the file cannot be written.
void writeCalibration(const std::filesystem::path& file, const StereoCalibration& calibration);

}  // namespace visgrab::database
