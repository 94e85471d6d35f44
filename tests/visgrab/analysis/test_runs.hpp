#pragma once

#include <string>
#include <vector>

#include "visgrab/results/trial_record.hpp"

/// The small hand-worked result set shared by the analysis tests (see analysis_test.cpp for the
/// arithmetic).
namespace visgrab::analysis::test_runs {

using database::SceneConditions;
using database::Texture;
using rwsim::trial::GraspOutcome;

/// A trial of method `method` in `scene`, rank = position in the scene's list.
inline results::TrialRecord trial(const results::RunScene& scene, const std::string& method,
                                  int rank, GraspOutcome outcome, double qLift = 0.0,
                                  double qGws = 0.0, int object = 0, double qGwsUnit = 0.0) {
  results::TrialRecord t;
  t.sceneId = scene.id;
  t.conditions = scene.conditions;
  t.method = method;
  t.graspId = "g" + std::to_string(rank);
  t.rank = rank;
  t.outcome = outcome;
  t.qLift = qLift;
  t.qGws = qGws;
  t.qGwsUnit = qGwsUnit;
  t.object = object;
  return t;
}

inline results::RunScene scene(const SceneConditions& c) { return {database::sceneIdOf(c), c}; }

/// Repeat `repeat` (> 0: perturbed, with a made-up seed) of `grasp`, ending with `outcome`.
inline results::TrialRecord repeated(results::TrialRecord grasp, int repeat, GraspOutcome outcome) {
  grasp.repeat = repeat;
  grasp.seed = repeat == 0 ? 0 : 1000U + static_cast<unsigned>(repeat);
  grasp.outcome = outcome;
  return grasp;
}

/// A run "label" of method `method` over `scenes`, scene i getting the outcomes outcomes[i] as
/// its grasps (rank order).
inline results::RunResults outcomesRun(const std::string& label, const std::string& method,
                                       const std::vector<results::RunScene>& scenes,
                                       const std::vector<std::vector<GraspOutcome>>& outcomes) {
  results::RunResults run;
  run.label = label;
  run.scenes = scenes;
  run.methods = {method};
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    for (std::size_t g = 0; g < outcomes[s].size(); ++g) {
      run.trials.push_back(trial(scenes[s], method, static_cast<int>(g), outcomes[s][g]));
    }
  }
  return run;
}

/// Run "runA", method "A":
/// (successes as (Q_lift, Q_GWS, Q_GWS,unit))
///  S1 textured single cocacola(5) pose 1 (standing): missed, stable(0.9, 0.4, 0.04), in
///     collision, slipped(0.5, 0.2, 0.02)                                  n = 4, k = 2
///  S2 textured single cocacola(5) pose 5 (lying): dropped, stable(0.4, 0.6, 0.06)  n = 2, k = 1
///  S3 textured single greencup(8) pose 2 (standing): no grasp                       n = 0
///  S4 textured double pair e (5-14) placement 1 (apart): stable holding 14 (1.0, 0.5, 0.05),
///     in collision, missed                                                          n = 3, k = 1
///  S5 textured double pair e placement 6 (close): invalid contacts                  n = 1, k = 0
///  P1 plain single amicelli(1) pose 3 (standing): stable(0.8, 0.1, 0.01)            n = 1, k = 1
/// The closings of S1's stable grasp and S2's dropped one hit the closing cap (their details say
/// so); 2 grasps of A were rejected.
inline results::RunResults runA() {
  results::RunResults run;
  run.label = "runA";
  const auto s1 = scene(SceneConditions::single(Texture::kTextured, 5, 1));
  const auto s2 = scene(SceneConditions::single(Texture::kTextured, 5, 5));
  const auto s3 = scene(SceneConditions::single(Texture::kTextured, 8, 2));
  const auto s4 = scene(SceneConditions::pairScene(Texture::kTextured, 'e', 1));
  const auto s5 = scene(SceneConditions::pairScene(Texture::kTextured, 'e', 6));
  const auto p1 = scene(SceneConditions::single(Texture::kPlain, 1, 3));
  run.scenes = {p1, s1, s2, s3, s4, s5};
  run.methods = {"A"};
  run.rejected = {{"A", 2}};
  run.trials = {
      trial(p1, "A", 0, GraspOutcome::kStable, 0.8, 0.1, 1, 0.01),
      trial(s1, "A", 0, GraspOutcome::kMissed),
      trial(s1, "A", 1, GraspOutcome::kStable, 0.9, 0.4, 5, 0.04),
      trial(s1, "A", 2, GraspOutcome::kInCollision),
      trial(s1, "A", 3, GraspOutcome::kSlipped, 0.5, 0.2, 5, 0.02),
      trial(s2, "A", 0, GraspOutcome::kDropped, 0.0, 0.0, 5),
      trial(s2, "A", 1, GraspOutcome::kStable, 0.4, 0.6, 5, 0.06),
      trial(s4, "A", 0, GraspOutcome::kStable, 1.0, 0.5, 14, 0.05),
      trial(s4, "A", 1, GraspOutcome::kInCollision),
      trial(s4, "A", 2, GraspOutcome::kMissed),
      trial(s5, "A", 0, GraspOutcome::kInvalidContacts),
  };
  run.trials[2].detail =
      "object drift 0.001 m [closing hit the cap: 5 s simulated with J still "
      "at 0.02 rad/s (at rest below 0.01)]";
  run.trials[5].detail = "no hand contact on x after lifting [closing hit the cap: ...]";
  run.trials[2].closingCapped = true;
  run.trials[5].closingCapped = true;
  return run;
}

/// Method "M" on two textured single standing scenes:
///  S1 (cocacola, pose 1): stable (Q_lift 0.9, Q_GWS 0.4), missed, slipped (0.5, 0.2), in
///     collision: n = 4, k = 2, first success at attempt 1 in the given order;
///  S2 (greencup, pose 2): missed, stable (0.4, 0.6), missed: n = 3, k = 1, first success at 2.
inline results::RunResults twoSceneRun() {
  const auto s1 = scene(SceneConditions::single(Texture::kTextured, 5, 1));
  const auto s2 = scene(SceneConditions::single(Texture::kTextured, 8, 2));
  results::RunResults run;
  run.label = "two";
  run.scenes = {s1, s2};
  run.methods = {"M"};
  run.trials = {trial(s1, "M", 0, GraspOutcome::kStable, 0.9, 0.4, 5),
                trial(s1, "M", 1, GraspOutcome::kMissed),
                trial(s1, "M", 2, GraspOutcome::kSlipped, 0.5, 0.2, 5),
                trial(s1, "M", 3, GraspOutcome::kInCollision),
                trial(s2, "M", 0, GraspOutcome::kMissed),
                trial(s2, "M", 1, GraspOutcome::kStable, 0.4, 0.6, 8),
                trial(s2, "M", 2, GraspOutcome::kMissed)};
  return run;
}

/// Run "runB": method "A" (same name as runA's) with S1: stable(0.6, 0.3) only, and method
/// "x<&>\"" that suggests nothing.
inline results::RunResults runB() {
  results::RunResults run;
  run.label = "runB";
  const auto s1 = scene(SceneConditions::single(Texture::kTextured, 5, 1));
  run.scenes = {s1};
  run.methods = {"A", "x<&>\""};
  run.trials = {trial(s1, "A", 0, GraspOutcome::kStable, 0.6, 0.3, 5)};
  return run;
}

}  // namespace visgrab::analysis::test_runs
