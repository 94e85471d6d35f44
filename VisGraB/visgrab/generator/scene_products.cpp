#include "visgrab/generator/scene_products.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <stdexcept>

#include "visgrab/database/atomic_file.hpp"
#include "visgrab/vision/stereo.hpp"

namespace visgrab::generator {

namespace {

using rw::math::Transform3D;

// The cloud's workspace box in the table frame and its sampling (cloudFromDisparity).
constexpr double kBoxHalfSide = 0.3;
constexpr double kBoxBottom = -0.02;
constexpr double kBoxTop = 0.35;
constexpr double kTableLevel = 0.005;
constexpr int kDenseStep = 2;
constexpr int kSparseStep = 8;

cv::Mat toCv(const Transform3D& X) {
  const Eigen::Matrix4d& m = X.matrix();
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}

std::string matrixText(const Eigen::Matrix4d& m) {
  std::string out;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.9g", m(r, c));
      out += (out.empty() ? "" : " ") + std::string(buffer);
    }
  }
  return out;
}

void checkSize(const cv::Mat& image, const database::StereoCalibration& calibration,
               const char* what) {
  if (image.cols != calibration.width || image.rows != calibration.height) {
    throw std::invalid_argument(
        std::string("scene products: the ") + what + " is " + std::to_string(image.cols) + "x" +
        std::to_string(image.rows) + ", the calibration's images are " +
        std::to_string(calibration.width) + "x" + std::to_string(calibration.height));
  }
}

}  // namespace

cv::Mat encodeDisparity(const cv::Mat& disparity) {
  CV_Assert(disparity.type() == CV_32FC1);
  cv::Mat out(disparity.size(), CV_16UC1, cv::Scalar(0));
  for (int r = 0; r < disparity.rows; ++r) {
    const auto* in = disparity.ptr<float>(r);
    auto* o = out.ptr<std::uint16_t>(r);
    for (int c = 0; c < disparity.cols; ++c) {
      if (!(in[c] > 0.0f)) continue;  // none (negative or NaN)
      const double v = std::round(static_cast<double>(in[c]) * database::kDisparityScale);
      if (v <= 65535.0) o[c] = static_cast<std::uint16_t>(std::max(v, 1.0));
    }
  }
  return out;
}

cv::Mat encodeDepth(const render::DepthImage& depth) {
  cv::Mat out(depth.height, depth.width, CV_16UC1, cv::Scalar(0));
  for (int r = 0; r < depth.height; ++r) {
    auto* o = out.ptr<std::uint16_t>(r);
    for (int c = 0; c < depth.width; ++c) {
      const double z = depth.at(r, c);
      if (!std::isfinite(z) || z <= 0.0) continue;
      const double v = std::round(z / database::kDepthUnit);
      if (v <= 65535.0) o[c] = static_cast<std::uint16_t>(v);
    }
  }
  return out;
}

cv::Mat encodeInstanceMask(const render::InstanceIdImage& ids, std::uint16_t tableInstance,
                           const std::vector<TruthObject>& objects) {
  std::map<std::uint16_t, std::uint8_t> value{{0, 0}, {tableInstance, kMaskTable}};
  for (const TruthObject& o : objects) {
    if (o.id < 1 || o.id >= kMaskTable) {
      throw std::invalid_argument("scene products: object id " + std::to_string(o.id) +
                                  " does not fit the 8-bit mask (1..254)");
    }
    value[o.instance] = static_cast<std::uint8_t>(o.id);
  }
  cv::Mat out(ids.height, ids.width, CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < ids.height; ++r) {
    auto* o = out.ptr<std::uint8_t>(r);
    for (int c = 0; c < ids.width; ++c) {
      const auto it = value.find(ids.at(r, c));
      if (it == value.end()) {
        throw std::invalid_argument("scene products: instance id " + std::to_string(ids.at(r, c)) +
                                    " at pixel (" + std::to_string(c) + ", " + std::to_string(r) +
                                    ") is neither the table's nor an object's");
      }
      o[c] = it->second;
    }
  }
  return out;
}

