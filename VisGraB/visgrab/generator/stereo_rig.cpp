#include "visgrab/generator/stereo_rig.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace visgrab::generator {

using rw::math::Transform3D;
using rw::math::Vector3D;

Transform3D lookAt(const Vector3D& eye, const Vector3D& target) {
  const Vector3D z = target - eye;
  const Vector3D x = z.cross(Vector3D::UnitZ());  // horizontal, to the right of the view
  if (z.norm() < 1e-12 || x.norm() < 1e-9 * z.norm()) {
    throw std::invalid_argument("lookAt: the camera must not look straight up or down");
  }
  const Vector3D zc = z.normalized();
  const Vector3D xc = x.normalized();
  const Vector3D yc = zc.cross(xc);  // downwards in the image
  rw::math::Rotation3D R;
  R.col(0) = xc;
  R.col(1) = yc;
  R.col(2) = zc;
  return rw::math::makeTransform(R, eye);
}

database::StereoCalibration rigCalibration(const StereoRigSpec& spec) {
  const Transform3D X_TC = lookAt(spec.eye, spec.target);
  Transform3D X_TL = X_TC;
  X_TL.translate(Vector3D(-0.5 * spec.baseline, 0.0, 0.0));
  const double cx = 0.5 * (spec.width - 1);
  const double cy = 0.5 * (spec.height - 1);
  return database::idealRectifiedRig(spec.focal, spec.focal, cx, cy, spec.baseline, spec.width,
                                     spec.height, X_TL);
}

std::pair<render::PinholeCamera, render::PinholeCamera> rigCameras(
    const database::StereoCalibration& calibration) {
  render::PinholeCamera left;
  left.fx = calibration.P1(0, 0);
  left.fy = calibration.P1(1, 1);
  left.cx = calibration.P1(0, 2);
  left.cy = calibration.P1(1, 2);
  left.width = calibration.width;
  left.height = calibration.height;
  left.near = 0.05;
  left.far = 10.0;
  left.X_WC = calibration.X_TL;
  render::PinholeCamera right = left;
  right.cx = calibration.P2(0, 2);
  right.cy = calibration.P2(1, 2);
  right.X_WC.translate(Vector3D(calibration.baseline(), 0.0, 0.0));
  return {left, right};
}

void addSensorEffects(visual::RgbImage& image, const StereoRigSpec& spec, Random& random) {
  if (image.empty()) return;
  cv::Mat mat(image.height, image.width, CV_8UC3, image.pixels.data());
  if (spec.blurSigma > 0.0) {
    cv::Mat blurred;
    cv::GaussianBlur(mat, blurred, cv::Size(0, 0), spec.blurSigma, spec.blurSigma,
                     cv::BORDER_REPLICATE);
    blurred.copyTo(mat);
  }
  if (spec.noiseSigma <= 0.0) return;
  for (std::uint8_t& p : image.pixels) {
    const double v = std::round(p + spec.noiseSigma * random.normal());
    p = static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0));
  }
}

}  // namespace visgrab::generator
