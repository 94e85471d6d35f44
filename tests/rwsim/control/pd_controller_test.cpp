#include "rwsim/control/pd_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "support/test_support.hpp"

namespace {

using rw::math::Q;
using rwsim::control::PDController;

Q vec(std::initializer_list<double> v) {
  Q q(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (const double x : v) q[i++] = x;
  return q;
}

TEST(PDController, FirstUpdateIsProportionalOnly) {
  PDController pd(vec({10.0, 2.0}), vec({0.003, 0.5}));
  pd.setTarget(vec({1.0, -1.0}));
  const Q v = pd.update(vec({0.0, 0.0}), 0.01);
  EXPECT_VECTOR_NEAR(v, vec({10.0, -2.0}), 1e-12);
}

TEST(PDController, DerivativeUsesErrorChangeOverDt) {
  PDController pd(vec({10.0}), vec({0.5}));
  pd.setTarget(vec({1.0}));
  pd.update(vec({0.0}), 0.01);              // e = 1
  const Q v = pd.update(vec({0.2}), 0.01);  // e = 0.8, de/dt = -20
  EXPECT_NEAR(v[0], 10.0 * 0.8 + 0.5 * (-20.0), 1e-12);
}

TEST(PDController, TargetVelocityIsFedForward) {
  PDController pd(vec({10.0}), vec({0.0}));
  pd.setTarget(vec({0.0}), vec({0.3}));
  EXPECT_NEAR(pd.update(vec({0.0}), 0.01)[0], 0.3, 1e-12);
}

TEST(PDController, ResetHoldsAndClearsHistory) {
  PDController pd(vec({10.0}), vec({1.0}));
  pd.setTarget(vec({1.0}));
  pd.update(vec({0.0}), 0.01);
  pd.reset(vec({0.5}));
  EXPECT_NEAR(pd.target()[0], 0.5, 0.0);
  // No derivative kick right after a reset.
  EXPECT_NEAR(pd.update(vec({0.4}), 0.01)[0], 10.0 * 0.1, 1e-12);
}

TEST(PDController, VelocityLimitsClamp) {
  PDController pd(vec({10.0, 10.0}), vec({0.0, 0.0}));
  const double inf = std::numeric_limits<double>::infinity();
  pd.setVelocityLimits(vec({1.0, inf}));
  pd.setTarget(vec({-1.0, 1.0}));
  EXPECT_VECTOR_NEAR(pd.update(vec({0.0, 0.0}), 0.01), vec({-1.0, 10.0}), 1e-12);
}

TEST(PDController, ConvergesOnAnIdealVelocityJoint) {
  // A joint that follows its commanded velocity exactly: e decays like exp(-P t).
  PDController pd(vec({10.0}), vec({0.003}));
  pd.setTarget(vec({1.0}));
  Q q = vec({0.0});
  const double dt = 0.001;
  for (int i = 0; i < 100; ++i) q += pd.update(q, dt) * dt;  // 0.1 s
  EXPECT_NEAR(1.0 - q[0], std::exp(-1.0), 0.01);
}

TEST(PDController, RejectsBadInput) {
  EXPECT_THROW(PDController(vec({1.0}), vec({1.0, 2.0})), std::invalid_argument);
  EXPECT_THROW(PDController(vec({-1.0}), vec({1.0})), std::invalid_argument);
  PDController pd(vec({1.0, 1.0}), vec({0.0, 0.0}));
  EXPECT_THROW(pd.setTarget(vec({1.0})), std::invalid_argument);
  EXPECT_THROW(pd.update(vec({1.0, 2.0}), 0.0), std::invalid_argument);
  EXPECT_THROW(pd.update(vec({1.0}), 0.01), std::invalid_argument);
  EXPECT_THROW(pd.setVelocityLimits(vec({1.0, -1.0})), std::invalid_argument);
}

}  // namespace
