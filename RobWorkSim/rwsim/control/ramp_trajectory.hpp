#pragma once

#include "rw/math/types.hpp"

namespace rwsim::control {

/// A 1-D move of length `distance` >= 0 from rest to rest with a trapezoidal velocity profile:
/// accelerate at `acceleration`, cruise at most at `velocity`, decelerate (a triangle when the
/// move is too short to reach the cruise speed).
class RampProfile {
 public:
  /// The fastest profile within the limits. @throws std::invalid_argument unless distance >= 0
  /// and velocity, acceleration > 0 (all finite).
  RampProfile(double distance, double velocity, double acceleration);
  /// The same move stretched to last `duration` (>= the fastest duration) with the same
  /// acceleration and a lower cruise speed. @throws std::invalid_argument if it cannot.
  RampProfile stretched(double duration) const;

  /// Total time, s.
  double duration() const { return duration_; }
  /// Cruise speed actually reached.
  double peakVelocity() const { return peak_; }
  /// Distance covered at time t (clamped to [0, duration]).
  double position(double t) const;
  /// Speed at time t (0 outside [0, duration]).
  double velocity(double t) const;

 private:
  RampProfile() = default;
  double distance_ = 0.0;
  double acceleration_ = 1.0;
  double peak_ = 0.0;
  double rampTime_ = 0.0;
  double duration_ = 0.0;
};

/// Limits of a Cartesian ramp; the defaults are RobWork's BodyController's (reference §4.2:
/// 0.5 m/s, 1.0 m/s^2, 0.4 rad/s, 1.0 rad/s^2).
struct RampLimits {
  /// Largest linear speed, m/s.
  double linearVelocity = 0.5;
  /// Linear acceleration, m/s^2.
  double linearAcceleration = 1.0;
  /// Largest angular speed, rad/s.
  double angularVelocity = 0.4;
  /// Angular acceleration, rad/s^2.
  double angularAcceleration = 1.0;
};

/// A straight-line, constant-axis move between two poses: the position follows a RampProfile
/// along the segment, the orientation turns about the fixed axis of X_start^-1 X_end with its own
/// RampProfile, both stretched to end together. Times are relative to the start.
class RampTrajectory {
 public:
  /// @throws std::invalid_argument for non-positive or non-finite limits.
  RampTrajectory(const rw::math::Transform3D& X_start, const rw::math::Transform3D& X_end,
                 const RampLimits& limits = {});
  /// Total time, s.
  double duration() const { return duration_; }
  /// Pose at time t (X_start before 0, X_end after duration()).
  rw::math::Transform3D pose(double t) const;
  /// Linear velocity of the moving frame's origin at time t (world), m/s.
  rw::math::Vector3D linearVelocity(double t) const;
  /// Angular velocity at time t (world), rad/s.
  rw::math::Vector3D angularVelocity(double t) const;
  /// The end pose.
  const rw::math::Transform3D& end() const { return end_; }

 private:
  rw::math::Transform3D start_;
  rw::math::Transform3D end_;
  rw::math::Vector3D direction_ = rw::math::Vector3D::Zero();
  rw::math::Vector3D axis_ = rw::math::Vector3D::UnitZ();
  RampProfile linear_;
  RampProfile angular_;
  double duration_ = 0.0;
};

/// A twist: linear velocity of a frame's origin and angular velocity, both in world coordinates.
struct Twist {
  /// m/s.
  rw::math::Vector3D linear = rw::math::Vector3D::Zero();
  /// rad/s.
  rw::math::Vector3D angular = rw::math::Vector3D::Zero();
};

/// The constant twist that moves X_now to X_next in dt (RobWork's BodyController step: the
/// velocity needed to reach the trajectory's next pose). @throws std::invalid_argument if dt <= 0.
Twist twistToReach(const rw::math::Transform3D& X_now, const rw::math::Transform3D& X_next,
                   double dt);

}  // namespace rwsim::control
