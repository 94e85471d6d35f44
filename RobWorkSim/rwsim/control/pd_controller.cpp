#include "rwsim/control/pd_controller.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rwsim::control {

namespace {

bool allFiniteNonNegative(const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]) || v[i] < 0.0) return false;
  }
  return true;
}

}  // namespace

PDController::PDController(const Eigen::VectorXd& p, const Eigen::VectorXd& d) : p_(p), d_(d) {
  if (p.size() != d.size()) {
    throw std::invalid_argument("PDController: " + std::to_string(p.size()) + " P gains but " +
                                std::to_string(d.size()) + " D gains");
  }
  if (!allFiniteNonNegative(p) || !allFiniteNonNegative(d)) {
    throw std::invalid_argument("PDController: gains must be finite and >= 0");
  }
  target_ = rw::math::Q::Zero(p.size());
  targetVelocity_ = rw::math::Q::Zero(p.size());
  lastError_ = rw::math::Q::Zero(p.size());
}

void PDController::checkSize(const rw::math::Q& q, const char* what) const {
  if (q.size() != p_.size()) {
    throw std::invalid_argument(std::string("PDController: ") + what + " has " +
                                std::to_string(q.size()) + " values for " +
                                std::to_string(p_.size()) + " joints");
  }
}

void PDController::setTarget(const rw::math::Q& q) {
  checkSize(q, "target");
  target_ = q;
  targetVelocity_.setZero();
}

void PDController::setTarget(const rw::math::Q& q, const rw::math::Q& velocity) {
  checkSize(q, "target");
  checkSize(velocity, "target velocity");
  target_ = q;
  targetVelocity_ = velocity;
}

void PDController::setVelocityLimits(const rw::math::Q& limits) {
  if (limits.size() == 0) {
    velocityLimits_.resize(0);
    return;
  }
  checkSize(limits, "velocity limits");
  for (Eigen::Index i = 0; i < limits.size(); ++i) {
    if (std::isnan(limits[i]) || limits[i] < 0.0) {
      throw std::invalid_argument("PDController: velocity limit " + std::to_string(i) +
                                  " must be >= 0");
    }
  }
  velocityLimits_ = limits;
}

void PDController::reset(const rw::math::Q& q) {
  checkSize(q, "configuration");
  target_ = q;
  targetVelocity_.setZero();
  lastError_.setZero();
  hasLastError_ = false;
}

rw::math::Q PDController::update(const rw::math::Q& q, double dt) {
  checkSize(q, "configuration");
  if (!(dt > 0.0)) throw std::invalid_argument("PDController: dt must be > 0");
  const rw::math::Q error = target_ - q;
  rw::math::Q velocity = targetVelocity_ + p_.cwiseProduct(error);
  if (hasLastError_) velocity += d_.cwiseProduct(error - lastError_) / dt;
  lastError_ = error;
  hasLastError_ = true;
  if (velocityLimits_.size() == velocity.size()) {
    velocity = velocity.cwiseMax(-velocityLimits_).cwiseMin(velocityLimits_);
  }
  return velocity;
}

}  // namespace rwsim::control
