#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "rw/math/types.hpp"
#include "visgrab/database/database_index.hpp"
#include "visgrab/database/database_writer.hpp"
#include "visgrab/database/point_cloud.hpp"
#include "visgrab/database/stereo_calibration.hpp"
#include "visgrab/render/render_result.hpp"

/// The files a generated scene has beside its images (docs/database-format.md): the disparity
/// of the documented matcher, the point cloud reprojected from it, and the ground truth of the
/// rectified left view (depth, instance mask, object poses).
namespace visgrab::generator {

/// Mask value of table pixels in mask.png (0 is the background, object ids are 1..254).
inline constexpr std::uint8_t kMaskTable = 255;

/// One object of a scene as the ground-truth files name it.
struct TruthObject {
  /// Object id (1..254): its value in mask.png.
  int id = 0;
  /// Object name.
  std::string name;
  /// Its instance id in the ground-truth render (render::SceneItem::instanceId).
  std::uint16_t instance = 0;
  /// Settled pose of the object's model frame in the table frame.
  rw::math::Transform3D X_TO = rw::math::Transform3D::Identity();
};

/// A disparity (CV_32F pixels, <= 0 or NaN: none) as disparity.png's pixels: CV_16U,
/// round(disparity * 256), 0 where there is none or it is too large for 16 bits (256 pixels
/// and more: with the default rig, points nearer than 0.38 m, out of the objects' reach).
cv::Mat encodeDisparity(const cv::Mat& disparity);

/// A ground-truth depth (camera z, metres, non-finite: nothing drawn) as depth.png's pixels:
/// CV_16U, round(z / 0.1 mm), 0 where nothing was drawn or z is beyond 6.5535 m.
cv::Mat encodeDepth(const render::DepthImage& depth);

/// A ground-truth instance-id image as mask.png's pixels: CV_8U, 0 for the background (id 0),
/// kMaskTable for `tableInstance`, the object id for each object's instance.
/// @throws std::invalid_argument for an id that is none of these or an object id outside
/// 1..254.
cv::Mat encodeInstanceMask(const render::InstanceIdImage& ids, std::uint16_t tableInstance,
                           const std::vector<TruthObject>& objects);

/// The point cloud of cloud.ply: each pixel (u, v) with u and v even and a disparity d > 0 is
/// reprojected as cv::reprojectImageTo3D does ((X, Y, Z, W) = Q (u, v, d, 1), point (X, Y, Z) /
/// W) into the rectified left camera frame, and kept if it lies in the workspace box of the
/// table frame (|x|, |y| <= 0.3 m, -0.02 m <= z <= 0.35 m). Points less than 5 mm above the
/// table, or on pixels without texture (vision::textureMask: SGBM's guesses, the plain table's
/// scatter), are kept only where u and v are multiples of 8: the table is most of the image, and
/// this keeps the file within its budget (docs/database-format.md). Colour: the left image's
/// pixel. The header comments name the frame, the rule and the frame's pose in the table frame.
/// @pre leftBgr is CV_8UC3 of the disparity's size.
database::PointCloud cloudFromDisparity(const cv::Mat& disparity, const cv::Mat& leftBgr,
                                        const database::StereoCalibration& calibration);

/// poses.yml as OpenCV FileStorage YAML text: the rectified left camera's pose in the table
/// frame (X_table_camera) and per object its id, name, X_table_object and X_camera_object
/// (4x4, metres).
std::string posesYaml(const database::StereoCalibration& calibration,
                      const std::vector<TruthObject>& objects);

/// Writes a scene's disparity.png, cloud.ply, depth.png, mask.png and poses.yml (the paths
/// `files` names, relative to writer's folder; an empty path is skipped), each atomically.
/// The disparity is vision::computeDisparity with default vision::StereoOptions on the
/// rectified pair. `truth` is the render of the rectified left view with depth and ids.
/// Deterministic. @throws std::invalid_argument for sizes that do not match the calibration
/// or unknown instance ids, std::runtime_error (rw::common::WriteError) if a file cannot be
/// written.
void writeSceneProducts(const cv::Mat& leftRectified, const cv::Mat& rightRectified,
                        const database::StereoCalibration& calibration,
                        const render::RenderResult& truth, std::uint16_t tableInstance,
                        const std::vector<TruthObject>& objects, const database::SceneFiles& files,
                        const database::DatabaseWriter& writer);

}  // namespace visgrab::generator
