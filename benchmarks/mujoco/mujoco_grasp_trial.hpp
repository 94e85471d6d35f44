#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mujoco/mjcf_export.hpp"
#include "rw/kinematics/state.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/simulator/grasp_trial.hpp"

struct mjModel_;
struct mjData_;

namespace visgrab::mujoco {

/// What a MuJoCo trial measured.
struct MujocoTrialResult {
  /// Outcome (kStable, kSlipped, kDropped, kMissed, kSimulationFailure or kTimeout).
  rwsim::simulator::GraspOutcome outcome = rwsim::simulator::GraspOutcome::kSimulationFailure;
  /// Simulated time used, s.
  double simulatedTime = 0.0;
  /// Drift of the object against the hand during the lift, m (when held).
  double drift = 0.0;
  /// Steps taken.
  long steps = 0;
  /// Sum over the steps of the constraint rows (mjData::nefc).
  long constraintRows = 0;
  /// Sum over the steps of the solver iterations.
  long solverIterations = 0;
  /// Free text about the outcome.
  std::string detail;
};

/// The project's grasp trial (rwsim::simulator::GraspTrial's phases and settings) on a dynamic
/// workcell exported to MJCF, run with MuJoCo's C API. The hand is placed by the project's own
/// GraspTrial::placedState(); closing commands the joint velocities of the dwc's PD controller
/// (rwsim::control::PDController), realised each step by motor torques within tauMax (the
/// project's velocity motors with a force limit; see driveJoints() in the source); the rest
/// detection, the lift ramp (rwsim::control::RampTrajectory and twistToReach, realised by the
/// base's slide motors), settle time and classification (drift of the object against the hand,
/// slip threshold) are GraspTrial's. No in-collision check and no Q_GWS. Owns its mjModel and
/// mjData: one trial at a time per object. Sets MuJoCo's global warning handler to ignore
/// warnings (they are counted in mjData and end a trial as kSimulationFailure).
class MujocoGraspTrial {
 public:
  /// Compiles `model` (exportMjcf(dwc)) and resolves the hand's names.
  /// @throws std::runtime_error with MuJoCo's message if the model does not compile;
  /// std::invalid_argument like GraspTrial's constructor, or if the hand's base is not exported
  /// as a kinematic body with slides.
  MujocoGraspTrial(const rwsim::dynamics::DynamicWorkCell& dwc, const MjcfModel& model,
                   rwsim::simulator::GraspTrialSetup setup);
  ~MujocoGraspTrial();
  MujocoGraspTrial(const MujocoGraspTrial&) = delete;
  MujocoGraspTrial& operator=(const MujocoGraspTrial&) = delete;

  /// Places the hand, closes, lifts and classifies. `initial` gives the objects' poses.
  /// @throws std::invalid_argument like GraspTrial::run(), or if the placement turns a kinematic
  /// body (its slides cannot).
  MujocoTrialResult run(const rwsim::simulator::GraspParameters& grasp,
                        const rw::kinematics::State& initial);

  /// The compiled model.
  const mjModel_& model() const { return *m_; }
  /// The MuJoCo body id of each dwc body (index as DynamicWorkCell::bodies()).
  const std::vector<int>& bodyIds() const { return bodyIds_; }

 private:
  struct Run;
  void setState(const rw::kinematics::State& state);
  void driveJoints(const rw::math::Q& handVelocity, const rw::math::Vector3D& baseVelocity);

  const rwsim::dynamics::DynamicWorkCell& dwc_;
  rwsim::simulator::GraspTrialSetup setup_;
  rwsim::simulator::GraspTrial placement_;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  std::vector<int> bodyIds_;          // per dwc body
  std::vector<int> dwcBodyOf_;        // per MuJoCo body: dwc body index or -1
  std::vector<int> jointQposAdr_;     // per dwc body: its joint's qpos address or -1
  std::vector<bool> isHandBody_;      // per dwc body
  std::vector<int> handQposAdr_;      // per active hand joint
  std::vector<int> handDofAdr_;       // per active hand joint
  std::vector<int> handActuators_;    // per active hand joint
  rw::math::Q restSpeed_;             // per active hand joint (GraspTrial's, by joint type)
  std::vector<int> slideQposAdr_[3];  // per dwc body, x y z (-1 if none)
  std::vector<int> drivenDofs_;       // the hand's active joints, then the base's slides
  std::vector<int> drivenActuators_;  // their motors
  std::vector<double> fullM_;         // nv x nv, scratch
  std::vector<rw::math::Vector3D> exportedPosition_;  // per dwc body, at qpos0
  std::vector<Eigen::Matrix3d> exportedRotation_;     // per dwc body, at qpos0
};

}  // namespace visgrab::mujoco
