#include "visgrab/generator/camera_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "rw/math/rpy.hpp"

namespace visgrab::generator {

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

cv::Mat toCv(const Eigen::MatrixXd& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}

Eigen::MatrixXd fromCv(const cv::Mat& m) {
  Eigen::MatrixXd out;
  cv::cv2eigen(m, out);
  return out;
}

Eigen::Matrix3d cameraMatrix(const StereoRigSpec& rig, const CameraSensorSpec& camera) {
  Eigen::Matrix3d K;
  K << rig.focal, 0.0, 0.5 * (rig.width - 1) + camera.principalOffset[0], 0.0,
      rig.focal * camera.focalRatio, 0.5 * (rig.height - 1) + camera.principalOffset[1], 0.0, 0.0,
      1.0;
  return K;
}

/// The right camera's pose in the left camera's frame: the ideal offset along x plus the
/// misalignment (rotation about the right camera's own axes, RobWork RPY in degrees).
Transform3D rightInLeft(const CameraProfile& p) {
  constexpr double kRadPerDeg = std::numbers::pi / 180.0;
  const rw::math::Rotation3D R = rw::math::rpyToRotation(
      Vector3D(p.misalignmentRpy[0], p.misalignmentRpy[1], p.misalignmentRpy[2]) * kRadPerDeg);
  const Vector3D t(p.rig.baseline + p.misalignmentOffset[0], p.misalignmentOffset[1],
                   p.misalignmentOffset[2]);
  return rw::math::makeTransform(R, t);
}

/// Vignetting times exposure at each pixel: cos^4 of an effective field angle whose tangent
/// grows linearly with the distance from the principal point, scaled so that the farthest
/// image corner keeps 1 - strength.
cv::Mat responseMap(int width, int height, double cx, double cy, double strength, double exposure) {
  cv::Mat out(height, width, CV_32F);
  double corner2 = 0.0;
  for (const double u : {0.0, width - 1.0}) {
    for (const double v : {0.0, height - 1.0}) {
      corner2 = std::max(corner2, (u - cx) * (u - cx) + (v - cy) * (v - cy));
    }
  }
  const double t2 = strength > 0.0 ? 1.0 / std::sqrt(1.0 - strength) - 1.0 : 0.0;
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const double rho2 = ((c - cx) * (c - cx) + (r - cy) * (r - cy)) / corner2;
      const double falloff = 1.0 / ((1.0 + rho2 * t2) * (1.0 + rho2 * t2));
      out.at<float>(r, c) = static_cast<float>(strength > 0.0 ? falloff * exposure : exposure);
    }
  }
  return out;
}

/// RGGB: the channel (0 red, 1 green, 2 blue) a photosite in row r and column c sees.
int rggbChannel(int r, int c) { return (r % 2) + (c % 2); }

}  // namespace

Eigen::Vector2d distortPoint(const Eigen::Vector2d& xy, const std::array<double, 5>& d) {
  const double x = xy.x();
  const double y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  return {x * radial + 2.0 * d[2] * x * y + d[3] * (r2 + 2.0 * x * x),
          y * radial + d[2] * (r2 + 2.0 * y * y) + 2.0 * d[3] * x * y};
}

Eigen::Vector2d undistortPoint(const Eigen::Vector2d& xyd, const std::array<double, 5>& d) {
  Eigen::Vector2d xy = xyd;
  for (int i = 0; i < 100; ++i) {
    const double x = xy.x();
    const double y = xy.y();
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
    const Eigen::Vector2d tangential(2.0 * d[2] * x * y + d[3] * (r2 + 2.0 * x * x),
                                     d[2] * (r2 + 2.0 * y * y) + 2.0 * d[3] * x * y);
    xy = (xyd - tangential) / radial;
    if ((distortPoint(xy, d) - xyd).norm() < 1e-12) break;
  }
  return xy;
}

