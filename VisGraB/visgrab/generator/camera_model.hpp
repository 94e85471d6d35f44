#pragma once

#include <array>
#include <opencv2/core/mat.hpp>

#include "rw/math/types.hpp"
#include "visgrab/database/stereo_calibration.hpp"
#include "visgrab/generator/camera_profile.hpp"
#include "visgrab/generator/placement.hpp"
#include "visgrab/render/camera.hpp"
#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::generator {

/// OpenCV's lens distortion (k1 k2 p1 p2 k3) of normalised image coordinates (x, y) = (X/Z,
/// Y/Z): x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2), y_d likewise
/// with p1 (r^2 + 2 y^2) + 2 p2 x y.
Eigen::Vector2d distortPoint(const Eigen::Vector2d& xy, const std::array<double, 5>& d);

/// The inverse of distortPoint by fixed-point iteration (until the point re-distorts within
/// 1e-12, at most 100 steps): the normalised coordinates whose distortion is `xyd`.
Eigen::Vector2d undistortPoint(const Eigen::Vector2d& xyd, const std::array<double, 5>& d);

/// A stereo rig made from a CameraProfile: its calibration, the cameras to render, and the
/// image pipeline from a render to the raw sensor image and from the raw image to the
/// rectified one. Built once per generation (the warp and rectification maps are computed
/// here) and then used const from any number of threads.
///
/// Left is side 0, right side 1. The raw left camera's pose is the ideal rig's left camera
/// (StereoCalibration::X_TL); the raw right camera is the ideal right camera turned and shifted
/// by the profile's misalignment. Raw intrinsics: fx = focal, fy = focal * focalRatio, principal
/// point at the image centre plus the offset, and the profile's distortion. The rectification
/// is cv::stereoRectify's (CALIB_ZERO_DISPARITY, alpha 0, same image size); for a profile that
/// is already rectified (CameraProfile::alreadyRectified) it is idealRectifiedRig (no warping).
class CameraRig {
 public:
  /// @throws std::invalid_argument if the rig's view is unusable (CameraProfile values out of
  ///   range, a vertical view direction).
  explicit CameraRig(CameraProfile profile);

  /// The profile.
  const CameraProfile& profile() const { return profile_; }
  /// The calibration written with every scene.
  const database::StereoCalibration& calibration() const { return calibration_; }
  /// Pose of camera `side`'s raw frame in the table frame.
  const rw::math::Transform3D& rawPose(int side) const;
  /// The pinhole camera whose render rawImage() turns into the raw image of `side`: the raw
  /// camera's pose and optical centre, focal length times the supersampling, and a field of view
  /// with a margin covering every raw pixel after undistortion (the raw camera itself, 1:1, when
  /// the profile is already rectified).
  const render::PinholeCamera& renderCamera(int side) const;
  /// The rectified camera of `side` (P1 or P2's intrinsics, pose raw pose * R_i^T): what the
  /// ground truth of the rectified view is rendered with.
  render::PinholeCamera rectifiedCamera(int side) const;

  /// The raw sensor image of `side` from a render of renderCamera(side): optical blur and lens
  /// distortion (warp), vignetting and exposure, Bayer mosaic, read and shot noise, gain,
  /// quantised to 8 bits. CV_8UC1 (the mosaic, profile().bayer) or CV_8UC3 (BGR, no mosaic).
  /// `noise` is the image's own random stream.
  cv::Mat rawImage(int side, const visual::RgbImage& render, Random& noise) const;

  /// The rectified colour image (CV_8UC3, BGR) of a raw image of `side`: demosaiced with
  /// cv::cvtColor (COLOR_BayerBG2BGR for the RGGB mosaic), undistorted and rectified with maps
  /// computed from the calibration (bilinear cv::remap).
  cv::Mat rectify(int side, const cv::Mat& raw) const;

 private:
  CameraProfile profile_;
  database::StereoCalibration calibration_;
  std::array<rw::math::Transform3D, 2> rawPoses_;
  std::array<render::PinholeCamera, 2> renderCameras_;
  /// Per side: render pixel coordinates of each raw pixel (CV_32FC1 x and y).
  std::array<std::array<cv::Mat, 2>, 2> warpMaps_;
  /// Per side: raw pixel coordinates of each rectified pixel (CV_32FC1 x and y).
  std::array<std::array<cv::Mat, 2>, 2> rectifyMaps_;
  /// Per side: vignetting times exposure of each raw pixel (CV_32FC1).
  std::array<cv::Mat, 2> response_;
};

}  // namespace visgrab::generator
