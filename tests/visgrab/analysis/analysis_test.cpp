#include "visgrab/analysis/analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "test_runs.hpp"
#include "visgrab/analysis/attempts.hpp"

namespace visgrab::analysis {
namespace {

using rwsim::trial::GraspOutcome;

std::size_t groupIndex(const Analysis& a, const std::string& key) {
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    if (a.groups[g].key == key) return g;
  }
  throw std::invalid_argument("no group " + key);
}

const GroupResult& result(const Analysis& a, const std::string& key, std::size_t column) {
  return a.results[groupIndex(a, key)][column];
}

double share(const Distribution& d, GraspOutcome o) { return d.share[static_cast<std::size_t>(o)]; }

constexpr double kTol = 1e-12;

class AnalysisTest : public ::testing::Test {
 protected:
  Analysis a = analyze({test_runs::runA(), test_runs::runB()});
};

TEST_F(AnalysisTest, GroupsAndColumns) {
  ASSERT_EQ(a.groups.size(), 15u);
  EXPECT_EQ(a.groups[0].key, "textured-single-standing");
  EXPECT_EQ(a.groups[6].key, "textured-all");
  EXPECT_EQ(a.groups[13].key, "plain-all");
  EXPECT_EQ(a.groups[14].key, "overall");
  ASSERT_EQ(a.columns.size(), 3u);
  EXPECT_EQ(a.columns[0].label, "runA: A");  // "A" is in both runs
  EXPECT_EQ(a.columns[1].label, "runB: A");
  EXPECT_EQ(a.columns[2].label, "x<&>\"");
  EXPECT_EQ(a.columns[0].rejected, 2);
  EXPECT_EQ(a.columns[0].closingCapped, 2);
  EXPECT_EQ(a.columns[1].closingCapped, 0);
  EXPECT_EQ(a.maxAttempts, 4);  // S1 has the most grasps
}

TEST_F(AnalysisTest, DistributionWeighsEverySceneEqually) {
  // textured single standing = S1 (4 grasps: missed, stable, collision, slipped) and S3 (none):
  // each outcome of S1 has 1/4 of S1's weight 1/2 -> 0.125; S3 is the grey share 1/2.
  const Distribution& d = result(a, "textured-single-standing", 0).distribution;
  EXPECT_EQ(d.scenes, 2);
  EXPECT_EQ(d.scenesWithoutGrasps, 1);
  EXPECT_EQ(d.grasps, 4);
  EXPECT_NEAR(share(d, GraspOutcome::kMissed), 0.125, kTol);
  EXPECT_NEAR(share(d, GraspOutcome::kStable), 0.125, kTol);
  EXPECT_NEAR(share(d, GraspOutcome::kInCollision), 0.125, kTol);
  EXPECT_NEAR(share(d, GraspOutcome::kSlipped), 0.125, kTol);
  EXPECT_NEAR(share(d, GraspOutcome::kDropped), 0.0, kTol);
  EXPECT_NEAR(d.noGraspShare, 0.5, kTol);

  // textured all = S1..S5, weight 1/5 each:
  //   stable   (1/4 [S1] + 1/2 [S2] + 1/3 [S4]) / 5 = (13/12) / 5 = 13/60
  //   slipped  (1/4) / 5 = 3/60;  dropped (1/2) / 5 = 6/60
  //   missed   (1/4 + 1/3) / 5 = 7/60;  in collision the same 7/60
  //   invalid  (1 [S5]) / 5 = 12/60;  no grasp (S3) 1/5 = 12/60;  total 60/60
  const Distribution& t = result(a, "textured-all", 0).distribution;
  EXPECT_EQ(t.scenes, 5);
  EXPECT_EQ(t.grasps, 10);
  EXPECT_EQ(t.counts[static_cast<std::size_t>(GraspOutcome::kStable)], 3);
  EXPECT_EQ(t.counts[static_cast<std::size_t>(GraspOutcome::kInCollision)], 2);
  EXPECT_NEAR(share(t, GraspOutcome::kStable), 13.0 / 60, kTol);
  EXPECT_NEAR(share(t, GraspOutcome::kSlipped), 3.0 / 60, kTol);
  EXPECT_NEAR(share(t, GraspOutcome::kDropped), 6.0 / 60, kTol);
  EXPECT_NEAR(share(t, GraspOutcome::kMissed), 7.0 / 60, kTol);
  EXPECT_NEAR(share(t, GraspOutcome::kInCollision), 7.0 / 60, kTol);
  EXPECT_NEAR(share(t, GraspOutcome::kInvalidContacts), 12.0 / 60, kTol);
  EXPECT_NEAR(t.noGraspShare, 12.0 / 60, kTol);
  double total = t.noGraspShare;
  for (const double s : t.share) total += s;
  EXPECT_NEAR(total, 1.0, kTol);

  // The method that suggests nothing: all grey.
  EXPECT_NEAR(result(a, "textured-single-standing", 2).distribution.noGraspShare, 1.0, kTol);
  // An empty group: no scenes, nothing shared.
  EXPECT_EQ(result(a, "plain-double-apart", 0).distribution.scenes, 0);
}

TEST(AnalysisQualityTest, TrialsWithoutThePapersQGwsMakeItsMeanUndefined) {
  // A version 1 trials.csv has only the unit-force value: its trials' Q_GWS is NaN, so Table 1
  // shows no Q_GWS for their groups (never the unit value in its place), but Q_GWS,unit.
  results::RunResults run = test_runs::runA();
  for (results::TrialRecord& t : run.trials) {
    if (t.sceneId == run.scenes[1].id) t.qGws = std::nan("");  // S1
  }
  const Analysis b = analyze({run});
  const QualityMeans& s = result(b, "textured-single-standing", 0).quality;
  EXPECT_TRUE(std::isnan(s.meanQGws));
  EXPECT_NEAR(s.meanQGwsUnit, 0.03, kTol);
  EXPECT_NEAR(s.meanQLift, 0.7, kTol);
  // Groups without S1 keep their value: lying = S2's stable (0.6).
  EXPECT_NEAR(result(b, "textured-single-lying", 0).quality.meanQGws, 0.6, kTol);
}

TEST_F(AnalysisTest, QualityMeansOverSuccessfulGrasps) {
  // standing: S1's stable (0.9, 0.4) and slipped (0.5, 0.2) -> (0.7, 0.3)
  const QualityMeans& s = result(a, "textured-single-standing", 0).quality;
  EXPECT_EQ(s.successes, 2);
  EXPECT_NEAR(s.meanQLift, 0.7, kTol);
  EXPECT_NEAR(s.meanQGws, 0.3, kTol);
  EXPECT_NEAR(s.meanQGwsUnit, 0.03, kTol);  // (0.04 + 0.02) / 2
  // single all: + S2's stable (0.4, 0.6) -> ((0.9+0.5+0.4)/3, (0.4+0.2+0.6)/3) = (0.6, 0.4)
  const QualityMeans& all = result(a, "textured-single-all", 0).quality;
  EXPECT_EQ(all.successes, 3);
  EXPECT_NEAR(all.meanQLift, 0.6, kTol);
  EXPECT_NEAR(all.meanQGws, 0.4, kTol);
  // textured all: + S4's stable (1.0, 0.5) -> (2.8/4, 1.7/4) = (0.7, 0.425)
  const QualityMeans& t = result(a, "textured-all", 0).quality;
  EXPECT_NEAR(t.meanQLift, 0.7, kTol);
  EXPECT_NEAR(t.meanQGws, 0.425, kTol);
  EXPECT_NEAR(t.meanQGwsUnit, 0.0425, kTol);  // (0.04 + 0.02 + 0.06 + 0.05) / 4
  // double close: S5 has no success -> undefined.
  EXPECT_TRUE(std::isnan(result(a, "textured-double-close", 0).quality.meanQLift));
  // runB's "A" is its own column: S1 stable (0.6, 0.3).
  EXPECT_NEAR(result(a, "textured-single-standing", 1).quality.meanQLift, 0.6, kTol);
}

TEST_F(AnalysisTest, ExactSuccessCurveByHand) {
  // Per scene, P(success within n) = 1 - C(n_s - k_s, n) / C(n_s, n):
  //   S1 (4, 2): 1/2, 5/6, 1, 1    S2 (2, 1): 1/2, 1, 1, 1    S4 (3, 1): 1/3, 2/3, 1, 1
  //   S3, S5: 0 (no grasp; no success)
  // standing (S1, S3): 1/4, 5/12, 1/2, 1/2
  const auto& standing = result(a, "textured-single-standing", 0).attempts.exact;
  ASSERT_EQ(standing.size(), 4u);
  EXPECT_NEAR(standing[0], 0.25, kTol);
  EXPECT_NEAR(standing[1], 5.0 / 12, kTol);
  EXPECT_NEAR(standing[2], 0.5, kTol);
  EXPECT_NEAR(standing[3], 0.5, kTol);
  // textured all (S1..S5): (1/2+1/2+1/3)/5 = 4/15, (5/6+1+2/3)/5 = 1/2, 3/5, 3/5
  const auto& all = result(a, "textured-all", 0).attempts.exact;
  EXPECT_NEAR(all[0], 4.0 / 15, kTol);
  EXPECT_NEAR(all[1], 0.5, kTol);
  EXPECT_NEAR(all[2], 0.6, kTol);
  EXPECT_NEAR(all[3], 0.6, kTol);
  // double all (S4, S5): 1/6, 1/3, 1/2, 1/2
  const auto& dbl = result(a, "textured-double-all", 0).attempts.exact;
  EXPECT_NEAR(dbl[0], 1.0 / 6, kTol);
  EXPECT_NEAR(dbl[1], 1.0 / 3, kTol);
  EXPECT_NEAR(dbl[2], 0.5, kTol);
}

TEST_F(AnalysisTest, RandomizedCurveIsNearTheExactOne) {
  // 20 trials x 5 scenes = 100 (scene, trial) draws per point: the standard error of a rate is
  // at most 0.5/sqrt(100) = 0.05; allow 4 of them.
  const AttemptsCurve& c = result(a, "textured-all", 0).attempts;
  ASSERT_EQ(c.randomized.size(), c.exact.size());
  for (std::size_t k = 0; k < c.exact.size(); ++k) EXPECT_NEAR(c.randomized[k], c.exact[k], 0.2);
  // Scenes that succeed for sure, or never, have no randomness: exact = randomized.
  EXPECT_EQ(c.randomized[3], 0.6);
  // With many trials the estimate is close.
  AnalysisOptions many;
  many.randomTrials = 20000;
  const Analysis b = analyze({test_runs::runA()}, many);
  const AttemptsCurve& m = result(b, "textured-all", 0).attempts;
  for (std::size_t k = 0; k < m.exact.size(); ++k) EXPECT_NEAR(m.randomized[k], m.exact[k], 0.01);
  EXPECT_NEAR(result(b, "textured-all", 0).firstSuccess.gaRandomized, 31.0 / 18, 0.02);
  // Deterministic: the same input and seed give the same numbers.
  const Analysis again = analyze({test_runs::runA(), test_runs::runB()});
  EXPECT_EQ(result(again, "textured-all", 0).attempts.randomized, c.randomized);
}

TEST_F(AnalysisTest, ProportionAndAttemptsToFirstSuccess) {
  // standing: S1 has a success, S3 not -> p = 1/2; ga = (4+1)/(2+1) = 5/3; in the given order
  // S1's first success is its 2nd grasp.
  const FirstSuccess& s = result(a, "textured-single-standing", 0).firstSuccess;
  EXPECT_EQ(s.scenes, 2);
  EXPECT_EQ(s.scenesWithSuccess, 1);
  EXPECT_NEAR(s.p, 0.5, kTol);
  EXPECT_NEAR(s.ga, 5.0 / 3, kTol);
  EXPECT_NEAR(s.gaGivenOrder, 2.0, kTol);
  // lying: S2 (2, 1): p = 1, ga = 3/2
  EXPECT_NEAR(result(a, "textured-single-lying", 0).firstSuccess.ga, 1.5, kTol);
  // textured all: S1, S2, S4 of 5 -> p = 3/5; ga = (5/3 + 3/2 + 4/2)/3 = 31/18;
  // given order: (2 + 2 + 1)/3 = 5/3
  const FirstSuccess& t = result(a, "textured-all", 0).firstSuccess;
  EXPECT_NEAR(t.p, 0.6, kTol);
  EXPECT_NEAR(t.ga, 31.0 / 18, kTol);
  EXPECT_NEAR(t.gaGivenOrder, 5.0 / 3, kTol);
  // overall adds P1 (1, 1): p = 4/6; ga = (5/3 + 3/2 + 2 + 1)/4 = 37/24
  const FirstSuccess& o = result(a, "overall", 0).firstSuccess;
  EXPECT_NEAR(o.p, 4.0 / 6, kTol);
  EXPECT_NEAR(o.ga, 37.0 / 24, kTol);
  // double close: S5 never succeeds -> p = 0, ga undefined.
  const FirstSuccess& c = result(a, "textured-double-close", 0).firstSuccess;
  EXPECT_NEAR(c.p, 0.0, kTol);
  EXPECT_TRUE(std::isnan(c.ga));
  // empty group: p undefined.
  EXPECT_TRUE(std::isnan(result(a, "plain-double-all", 0).firstSuccess.p));
}

TEST_F(AnalysisTest, SuccessPerObject) {
  const ObjectTable& textured = a.objectTables[0][0];
  // cocacola (5) standing: S1, 2 of 4; lying: S2, 1 of 2.
  EXPECT_EQ(textured.single[4][0].grasps, 4);
  EXPECT_NEAR(textured.single[4][0].percent(), 50.0, kTol);
  EXPECT_NEAR(textured.single[4][1].percent(), 50.0, kTol);
  // greencup (8) standing: S3 has no grasps -> undefined.
  EXPECT_TRUE(std::isnan(textured.single[7][0].percent()));
  // pair e far: S4, 1 of 3 successful, holding saltcylinder (14, the pair's second object).
  const SuccessCount& far = textured.pairs[4][0];
  EXPECT_EQ(far.grasps, 3);
  EXPECT_EQ(far.successes, 1);
  EXPECT_NEAR(far.percent(), 100.0 / 3, kTol);
  EXPECT_NEAR(far.percentOf(0), 0.0, kTol);
  EXPECT_NEAR(far.percentOf(1), 100.0 / 3, kTol);
  // pair e close: S5, 0 of 1.
  EXPECT_NEAR(textured.pairs[4][1].percent(), 0.0, kTol);
  // plain table: amicelli (1) standing 1 of 1; nothing else.
  EXPECT_NEAR(a.objectTables[1][0].single[0][0].percent(), 100.0, kTol);
  EXPECT_EQ(a.objectTables[1][0].single[4][0].grasps, 0);
}

TEST(AnalysisOptionsTest, RejectsBadOptions) {
  AnalysisOptions bad;
  bad.randomTrials = 0;
  EXPECT_THROW(analyze({}, bad), std::invalid_argument);
  bad.randomTrials = 20;
  bad.maxAttempts = -1;
  EXPECT_THROW(analyze({}, bad), std::invalid_argument);
  bad.maxAttempts = 2;
  const Analysis a = analyze({test_runs::runA()}, bad);
  EXPECT_EQ(a.results[0][0].attempts.exact.size(), 2u);
}

}  // namespace
}  // namespace visgrab::analysis
