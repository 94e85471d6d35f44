#pragma once

#include <gtest/gtest.h>

#include "rw/math/types.hpp"
#include "rwsim/trial/physics_engine.hpp"

/// Stepping and force helpers shared by the engine tests (ODE's and MuJoCo's).
namespace visgrab::test::sim {

/// Steps `engine` until its time reaches `t`; every step must succeed.
inline void runUntil(rwsim::trial::PhysicsEngine& engine, double t) {
  while (engine.time() < t - 1e-9) {
    const rwsim::trial::StepStatus s = engine.step();
    ASSERT_EQ(s, rwsim::trial::StepStatus::kOk) << engine.failureDetail();
  }
}

/// Sum of the contact forces on body `b` in the last step.
inline rw::math::Vector3D forceOn(const rwsim::trial::PhysicsEngine& engine,
                                  rwsim::dynamics::BodyId b) {
  rw::math::Vector3D f = rw::math::Vector3D::Zero();
  for (const auto& bc : engine.contacts()) {
    for (const auto& p : bc.points) {
      if (bc.bodyB == b) f += p.force;
      if (bc.bodyA == b) f -= p.force;
    }
  }
  return f;
}

}  // namespace visgrab::test::sim
