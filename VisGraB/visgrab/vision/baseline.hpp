#pragma once

#include <functional>
#include <string>
#include <vector>

#include "visgrab/database/database.hpp"
#include "visgrab/request/grasp_request.hpp"
#include "visgrab/vision/ega.hpp"
#include "visgrab/vision/segmentation.hpp"
#include "visgrab/vision/stereo.hpp"

namespace visgrab::vision {

/// Every setting of the baseline method, with the defaults `visgrab baseline` uses.
struct BaselineOptions {
  /// Dense stereo.
  StereoOptions stereo;
  /// Table, clusters, patches.
  SegmentationOptions segmentation;
  /// Grasp synthesis and ranking.
  GraspOptions grasps;
  /// Worker threads over scenes (>= 1). The grasps do not depend on it.
  int threads = 1;
};

/// The baseline's view of one scene (for tests, the viewer and debugging).
/// @throws database::DatabaseError, database::CalibrationError (images or calibration
/// unreadable), std::runtime_error (no table plane), std::invalid_argument (sizes).
SceneSegmentation analyzeScene(const database::Database& db, const database::SceneEntry& scene,
                               const BaselineOptions& options);

/// What the baseline made of one scene.
struct SceneGrasps {
  /// The scene's id.
  std::string sceneId;
  /// Contact grasps, method = the grasp type's name, id "<type>-<rank>" (rank from 1, best
  /// first), types in kGraspTypes order.
  std::vector<grasp::GraspRequest> grasps;
  /// Objects (clusters) and surface patches found.
  int clusters = 0;
  /// See clusters.
  int patches = 0;
  /// Why the scene has no grasps when it could not be analysed (empty otherwise).
  std::string error;
};

/// Progress of baselineGrasps: scenes done of total, the last scene finished.
struct BaselineProgress {
  /// Scenes finished.
  int done = 0;
  /// Scenes to do.
  int total = 0;
  /// Id of the scene finished last.
  std::string lastId;
};

/// The baseline on `scenes` in parallel (options.threads). A scene that cannot be analysed gets
/// no grasps and its error; the others go on. Results in the order of `scenes`; the same for
/// any thread count. `progress` (if set) is called from one thread at a time.
std::vector<SceneGrasps> baselineGrasps(
    const database::Database& db, const std::vector<const database::SceneEntry*>& scenes,
    const BaselineOptions& options,
    const std::function<void(const BaselineProgress&)>& progress = {});

/// A picture of what the baseline saw, for checking it by eye: the left image, each patch
/// tinted in its own colour, patch boundaries where the object ends in red and creases in
/// yellow, and the grasps' contacts (projected with the calibration) as circles coloured by
/// type (s2EGA1 green, s2EGA3 magenta, s3EGA1 cyan), the best grasp of each type larger.
cv::Mat drawSegmentation(const cv::Mat& left, const SceneSegmentation& scene,
                         const std::vector<CandidateGrasp>& grasps,
                         const database::StereoCalibration& calibration);

}  // namespace visgrab::vision