namespace {

/// The raw calibration of the profile's cameras with cv::stereoRectify's rectification
/// (CALIB_ZERO_DISPARITY, alpha 0, the image size kept). @throws std::invalid_argument if the
/// result fails StereoCalibration::check().
database::StereoCalibration rectifiedCalibration(const CameraProfile& profile,
                                                 const std::array<Eigen::Matrix3d, 2>& K,
                                                 const Transform3D& X_TL, const Transform3D& X_LR) {
  database::StereoCalibration c;
  c.width = profile.rig.width;
  c.height = profile.rig.height;
  c.K1 = K[0];
  c.K2 = K[1];
  c.D1 = Eigen::Map<const Eigen::VectorXd>(profile.cameras[0].distortion.data(), 5);
  c.D2 = Eigen::Map<const Eigen::VectorXd>(profile.cameras[1].distortion.data(), 5);
  c.R = X_LR.linear().transpose();
  c.T = -(X_LR.linear().transpose() * X_LR.translation());
  const cv::Size size(c.width, c.height);
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(toCv(c.K1), toCv(c.D1), toCv(c.K2), toCv(c.D2), size, toCv(c.R), toCv(c.T), R1,
                    R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0.0, size);
  c.R1 = fromCv(R1);
  c.R2 = fromCv(R2);
  c.P1 = fromCv(P1);
  c.P2 = fromCv(P2);
  c.Q = fromCv(Q);
  c.X_TL = X_TL;
  const std::string why = c.check();
  if (!why.empty()) {
    throw std::invalid_argument("camera profile \"" + profile.name +
                                "\": the rectified calibration is inconsistent: " + why);
  }
  return c;
}

/// The supersampled pinhole camera at `pose` that covers every raw pixel of a camera with
/// matrix `k` and distortion `d` after undistortion (with a margin for the blur), and the maps
/// from each raw pixel to its place in that camera's image.
render::PinholeCamera lensWarp(const CameraProfile& profile, const Eigen::Matrix3d& k,
                               const std::array<double, 5>& d, const Transform3D& pose,
                               std::array<cv::Mat, 2>& maps) {
  const StereoRigSpec& rig = profile.rig;
  cv::Mat nx(rig.height, rig.width, CV_64F);
  cv::Mat ny(rig.height, rig.width, CV_64F);
  double xmin = std::numeric_limits<double>::infinity();
  double xmax = -xmin;
  double ymin = xmin;
  double ymax = -xmin;
  for (int r = 0; r < rig.height; ++r) {
    for (int col = 0; col < rig.width; ++col) {
      const Eigen::Vector2d xyd((col - k(0, 2)) / k(0, 0), (r - k(1, 2)) / k(1, 1));
      const Eigen::Vector2d xy = undistortPoint(xyd, d);
      nx.at<double>(r, col) = xy.x();
      ny.at<double>(r, col) = xy.y();
      xmin = std::min(xmin, xy.x());
      xmax = std::max(xmax, xy.x());
      ymin = std::min(ymin, xy.y());
      ymax = std::max(ymax, xy.y());
    }
  }
  const double s = profile.supersampling;
  render::PinholeCamera camera;
  camera.fx = s * k(0, 0);
  camera.fy = s * k(1, 1);
  const double margin = std::ceil(3.0 * s * rig.blurSigma) + 2.0;
  camera.cx = margin - camera.fx * xmin;
  camera.cy = margin - camera.fy * ymin;
  camera.width = static_cast<int>(std::ceil(camera.fx * (xmax - xmin) + 2.0 * margin)) + 1;
  camera.height = static_cast<int>(std::ceil(camera.fy * (ymax - ymin) + 2.0 * margin)) + 1;
  camera.near = 0.05;
  camera.far = 10.0;
  camera.X_WC = pose;
  maps[0].create(rig.height, rig.width, CV_32F);
  maps[1].create(rig.height, rig.width, CV_32F);
  for (int r = 0; r < rig.height; ++r) {
    for (int col = 0; col < rig.width; ++col) {
      maps[0].at<float>(r, col) = static_cast<float>(camera.fx * nx.at<double>(r, col) + camera.cx);
      maps[1].at<float>(r, col) = static_cast<float>(camera.fy * ny.at<double>(r, col) + camera.cy);
    }
  }
  return camera;
}

/// For each rectified pixel of projection `p` and rectifying rotation `R`: its ray turned back
/// into the raw camera, distorted and projected with `k` (what cv::initUndistortRectifyMap
/// computes).
std::array<cv::Mat, 2> rectifyMap(const StereoRigSpec& rig, const Eigen::Matrix3d& k,
                                  const std::array<double, 5>& d, const Eigen::Matrix3d& R,
                                  const Eigen::Matrix<double, 3, 4>& p) {
  std::array<cv::Mat, 2> maps;
  maps[0].create(rig.height, rig.width, CV_32F);
  maps[1].create(rig.height, rig.width, CV_32F);
  const Eigen::Matrix3d Rt = R.transpose();
  for (int r = 0; r < rig.height; ++r) {
    for (int col = 0; col < rig.width; ++col) {
      const Eigen::Vector3d ray =
          Rt * Eigen::Vector3d((col - p(0, 2)) / p(0, 0), (r - p(1, 2)) / p(1, 1), 1.0);
      const Eigen::Vector2d xd = distortPoint(ray.head<2>() / ray.z(), d);
      maps[0].at<float>(r, col) = static_cast<float>(k(0, 0) * xd.x() + k(0, 2));
      maps[1].at<float>(r, col) = static_cast<float>(k(1, 1) * xd.y() + k(1, 2));
    }
  }
  return maps;
}

}  // namespace

