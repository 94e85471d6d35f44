#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rw/kinematics/state.hpp"
#include "rw/math/types.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/results/trial_record.hpp"

namespace visgrab::view {

/// A contact between the hand and another body, with the force on that body.
struct ContactForce {
  /// Contact point, world frame, m.
  rw::math::Vector3D point = rw::math::Vector3D::Zero();
  /// Force the hand applies to the other body, world frame, N.
  rw::math::Vector3D force = rw::math::Vector3D::Zero();
  /// The other body.
  rwsim::dynamics::BodyId body;
};

/// One recorded moment of a trial.
struct ReplayFrame {
  /// Simulated time, s (0 = the hand placed, before closing).
  double time = 0.0;
  /// "placed", "close", "lift" or "settle".
  std::string phase;
  /// Poses of every body and the hand's joint values.
  rw::kinematics::State state;
  /// Hand contacts after the step, with the solver's forces.
  std::vector<ContactForce> contacts;
};

/// A grasp trial run again with its trajectory recorded.
struct TrialReplay {
  /// What the trial measured (the same as GraspTrial::run gives: trials are deterministic).
  rwsim::simulator::GraspTrialResult result;
  /// Frames in time order: the placed hand first, then one every `interval` of simulated time,
  /// plus the last step of closing and the last step of all.
  std::vector<ReplayFrame> frames;
  /// The paper's three moments: the hand placed (always 0), the fingers closed (the last step of
  /// closing) and after the lift (the last step). A trial that stopped earlier (in collision,
  /// missed, failed) repeats the last frame it reached.
  std::size_t placed = 0;
  /// See placed.
  std::size_t closed = 0;
  /// See placed.
  std::size_t lifted = 0;
};

/// Runs `trial` for `grasp` from `initial` with a recording observer (the trial's own observer,
/// if any, is not called). Contacts with a force below `minForce` (N) are left out.
/// @throws std::invalid_argument as GraspTrial::run, or for interval <= 0.
TrialReplay replayTrial(const rwsim::simulator::GraspTrial& trial,
                        const rwsim::simulator::GraspParameters& grasp,
                        const rw::kinematics::State& initial, double interval = 0.02,
                        double minForce = 1e-3);

/// True when a replay is not the recorded trial: trials are deterministic, so the run's trial
/// ends with the same outcome at the same simulated time; a difference means another build,
/// hand, database or protocol than the run's.
bool replayDiffers(const results::TrialRecord& record,
                   const rwsim::simulator::GraspTrialResult& replayed);

}  // namespace visgrab::view
