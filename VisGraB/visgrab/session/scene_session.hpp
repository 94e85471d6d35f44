#pragma once

#include <memory>
#include <vector>

#include "rw/kinematics/state.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/request/grasp_request.hpp"
#include "visgrab/session/scene_loader.hpp"

namespace visgrab::session {

/// One database scene loaded with one hand to simulate and draw grasps exactly as the benchmark
/// runs them: the dynamic workcell (SceneLoader), the trial setup (trialSetup), the initial
/// state and the grasp resolver with its placement test in this scene.
class SceneSession {
 public:
  /// Loads the scene with `loader`'s hand, which must outlive the session (the loader need not).
  /// @throws as SceneLoader::load; std::invalid_argument if the scene's workcell lacks the
  ///   hand's device, controller or TCP frame.
  SceneSession(const SceneLoader& loader, const database::SceneEntry& entry);

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
  /// The scene as generated: objects at rest, the hand at its mount (the workcell's default
  /// state, where every trial starts).
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

}  // namespace visgrab::session
