#pragma once

#include "rw/math/types.hpp"

namespace rwsim::control {

/// RobWork's PDController for joint motors with a velocity interface (reference §8.5): each
/// update, with e = q_target - q, the commanded joint velocity is
///   v = v_target + P e + D (e - e_prev) / dt
/// (no D term on the first update after reset). The output goes to velocity motors whose force
/// limit bounds the torque, so P has units 1/s and D is dimensionless time (s).
/// Optionally the command is clamped to per-joint speed limits (RobWork does not clamp).
class PDController {
 public:
  /// Gains per DOF. @throws std::invalid_argument if the sizes differ or a gain is negative or
  /// not finite.
  PDController(const Eigen::VectorXd& p, const Eigen::VectorXd& d);

  /// Number of joints controlled.
  int dof() const { return static_cast<int>(p_.size()); }
  /// Proportional gains (1/s).
  const Eigen::VectorXd& p() const { return p_; }
  /// Derivative gains (s).
  const Eigen::VectorXd& d() const { return d_; }

  /// Sets the target configuration with zero target velocity (keeps the derivative history, as
  /// RobWork does). @throws std::invalid_argument on a size mismatch.
  void setTarget(const rw::math::Q& q);
  /// Sets the target configuration and velocity. @throws std::invalid_argument on a size mismatch.
  void setTarget(const rw::math::Q& q, const rw::math::Q& velocity);
  /// The target configuration.
  const rw::math::Q& target() const { return target_; }
  /// The target velocity.
  const rw::math::Q& targetVelocity() const { return targetVelocity_; }

  /// Clamps every command to |v_i| <= limits_i (infinite entries do not clamp; empty: no clamp).
  /// @throws std::invalid_argument on a size mismatch or a negative/NaN limit.
  void setVelocityLimits(const rw::math::Q& limits);

  /// Holds `q`: target = q, target velocity 0, derivative history cleared.
  /// @throws std::invalid_argument on a size mismatch.
  void reset(const rw::math::Q& q);

  /// One control update at the measured configuration `q`, `dt` seconds after the previous one;
  /// returns the joint velocities to command. @throws std::invalid_argument on a size mismatch
  /// or dt <= 0.
  rw::math::Q update(const rw::math::Q& q, double dt);

 private:
  void checkSize(const rw::math::Q& q, const char* what) const;

  Eigen::VectorXd p_;
  Eigen::VectorXd d_;
  rw::math::Q target_;
  rw::math::Q targetVelocity_;
  rw::math::Q velocityLimits_;
  rw::math::Q lastError_;
  bool hasLastError_ = false;
};

}  // namespace rwsim::control
