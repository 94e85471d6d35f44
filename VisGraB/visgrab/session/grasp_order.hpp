#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/database/database.hpp"
#include "visgrab/request/grasp_request.hpp"
#include "visgrab/results/trial_record.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace visgrab::session {

/// A grasp in the benchmark's order: its request and its rank among its scene's grasps of its
/// method (from 0, in file order; trials.csv's rank column).
struct RankedGrasp {
  /// The grasp as read (owned by the caller's request list).
  const grasp::GraspRequest* request = nullptr;
  /// See RankedGrasp.
  int rank = 0;
};

/// One scene's grasps in the benchmark's order: methods in `GraspOrder::methods` order, then
/// rank; trials.csv lists a scene's trials in this order.
struct SceneGraspList {
  /// The scene.
  const database::SceneEntry* entry = nullptr;
  /// Its grasps (empty: none in the grasp files).
  std::vector<RankedGrasp> grasps;
};

/// How the benchmark orders the grasps of a run.
struct GraspOrder {
  /// The methods in the order first seen among the grasps of the selected scenes (run.csv).
  std::vector<std::string> methods;
  /// One list per selected scene, in the selection's order.
  std::vector<SceneGraspList> scenes;
  /// The requests that name no scene of the database, in file order.
  std::vector<const grasp::GraspRequest*> unknownScene;
};

/// The benchmark's order of `requests` over the `selected` scenes of `db` (selectScenes):
/// grouped by scene, ranked per (scene, method) in file order, methods in the order first seen.
/// Requests of scenes not selected are left out. The runner runs and writes trials in this
/// order, and `visgrab render --grasp N` and the viewer count grasps in it. `requests` must
/// outlive the result.
GraspOrder benchmarkOrder(const database::Database& db,
                          const std::vector<const database::SceneEntry*>& selected,
                          const std::vector<grasp::GraspRequest>& requests);

/// A grasp of one scene with its trial record from a results folder, if there is one.
struct SceneGrasp {
  /// The grasp as read from its file.
  grasp::GraspRequest request;
  /// Its rank among the scene's grasps of its method (RankedGrasp::rank).
  int rank = 0;
  /// Its row of trials.csv (nullopt: not run, or no results given).
  std::optional<results::TrialRecord> record;
};

/// The grasps of `entry` among `grasps` in the benchmark's order (benchmarkOrder) over the
/// scenes `results` covered, or over all scenes of `db` without results (a run without a
/// scene filter); each with its trial record from `results` (nullptr: none). So the N-th grasp
/// is the scene's N-th row of trials.csv, and with one method the grasp of rank N - 1.
std::vector<SceneGrasp> sceneGrasps(const database::Database& db, const database::SceneEntry& entry,
                                    const taskio::GraspFileContents& grasps,
                                    const results::RunResults* results);

/// The grasp `spec` names among `grasps`: a grasp id, or a number N for the N-th grasp (from 1)
/// in that order; with a non-empty `method`, only that method's grasps count.
/// @throws std::invalid_argument naming the choices when there is no such grasp, or when an id
///   is ambiguous across methods.
const SceneGrasp& selectGrasp(const std::vector<SceneGrasp>& grasps, std::string_view spec,
                              std::string_view method = {});

}  // namespace visgrab::session
