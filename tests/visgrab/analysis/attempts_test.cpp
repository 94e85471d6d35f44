#include "visgrab/analysis/attempts.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace visgrab::analysis {
namespace {

TEST(AttemptsTest, HypergeometricByHand) {
  // 4 grasps, 2 successful: one draw succeeds with 2/4; two draws all fail with
  // C(2,2)/C(4,2) = 1/6, so succeed with 5/6; three draws cannot all fail.
  EXPECT_DOUBLE_EQ(successWithinAttempts(4, 2, 1), 0.5);
  EXPECT_DOUBLE_EQ(successWithinAttempts(4, 2, 2), 5.0 / 6.0);
  EXPECT_DOUBLE_EQ(successWithinAttempts(4, 2, 3), 1.0);
  EXPECT_DOUBLE_EQ(successWithinAttempts(4, 2, 9), 1.0);
  // 10 grasps, 3 successful, 4 draws: 1 - C(7,4)/C(10,4) = 1 - 35/210 = 5/6.
  EXPECT_DOUBLE_EQ(successWithinAttempts(10, 3, 4), 5.0 / 6.0);
  EXPECT_EQ(successWithinAttempts(0, 0, 3), 0.0);
  EXPECT_EQ(successWithinAttempts(5, 0, 5), 0.0);
  EXPECT_EQ(successWithinAttempts(5, 2, 0), 0.0);
  // Expected first-success position (n+1)/(k+1): 4 grasps, 2 successful -> 5/3.
  EXPECT_DOUBLE_EQ(expectedAttemptsToFirstSuccess(4, 2), 5.0 / 3.0);
  EXPECT_DOUBLE_EQ(expectedAttemptsToFirstSuccess(1, 1), 1.0);
}

TEST(AttemptsTest, FormulasAgreeWithEveryOrderOfASmallScene) {
  // Independent truth: enumerate all 5! orders of 5 grasps with 2 successes.
  const std::vector<bool> success = {false, true, false, false, true};
  std::vector<int> order(5);
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> within(5, 0.0);
  double firstSum = 0.0;
  int orders = 0;
  do {
    int first = 0;
    for (int i = 0; i < 5 && first == 0; ++i) first = success[order[i]] ? i + 1 : 0;
    firstSum += first;
    for (int n = first; n <= 5; ++n) within[n - 1] += 1.0;
    ++orders;
  } while (std::next_permutation(order.begin(), order.end()));
  for (int n = 1; n <= 5; ++n) {
    EXPECT_NEAR(successWithinAttempts(5, 2, n), within[n - 1] / orders, 1e-12) << n;
  }
  EXPECT_NEAR(expectedAttemptsToFirstSuccess(5, 2), firstSum / orders, 1e-12);
}

TEST(AttemptsTest, RandomizedTrialsConvergeToTheExactCurve) {
  const std::vector<SceneOutcomes> scenes = {
      {"m|a", {false, true, false, true}}, {"m|b", {false, true}}, {"m|c", {}},
      {"m|d", {true, false, false}},       {"m|e", {false}},
  };
  const int n = 4;
  const RandomizedAttempts many = randomizedAttempts(scenes, n, 20000, 7);
  // 20000 trials x 5 scenes: the standard error of each rate is below 0.5/sqrt(1e5) = 0.0016.
  for (int k = 1; k <= n; ++k) {
    double exact = 0.0;
    for (const auto& s : scenes) {
      const int grasps = static_cast<int>(s.success.size());
      const int successes = static_cast<int>(std::count(s.success.begin(), s.success.end(), true));
      exact += successWithinAttempts(grasps, successes, k);
    }
    exact /= static_cast<double>(scenes.size());
    EXPECT_NEAR(many.rate[static_cast<std::size_t>(k - 1)], exact, 0.01) << k;
  }
  // Mean first success over the scenes with one: (5/3 + 3/2 + 4/2) / 3 = 31/18.
  EXPECT_NEAR(many.meanFirstSuccess, 31.0 / 18.0, 0.02);
}

TEST(AttemptsTest, RandomizedTrialsAreDeterministicAndMonotone) {
  const std::vector<SceneOutcomes> scenes = {{"x", {false, false, true, false, true, false}},
                                             {"y", {true}}};
  const RandomizedAttempts a = randomizedAttempts(scenes, 6, 20, 1);
  const RandomizedAttempts b = randomizedAttempts(scenes, 6, 20, 1);
  EXPECT_EQ(a.rate, b.rate);
  for (std::size_t k = 1; k < a.rate.size(); ++k) EXPECT_GE(a.rate[k], a.rate[k - 1]);
  // Every scene has a success and at most 6 grasps: within 5 attempts (6 - 2 + 1) always.
  EXPECT_EQ(a.rate[4], 1.0);
  // A scene's order depends on its key, not on the other scenes.
  const RandomizedAttempts alone = randomizedAttempts({scenes[0]}, 6, 20, 1);
  const RandomizedAttempts other = randomizedAttempts({{"z", {true}}, scenes[0]}, 6, 20, 1);
  for (std::size_t k = 0; k < 6; ++k) {
    // other = (alone + 1) / 2 for every n, since "z" always succeeds at once.
    EXPECT_DOUBLE_EQ(other.rate[k], (alone.rate[k] + 1.0) / 2.0);
  }
}

}  // namespace
}  // namespace visgrab::analysis
