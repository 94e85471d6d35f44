#pragma once

#include <utility>

#include "rw/math/types.hpp"
#include "visgrab/database/stereo_calibration.hpp"
#include "visgrab/generator/placement.hpp"
#include "visgrab/render/camera.hpp"
#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::generator {

/// The geometry of the database's stereo rig and its ideal sensor (CameraProfile::rig; the
/// ideal profile is this rig alone): two identical parallel cameras (already rectified, no
/// distortion) in front of and above the table, looking down at its centre as in the paper's
/// Figure 3. Defaults: 720 x 540 pixels, fx = fy = 810 px (48 degrees horizontal field of view,
/// like a 1/3" sensor behind a 6 mm lens), baseline 12 cm, rig centre 0.5 m in front of and
/// 0.5 m above the table centre (0.66 m from the objects, 43 degrees down). The image size
/// keeps the 432 scenes' noisy PNG pairs within the database's 600 MB.
struct StereoRigSpec {
  /// Image width, pixels.
  int width = 720;
  /// Image height, pixels.
  int height = 540;
  /// Focal length, pixels (fx = fy).
  double focal = 810.0;
  /// Distance between the optical centres, m.
  double baseline = 0.12;
  /// Midpoint between the optical centres, table frame, m.
  rw::math::Vector3D eye{0.0, -0.5, 0.5};
  /// The point both optical axes aim at (parallel axes through the rig centre), table frame.
  rw::math::Vector3D target{0.0, 0.0, 0.05};
  /// Sensor noise, standard deviation in grey levels of 0..255, per channel and pixel.
  double noiseSigma = 1.2;
  /// Optical blur, Gaussian standard deviation in pixels (0: none).
  double blurSigma = 0.5;
};

/// The pose of a camera at `eye` looking at `target` in OpenCV axes (z forward, x right, y
/// down), with x horizontal (perpendicular to the table normal z).
/// @throws std::invalid_argument if the view direction is vertical or zero.
rw::math::Transform3D lookAt(const rw::math::Vector3D& eye, const rw::math::Vector3D& target);

/// The calibration of the rig (database::idealRectifiedRig over the left camera's pose).
database::StereoCalibration rigCalibration(const StereoRigSpec& spec);

/// The left and right cameras that render rectified images matching `calibration`'s P1 and P2
/// (the right camera baseline() metres along the left camera's x axis).
std::pair<render::PinholeCamera, render::PinholeCamera> rigCameras(
    const database::StereoCalibration& calibration);

/// Adds optical blur and Gaussian sensor noise to a rendered image, deterministically for the
/// stream `random`: the ideal rig's effects as the generator applied them before camera
/// profiles (CameraRig with the ideal profile gives the same bytes; kept as that reference).
void addSensorEffects(visual::RgbImage& image, const StereoRigSpec& spec, Random& random);

}  // namespace visgrab::generator
