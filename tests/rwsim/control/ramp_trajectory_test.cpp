#include "rwsim/control/ramp_trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "support/test_support.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::control::RampLimits;
using rwsim::control::RampProfile;
using rwsim::control::RampTrajectory;
using rwsim::control::twistToReach;

TEST(RampProfile, TrapezoidWhenLongEnough) {
  const RampProfile r(1.0, 0.5, 1.0);  // ramps of 0.5 s covering 0.125 m each
  EXPECT_NEAR(r.duration(), 0.5 + 0.5 + 0.75 / 0.5, 1e-12);
  EXPECT_NEAR(r.peakVelocity(), 0.5, 1e-12);
  EXPECT_NEAR(r.position(0.5), 0.125, 1e-12);
  EXPECT_NEAR(r.velocity(1.0), 0.5, 1e-12);
  EXPECT_NEAR(r.position(r.duration()), 1.0, 1e-12);
  EXPECT_NEAR(r.position(r.duration() - 0.5), 1.0 - 0.125, 1e-12);
}

TEST(RampProfile, TriangleWhenShort) {
  const RampProfile r(0.1, 0.5, 1.0);
  EXPECT_NEAR(r.duration(), 2.0 * std::sqrt(0.1), 1e-12);
  EXPECT_NEAR(r.peakVelocity(), std::sqrt(0.1), 1e-12);
  EXPECT_NEAR(r.position(r.duration() / 2), 0.05, 1e-12);
}

TEST(RampProfile, PositionIsIntegralOfVelocity) {
  const RampProfile r(0.3, 0.2, 0.8);
  double s = 0.0;
  const double dt = 1e-5;
  for (double t = 0.0; t < r.duration(); t += dt) s += r.velocity(t + dt / 2) * dt;
  EXPECT_NEAR(s, 0.3, 1e-5);
}

TEST(RampProfile, StretchedEndsAtTheGivenTime) {
  const RampProfile r = RampProfile(0.1, 0.5, 1.0).stretched(2.0);
  EXPECT_NEAR(r.duration(), 2.0, 1e-12);
  EXPECT_NEAR(r.position(2.0), 0.1, 1e-12);
  EXPECT_NEAR(r.position(1.0), 0.05, 1e-9);
  EXPECT_LE(r.peakVelocity(), 0.1);
  EXPECT_THROW(RampProfile(0.1, 0.5, 1.0).stretched(0.1), std::invalid_argument);
  EXPECT_THROW(RampProfile(-1.0, 0.5, 1.0), std::invalid_argument);
}

TEST(RampTrajectory, StraightLiftWithRobWorkLimits) {
  const Transform3D start = rw::math::makeTranslation(Vector3D(0.1, 0.2, 0.3));
  const Transform3D end = rw::math::makeTranslation(Vector3D(0.1, 0.2, 0.4));
  const RampTrajectory traj(start, end);
  EXPECT_NEAR(traj.duration(), 2.0 * std::sqrt(0.1), 1e-12);
  EXPECT_TRANSFORM_NEAR(traj.pose(traj.duration() / 2),
                        rw::math::makeTranslation(Vector3D(0.1, 0.2, 0.35)), 1e-12);
  EXPECT_TRANSFORM_NEAR(traj.pose(10.0), end, 0.0);
  EXPECT_NEAR(traj.linearVelocity(traj.duration() / 2).z(), std::sqrt(0.1), 1e-12);
}

TEST(RampTrajectory, RotationAndTranslationEndTogether) {
  const Transform3D start = Transform3D::Identity();
  Transform3D end = rw::math::makeTranslation(Vector3D(0.01, 0, 0));
  end.linear() = Eigen::AngleAxisd(std::numbers::pi / 2, Vector3D::UnitY()).toRotationMatrix();
  const RampTrajectory traj(start, end, RampLimits{});
  // The rotation (pi/2 at 0.4 rad/s) is the slower one.
  EXPECT_GT(traj.duration(), std::numbers::pi / 2 / 0.4);
  const Transform3D mid = traj.pose(traj.duration() / 2);
  EXPECT_NEAR(Eigen::AngleAxisd(mid.linear()).angle(), std::numbers::pi / 4, 1e-9);
  EXPECT_NEAR(mid.translation().x(), 0.005, 1e-9);
  EXPECT_NEAR(traj.angularVelocity(traj.duration() / 2).normalized().y(), 1.0, 1e-9);
}

TEST(TwistToReach, RecoversVelocity) {
  Transform3D a = rw::math::makeTranslation(Vector3D(1, 2, 3));
  a.linear() = Eigen::AngleAxisd(0.3, Vector3D(1, 1, 0).normalized()).toRotationMatrix();
  Transform3D b = a;
  b.translation() += Vector3D(0.001, 0, -0.002);
  b.linear() = Eigen::AngleAxisd(0.01, Vector3D::UnitZ()).toRotationMatrix() * a.linear();
  const auto twist = twistToReach(a, b, 0.01);
  EXPECT_VECTOR_NEAR(twist.linear, Vector3D(0.1, 0, -0.2), 1e-12);
  EXPECT_VECTOR_NEAR(twist.angular, Vector3D(0, 0, 1.0), 1e-9);
  EXPECT_THROW(twistToReach(a, b, 0.0), std::invalid_argument);
}

}  // namespace
