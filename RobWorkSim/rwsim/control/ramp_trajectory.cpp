#include "rwsim/control/ramp_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rwsim::control {

namespace {

bool positiveFinite(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

RampProfile::RampProfile(double distance, double velocity, double acceleration)
    : distance_(distance), acceleration_(acceleration) {
  if (!std::isfinite(distance) || distance < 0.0 || !positiveFinite(velocity) ||
      !positiveFinite(acceleration)) {
    throw std::invalid_argument(
        "RampProfile: need distance >= 0 and velocity, acceleration > 0 (finite)");
  }
  if (distance * acceleration >= velocity * velocity) {
    peak_ = velocity;
    rampTime_ = velocity / acceleration;
    duration_ = 2.0 * rampTime_ + (distance - velocity * rampTime_) / velocity;
  } else {
    rampTime_ = std::sqrt(distance / acceleration);
    peak_ = acceleration * rampTime_;
    duration_ = 2.0 * rampTime_;
  }
}

RampProfile RampProfile::stretched(double duration) const {
  if (!std::isfinite(duration) || duration < duration_ * (1.0 - 1e-12)) {
    throw std::invalid_argument("RampProfile: cannot be done faster than its fastest profile");
  }
  RampProfile r;
  r.distance_ = distance_;
  r.acceleration_ = acceleration_;
  r.duration_ = duration;
  if (distance_ == 0.0) return r;
  // distance = v (T - v / a): the smaller root is the cruise speed that ends at T.
  const double a = acceleration_;
  const double disc = std::max(0.0, a * a * duration * duration - 4.0 * a * distance_);
  r.peak_ = 0.5 * (a * duration - std::sqrt(disc));
  r.rampTime_ = r.peak_ / a;
  return r;
}

double RampProfile::position(double t) const {
  if (t <= 0.0) return 0.0;
  if (t >= duration_) return distance_;
  const double a = acceleration_;
  if (t < rampTime_) return 0.5 * a * t * t;
  const double rampDistance = 0.5 * a * rampTime_ * rampTime_;
  const double decelStart = duration_ - rampTime_;
  if (t <= decelStart) return rampDistance + peak_ * (t - rampTime_);
  const double left = duration_ - t;
  return distance_ - 0.5 * a * left * left;
}

double RampProfile::velocity(double t) const {
  if (t <= 0.0 || t >= duration_) return 0.0;
  if (t < rampTime_) return acceleration_ * t;
  if (t <= duration_ - rampTime_) return peak_;
  return acceleration_ * (duration_ - t);
}

RampTrajectory::RampTrajectory(const rw::math::Transform3D& X_start,
                               const rw::math::Transform3D& X_end, const RampLimits& limits)
    : start_(X_start), end_(X_end), linear_(0.0, 1.0, 1.0), angular_(0.0, 1.0, 1.0) {
  const rw::math::Vector3D delta = X_end.translation() - X_start.translation();
  const double distance = delta.norm();
  if (distance > 0.0) direction_ = delta / distance;
  const Eigen::AngleAxisd turn(X_start.linear().transpose() * X_end.linear());
  double angle = turn.angle();
  if (angle > 0.0) {
    axis_ = turn.axis();
  } else {
    angle = 0.0;
  }
  linear_ = RampProfile(distance, limits.linearVelocity, limits.linearAcceleration);
  angular_ = RampProfile(angle, limits.angularVelocity, limits.angularAcceleration);
  duration_ = std::max(linear_.duration(), angular_.duration());
  linear_ = linear_.stretched(duration_);
  angular_ = angular_.stretched(duration_);
}

rw::math::Transform3D RampTrajectory::pose(double t) const {
  if (t >= duration_) return end_;
  rw::math::Transform3D X = start_;
  X.translation() += direction_ * linear_.position(t);
  X.linear() = start_.linear() * Eigen::AngleAxisd(angular_.position(t), axis_).toRotationMatrix();
  return X;
}

rw::math::Vector3D RampTrajectory::linearVelocity(double t) const {
  return direction_ * linear_.velocity(t);
}

rw::math::Vector3D RampTrajectory::angularVelocity(double t) const {
  // The axis is fixed in the start frame; in world coordinates it is R_start * axis.
  return start_.linear() * axis_ * angular_.velocity(t);
}

Twist twistToReach(const rw::math::Transform3D& X_now, const rw::math::Transform3D& X_next,
                   double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("twistToReach: dt must be > 0");
  Twist twist;
  twist.linear = (X_next.translation() - X_now.translation()) / dt;
  const Eigen::AngleAxisd turn(X_next.linear() * X_now.linear().transpose());
  twist.angular = turn.axis() * (turn.angle() / dt);
  return twist;
}

}  // namespace rwsim::control