CameraRig::CameraRig(CameraProfile profile) : profile_(std::move(profile)) {
  const StereoRigSpec& rig = profile_.rig;
  if (rig.width < 16 || rig.height < 16 || !(rig.focal > 0.0) || !(rig.baseline > 0.0) ||
      !(profile_.supersampling >= 1.0)) {
    throw std::invalid_argument("camera profile \"" + profile_.name +
                                "\": image size, focal length, baseline or supersampling out of "
                                "range");
  }
  const Transform3D X_TL = rigCalibration(rig).X_TL;
  const Transform3D X_LR = rightInLeft(profile_);
  rawPoses_ = {X_TL, X_TL * X_LR};
  std::array<Eigen::Matrix3d, 2> K;
  for (int side = 0; side < 2; ++side) {
    const CameraSensorSpec& camera = profile_.cameras[static_cast<std::size_t>(side)];
    K[static_cast<std::size_t>(side)] = cameraMatrix(rig, camera);
    response_[static_cast<std::size_t>(side)] =
        responseMap(rig.width, rig.height, K[static_cast<std::size_t>(side)](0, 2),
                    K[static_cast<std::size_t>(side)](1, 2), profile_.vignetting, camera.exposure);
  }
  if (profile_.alreadyRectified()) {
    calibration_ = rigCalibration(rig);
    const auto [left, right] = rigCameras(calibration_);
    renderCameras_ = {left, right};
    return;
  }

  calibration_ = rectifiedCalibration(profile_, K, X_TL, X_LR);
  const std::array<const Eigen::Matrix<double, 3, 4>*, 2> P{&calibration_.P1, &calibration_.P2};
  const std::array<const Eigen::Matrix3d*, 2> R{&calibration_.R1, &calibration_.R2};
  for (std::size_t side = 0; side < 2; ++side) {
    const auto& d = profile_.cameras[side].distortion;
    renderCameras_[side] = lensWarp(profile_, K[side], d, rawPoses_[side], warpMaps_[side]);
    rectifyMaps_[side] = rectifyMap(rig, K[side], d, *R[side], *P[side]);
  }
}

const Transform3D& CameraRig::rawPose(int side) const {
  return rawPoses_.at(static_cast<std::size_t>(side));
}

const render::PinholeCamera& CameraRig::renderCamera(int side) const {
  return renderCameras_.at(static_cast<std::size_t>(side));
}

render::PinholeCamera CameraRig::rectifiedCamera(int side) const {
  const auto& P = side == 0 ? calibration_.P1 : calibration_.P2;
  const auto& R = side == 0 ? calibration_.R1 : calibration_.R2;
  render::PinholeCamera camera;
  camera.fx = P(0, 0);
  camera.fy = P(1, 1);
  camera.cx = P(0, 2);
  camera.cy = P(1, 2);
  camera.width = calibration_.width;
  camera.height = calibration_.height;
  camera.near = 0.05;
  camera.far = 10.0;
  camera.X_WC = rawPose(side);
  camera.X_WC.linear() = camera.X_WC.linear() * R.transpose();
  return camera;
}

