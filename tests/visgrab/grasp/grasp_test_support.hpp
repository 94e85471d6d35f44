#pragma once

// Shared helpers of the grasp-utility tests: the project's hands, loaded once per process.
#include <initializer_list>
#include <memory>
#include <numbers>

#include "support/test_support.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"

namespace visgrab::test::grasp {

/// One degree in radians.
inline constexpr double kDeg = std::numbers::pi / 180.0;

/// The SDH's setup (scenes/hands/sdh/sdh.grasp.xml), loaded on first use.
inline const visgrab::grasp::HandGraspSetup& sdh() {
  static const std::unique_ptr<visgrab::grasp::HandGraspSetup> setup =
      visgrab::grasp::loadHandGraspSetup(sourceDir() / "scenes/hands/sdh/sdh.grasp.xml");
  return *setup;
}

/// The PG70's setup (scenes/hands/pg70/pg70.grasp.xml), loaded on first use.
inline const visgrab::grasp::HandGraspSetup& pg70() {
  static const std::unique_ptr<visgrab::grasp::HandGraspSetup> setup =
      visgrab::grasp::loadHandGraspSetup(sourceDir() / "scenes/hands/pg70/pg70.grasp.xml");
  return *setup;
}

/// A Q from a list.
inline rw::math::Q makeQ(std::initializer_list<double> v) {
  rw::math::Q out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (const double x : v) out[i++] = x;
  return out;
}

}  // namespace visgrab::test::grasp
