#include "visgrab/vision/baseline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <opencv2/imgproc.hpp>

#include "rw/common/task_pool.hpp"

namespace visgrab::vision {
namespace {

SceneGrasps graspsOf(const database::Database& db, const database::SceneEntry& scene,
                     const BaselineOptions& options) {
  SceneGrasps out;
  out.sceneId = scene.id;
  try {
    const SceneSegmentation s = analyzeScene(db, scene, options);
    out.clusters = static_cast<int>(s.clusters.size());
    out.patches = static_cast<int>(s.patches.size());
    std::vector<int> rank(kGraspTypes.size(), 0);
    for (const CandidateGrasp& c : generateGrasps(s, options.grasps)) {
      grasp::GraspRequest r;
      r.sceneId = scene.id;
      r.method = graspTypeName(c.type);
      char id[32];
      std::snprintf(id, sizeof id, "%s-%02d", graspTypeName(c.type),
                    ++rank[static_cast<std::size_t>(c.type)]);
      r.id = id;
      r.kind = grasp::GraspKind::kContacts;
      r.contacts = c.contacts;
      r.approach = c.approach;
      out.grasps.push_back(std::move(r));
    }
  } catch (const std::exception& e) {
    out.grasps.clear();
    out.error = e.what();
  }
  return out;
}

}  // namespace

SceneSegmentation analyzeScene(const database::Database& db, const database::SceneEntry& scene,
                               const BaselineOptions& options) {
  const cv::Mat left = db.leftImage(scene.id);
  const cv::Mat right = db.rightImage(scene.id);
  const database::StereoCalibration calibration = db.calibration(scene.id);
  // left.png and right.png are the rectified pair: no second rectification.
  return segmentScene(stereoCloud(left, right, calibration, options.stereo, StereoPair::kRectified),
                      options.segmentation);
}

std::vector<SceneGrasps> baselineGrasps(
    const database::Database& db, const std::vector<const database::SceneEntry*>& scenes,
    const BaselineOptions& options, const std::function<void(const BaselineProgress&)>& progress) {
  std::vector<SceneGrasps> results(scenes.size());
  std::mutex progressMutex;
  int done = 0;
  const rw::common::TaskPool pool(
      std::min(options.threads, std::max(1, static_cast<int>(scenes.size()))));
  pool.run(scenes.size(), [&](std::size_t i, int /*worker*/) {
    results[i] = graspsOf(db, *scenes[i], options);
    if (!progress) return;
    std::lock_guard lock(progressMutex);
    progress({++done, static_cast<int>(scenes.size()), scenes[i]->id});
  });
  return results;
}

cv::Mat drawSegmentation(const cv::Mat& left, const SceneSegmentation& scene,
                         const std::vector<CandidateGrasp>& grasps,
                         const database::StereoCalibration& calibration) {
  cv::Mat out;
  if (left.channels() == 1) {
    cv::cvtColor(left, out, cv::COLOR_GRAY2BGR);
  } else {
    out = left.clone();
  }
  const auto& cloud = scene.cloud;
  const int step = cloud.step;
  auto fill = [&](int cell, const cv::Scalar& colour, double alpha) {
    const int r = cell / cloud.width * step, c = cell % cloud.width * step;
    const cv::Rect box(c, r, step, step);
    cv::Mat roi = out(box & cv::Rect(0, 0, out.cols, out.rows));
    cv::addWeighted(roi, 1.0 - alpha, cv::Mat(roi.size(), roi.type(), colour), alpha, 0.0, roi);
  };
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    // Colours spread round the hue circle by the golden angle.
    const double hue = std::fmod(static_cast<double>(p) * 137.508, 360.0);
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue / 2.0, 200, 255)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    const cv::Vec3b v = bgr.at<cv::Vec3b>(0, 0);
    const cv::Scalar colour(v[0], v[1], v[2]);
    const auto& patch = scene.patches[p];
    for (int cell : patch.cells) fill(cell, colour, 0.45);
    for (std::size_t k = 0; k < patch.boundary.size(); ++k)
      fill(patch.boundary[k], patch.edge[k] ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 255, 255), 1.0);
  }
  const Eigen::Matrix3d R_LT = calibration.X_TL.linear().transpose();
  const Eigen::Vector3d t_TL = calibration.X_TL.translation();
  auto project = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d rect = calibration.R1 * (R_LT * (p - t_TL));
    const Eigen::Vector3d u = calibration.P1 * rect.homogeneous();
    return cv::Point(static_cast<int>(std::lround(u.x() / u.z())),
                     static_cast<int>(std::lround(u.y() / u.z())));
  };
  std::vector<int> drawn(kGraspTypes.size(), 0);
  for (const auto& g : grasps) {
    const auto type = static_cast<std::size_t>(g.type);
    const cv::Scalar colour = g.type == GraspType::kS2Ega1   ? cv::Scalar(0, 200, 0)
                              : g.type == GraspType::kS2Ega3 ? cv::Scalar(255, 0, 255)
                                                             : cv::Scalar(255, 255, 0);
    const int radius = drawn[type]++ == 0 ? 6 : 3;
    for (std::size_t i = 0; i < g.contacts.size(); ++i) {
      const cv::Point a = project(g.contacts[i].position);
      cv::circle(out, a, radius, colour, 2, cv::LINE_AA);
      if (drawn[type] == 1) {
        const cv::Point b = project(g.contacts[(i + 1) % g.contacts.size()].position);
        cv::line(out, a, b, colour, 1, cv::LINE_AA);
      }
    }
  }
  return out;
}

}  // namespace visgrab::vision
