#pragma once

#include <string>
#include <vector>

#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"

namespace visgrab::generator {

/// When a dropped scene counts as settled.
struct SettleOptions {
  /// Never judged before this, s.
  double minTime = 0.3;
  /// Given up after this, s.
  double maxTime = 4.0;
  /// Every object slower than this (m/s) ...
  double restLinearSpeed = 1e-3;
  /// ... and turning slower than this (rad/s) ...
  double restAngularSpeed = 0.02;
  /// ... for this long, s.
  double restDuration = 0.2;
};

/// How settling ended.
struct SettleResult {
  /// World pose of each object's frame at the end, in the order asked for.
  std::vector<rw::math::Transform3D> X_WO;
  /// True when all objects were at rest (SettleOptions) before maxTime.
  bool atRest = false;
  /// Simulated time, s.
  double time = 0.0;
  /// Deepest penetration of an object into the table or another object in the last step, m.
  double maxPenetration = 0.0;
  /// Fastest object speed in the last step, m/s.
  double maxSpeed = 0.0;
  /// Why settling failed (empty when the simulation ran); a failed step ends settling.
  std::string failure;
};

/// Lets the rigid bodies named `objects` fall and come to rest in `dwc` (from its default
/// state), with the project's simulator. Deterministic.
/// @throws std::invalid_argument if a name is not a rigid body of `dwc`.
SettleResult settle(const rwsim::dynamics::DynamicWorkCell& dwc,
                    const std::vector<std::string>& objects, const SettleOptions& options = {});

}  // namespace visgrab::generator