database::PointCloud cloudFromDisparity(const cv::Mat& disparity, const cv::Mat& leftBgr,
                                        const database::StereoCalibration& calibration) {
  CV_Assert(disparity.type() == CV_32FC1 && leftBgr.type() == CV_8UC3 &&
            leftBgr.size() == disparity.size());
  const Transform3D X_TC = calibration.rectifiedLeftPose();
  const cv::Mat textured = vision::textureMask(leftBgr, vision::StereoOptions{});
  database::PointCloud cloud;
  cloud.comments = {
      "VisGraB point cloud: metres, in the rectified left camera frame (x right, y down, z "
      "forward)",
      "points: (X, Y, Z, W) = Q (u, v, d, 1) as cv::reprojectImageTo3D, from disparity.png and "
      "calibration.yml's Q",
      "sampling: u, v multiples of " + std::to_string(kDenseStep) +
          ", in the table-frame box |x|,|y| <= 0.3, -0.02 <= z <= 0.35 m; points under 5 mm "
          "above the table or on untextured pixels only at u, v multiples of " +
          std::to_string(kSparseStep),
      "X_table_camera (row-major 4x4, the frame's pose in the table frame): " +
          matrixText(X_TC.matrix())};
  for (int v = 0; v < disparity.rows; v += kDenseStep) {
    const auto* row = disparity.ptr<float>(v);
    for (int u = 0; u < disparity.cols; u += kDenseStep) {
      const float d = row[u];
      if (!(d > 0.0f)) continue;
      const Eigen::Vector4d h = calibration.Q * Eigen::Vector4d(u, v, d, 1.0);
      if (std::abs(h.w()) < 1e-12) continue;
      const Eigen::Vector3d p_C = h.head<3>() / h.w();
      const Eigen::Vector3d p_T = X_TC * p_C;
      if (std::abs(p_T.x()) > kBoxHalfSide || std::abs(p_T.y()) > kBoxHalfSide ||
          p_T.z() < kBoxBottom || p_T.z() > kBoxTop) {
        continue;
      }
      const bool dense = p_T.z() >= kTableLevel && textured.at<std::uint8_t>(v, u) != 0;
      if (!dense && (u % kSparseStep != 0 || v % kSparseStep != 0)) continue;
      const auto& bgr = leftBgr.at<cv::Vec3b>(v, u);
      cloud.points.emplace_back(p_C.cast<float>());
      cloud.colours.push_back({bgr[2], bgr[1], bgr[0]});
    }
  }
  return cloud;
}

std::string posesYaml(const database::StereoCalibration& calibration,
                      const std::vector<TruthObject>& objects) {
  const Transform3D X_TC = calibration.rectifiedLeftPose();
  cv::FileStorage fs(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs.writeComment(
      "VisGraB ground-truth poses: 4x4 transforms in metres; camera = the rectified left camera "
      "(x right, y down, z forward), table = the scene's world frame (z up)");
  fs << "X_table_camera" << toCv(X_TC);
  fs << "objects"
     << "[";
  for (const TruthObject& o : objects) {
    fs << "{"
       << "id" << o.id << "name" << o.name;
    fs << "X_table_object" << toCv(o.X_TO);
    fs << "X_camera_object" << toCv(X_TC.inverse() * o.X_TO);
    fs << "}";
  }
  fs << "]";
  return fs.releaseAndGetString();
}

void writeSceneProducts(const cv::Mat& leftRectified, const cv::Mat& rightRectified,
                        const database::StereoCalibration& calibration,
                        const render::RenderResult& truth, std::uint16_t tableInstance,
                        const std::vector<TruthObject>& objects, const database::SceneFiles& files,
                        const database::DatabaseWriter& writer) {
  checkSize(leftRectified, calibration, "left image");
  checkSize(rightRectified, calibration, "right image");
  if (truth.depth.width != calibration.width || truth.depth.height != calibration.height ||
      truth.instanceIds.width != calibration.width ||
      truth.instanceIds.height != calibration.height) {
    throw std::invalid_argument(
        "scene products: the ground-truth render has no depth and ids of the calibration's size");
  }
  if (!files.disparity.empty() || !files.pointCloud.empty()) {
    const cv::Mat stored = encodeDisparity(vision::computeDisparity(
        leftRectified, rightRectified, calibration, vision::StereoOptions{}));
    if (!files.disparity.empty())
      database::writeImageAtomically(writer.path(files.disparity), stored,
                                     database::PngCompression::kRle);
    if (!files.pointCloud.empty()) {
      // From the stored disparities (SGBM's 1/16 pixel steps survive the 1/256 scale exactly;
      // those that do not fit are none in both files).
      cv::Mat disparity;
      stored.convertTo(disparity, CV_32F, 1.0 / database::kDisparityScale);
      database::writeFileAtomically(
          writer.path(files.pointCloud),
          database::pointCloudToPly(cloudFromDisparity(disparity, leftRectified, calibration)));
    }
  }
  if (!files.depth.empty()) {
    database::writeImageAtomically(writer.path(files.depth), encodeDepth(truth.depth));
  }
  if (!files.mask.empty()) {
    database::writeImageAtomically(writer.path(files.mask),
                                   encodeInstanceMask(truth.instanceIds, tableInstance, objects),
                                   database::PngCompression::kRle);
  }
  if (!files.poses.empty()) {
    database::writeFileAtomically(writer.path(files.poses), posesYaml(calibration, objects));
  }
}

}  // namespace visgrab::generator