cv::Mat CameraRig::rawImage(int side, const visual::RgbImage& render, Random& noise) const {
  const render::PinholeCamera& camera = renderCamera(side);
  if (render.width != camera.width || render.height != camera.height) {
    throw std::invalid_argument("CameraRig::rawImage: the render is " +
                                std::to_string(render.width) + "x" + std::to_string(render.height) +
                                ", expected " + std::to_string(camera.width) + "x" +
                                std::to_string(camera.height));
  }
  const StereoRigSpec& rig = profile_.rig;
  const cv::Mat rgb(render.height, render.width, CV_8UC3,
                    const_cast<std::uint8_t*>(render.pixels.data()));
  cv::Mat source;  // CV_32FC3, RGB, raw image size
  if (profile_.alreadyRectified()) {
    // Rendered 1:1: the blur on the 8-bit image, exactly as the ideal rig always did.
    cv::Mat blurred;
    if (rig.blurSigma > 0.0) {
      cv::GaussianBlur(rgb, blurred, cv::Size(0, 0), rig.blurSigma, rig.blurSigma,
                       cv::BORDER_REPLICATE);
    } else {
      blurred = rgb;
    }
    blurred.convertTo(source, CV_32F);
  } else {
    cv::Mat linear;
    rgb.convertTo(linear, CV_32F);
    const double sigma = profile_.supersampling * rig.blurSigma;
    if (sigma > 0.0) {
      cv::GaussianBlur(linear, linear, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
    }
    const auto& warp = warpMaps_[static_cast<std::size_t>(side)];
    cv::remap(linear, source, warp[0], warp[1], cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  }
  const CameraSensorSpec& sensor = profile_.cameras[static_cast<std::size_t>(side)];
  const cv::Mat& response = response_[static_cast<std::size_t>(side)];
  const bool mosaic = profile_.bayer != BayerPattern::kNone;
  const double read = rig.noiseSigma;
  const double shot = profile_.shotNoise;
  const auto expose = [&](float value, float factor) {
    const double signal = static_cast<double>(value) * static_cast<double>(factor);
    const double sigma =
        shot > 0.0 ? std::sqrt(read * read + shot * shot * std::max(signal, 0.0)) : read;
    const double v =
        sigma > 0.0 ? sensor.gain * (signal + sigma * noise.normal()) : sensor.gain * signal;
    return static_cast<std::uint8_t>(std::clamp(std::round(v), 0.0, 255.0));
  };
  cv::Mat out(rig.height, rig.width, mosaic ? CV_8UC1 : CV_8UC3);
  for (int r = 0; r < rig.height; ++r) {
    const auto* in = source.ptr<float>(r);
    const auto* factor = response.ptr<float>(r);
    std::uint8_t* o = out.ptr<std::uint8_t>(r);
    for (int col = 0; col < rig.width; ++col) {
      if (mosaic) {
        o[col] = expose(in[3 * col + rggbChannel(r, col)], factor[col]);
      } else {
        for (int k = 0; k < 3; ++k) o[3 * col + k] = expose(in[3 * col + k], factor[col]);
      }
    }
  }
  if (!mosaic) cv::cvtColor(out, out, cv::COLOR_RGB2BGR);
  return out;
}

cv::Mat CameraRig::rectify(int side, const cv::Mat& raw) const {
  cv::Mat bgr;
  if (raw.channels() == 1) {
    // OpenCV names a mosaic by the second row's second and third photosites: RGGB is "BG".
    cv::cvtColor(raw, bgr, cv::COLOR_BayerBG2BGR);
  } else {
    bgr = raw;
  }
  if (profile_.alreadyRectified()) return bgr;
  const auto& maps = rectifyMaps_[static_cast<std::size_t>(side)];
  cv::Mat out;
  cv::remap(bgr, out, maps[0], maps[1], cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar());
  return out;
}

}  // namespace visgrab::generator
