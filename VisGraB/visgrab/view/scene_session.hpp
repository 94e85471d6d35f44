#pragma once

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "rw/kinematics/state.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_request.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/trial_record.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace visgrab::view {

/// One database scene loaded to simulate and draw grasps with one hand, exactly as the
/// benchmark runs them (same dynamic workcell, trial setup and initial state).
class SceneSession {
 public:
  /// Loads the scene's dynamic workcell. `hand` must outlive the session.
  /// @throws rw::common::LoadError for an unreadable scene, std::invalid_argument if the
  ///   scene's workcell lacks the hand's device, controller or TCP frame.
  SceneSession(const database::SceneEntry& entry, const grasp::HandGraspSetup& hand);

  /// The scene.
  const database::SceneEntry& entry() const { return entry_; }
  /// The hand's grasp description.
  const grasp::HandGraspSetup& hand() const { return *hand_; }
  /// The scene's dynamic workcell.
  const rwsim::dynamics::DynamicWorkCell& dynamicWorkcell() const { return *dwc_; }
  /// Its workcell.
  const rw::models::WorkCell& workcell() const { return dwc_->workcell(); }
  /// Trials in this scene (GraspTrial::run, placedState).
  const rwsim::simulator::GraspTrial& trial() const { return *trial_; }
  /// The scene as generated: objects at rest, the hand at its mount.
  const rw::kinematics::State& initialState() const { return initial_; }
  /// The frames carrying geometry of the rigid bodies that are not the hand (the objects).
  const std::vector<rw::kinematics::FrameId>& objectFrames() const { return objectFrames_; }
  /// grasp::resolve of `request` with this session's hand, contact grasps placed in this scene
  /// (as the benchmark places them).
  grasp::ResolvedGrasp resolve(const grasp::GraspRequest& request) const;

 private:
  database::SceneEntry entry_;
  const grasp::HandGraspSetup* hand_;
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc_;
  std::unique_ptr<rwsim::simulator::GraspTrial> trial_;
  rw::kinematics::State initial_;
  std::vector<rw::kinematics::FrameId> objectFrames_;
};

/// A grasp of one scene with its trial record from a results folder, if there is one.
struct SceneGrasp {
  /// The grasp as read from its file.
  grasp::GraspRequest request;
  /// Its row of trials.csv (nullopt: not run, or no results given).
  std::optional<results::TrialRecord> record;
};

/// The grasps of `entry` among `grasps`, ordered as the benchmark orders them (methods in the
/// order first seen, or `results`' method order when given; then file order), each with its
/// trial record from `results` (nullptr: none).
std::vector<SceneGrasp> sceneGrasps(const database::Database& db, const database::SceneEntry& entry,
                                    const taskio::GraspFileContents& grasps,
                                    const results::RunResults* results);

/// The grasp `spec` names among `grasps`: a grasp id, or a number N for the N-th grasp (from 1)
/// in that order; with a non-empty `method`, only that method's grasps count.
/// @throws std::invalid_argument naming the choices when there is no such grasp, or when an id
///   is ambiguous across methods.
const SceneGrasp& selectGrasp(const std::vector<SceneGrasp>& grasps, std::string_view spec,
                              std::string_view method = {});

}  // namespace visgrab::view
