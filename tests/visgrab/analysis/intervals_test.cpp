// The scene bootstrap's intervals against hand-worked resample distributions.
//
// With two scenes a resample draws scene 1 twice (probability 1/4), each once (1/2) or scene 2
// twice (1/4). Every estimate here is a ratio of sums over the drawn scenes, so the both-once
// value lies between the two single-scene values, and each single-scene value holds a quarter
// of the resamples: the 2.5 % and 97.5 % quantiles of 2,000 replicates (linear interpolation at
// positions 49.975 and 1949.025 of the sorted replicates) fall inside those quarters unless one
// of them got fewer than 51 of the 2,000 draws (expected 500; the chance is below 1e-100). So
// the 95 % interval is exactly [min, max] of the estimate on scene 1 alone and on scene 2 alone,
// whatever the random stream.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "test_runs.hpp"
#include "visgrab/analysis/analysis.hpp"

namespace visgrab::analysis {
namespace {

using rwsim::trial::GraspOutcome;
using test_runs::scene;
using test_runs::trial;

constexpr double kTol = 1e-12;

std::size_t groupIndex(const Analysis& a, const std::string& key) {
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    if (a.groups[g].key == key) return g;
  }
  throw std::invalid_argument("no group " + key);
}

void expectInterval(const results::Interval& i, double low, double high, const char* what) {
  EXPECT_NEAR(i.low, low, kTol) << what;
  EXPECT_NEAR(i.high, high, kTol) << what;
}

double share(const Distribution& d, GraspOutcome o) { return d.share[static_cast<std::size_t>(o)]; }
results::Interval shareCi(const Distribution& d, GraspOutcome o) {
  return d.shareCi[static_cast<std::size_t>(o)];
}

TEST(IntervalsTest, TwoScenesGiveTheSingleSceneValuesAsEnds) {
  const Analysis a = analyze({test_runs::twoSceneRun()});
  ASSERT_TRUE(a.intervals);
  for (const char* key : {"textured-single-standing", "textured-single-all", "overall"}) {
    SCOPED_TRACE(key);
    const GroupResult& r = a.results[groupIndex(a, key)][0];
    // Success rate: 3 of 7 pooled; S1 alone 2/4, S2 alone 1/3.
    EXPECT_EQ(r.success.grasps, 7);
    EXPECT_EQ(r.success.successes, 3);
    EXPECT_NEAR(r.success.rate, 3.0 / 7, kTol);
    expectInterval(r.success.rateCi, 1.0 / 3, 0.5, "success rate");
    // Shares: S1 a quarter per outcome, S2 1/3 stable and 2/3 missed.
    const Distribution& d = r.distribution;
    EXPECT_NEAR(share(d, GraspOutcome::kStable), (0.25 + 1.0 / 3) / 2, kTol);
    expectInterval(shareCi(d, GraspOutcome::kStable), 0.25, 1.0 / 3, "stable");
    expectInterval(shareCi(d, GraspOutcome::kMissed), 0.25, 2.0 / 3, "missed");
    expectInterval(shareCi(d, GraspOutcome::kSlipped), 0.0, 0.25, "slipped");
    expectInterval(shareCi(d, GraspOutcome::kInCollision), 0.0, 0.25, "in collision");
    expectInterval(shareCi(d, GraspOutcome::kDropped), 0.0, 0.0, "dropped");
    expectInterval(d.noGraspShareCi, 0.0, 0.0, "no grasp");
    // Qualities over the successes: S1 (0.9 + 0.5) / 2, S2 0.4; Q_GWS 0.3 and 0.6.
    EXPECT_NEAR(r.quality.meanQLift, 0.6, kTol);
    expectInterval(r.quality.meanQLiftCi, 0.4, 0.7, "Q_lift");
    expectInterval(r.quality.meanQGwsCi, 0.3, 0.6, "Q_GWS");
    expectInterval(r.quality.meanQGwsUnitCi, 0.0, 0.0, "Q_GWS,unit");
    // p: both scenes have a success; ga: S1 (4 + 1) / (2 + 1), S2 (3 + 1) / (1 + 1); given order
    // 1 and 2.
    expectInterval(r.firstSuccess.pCi, 1.0, 1.0, "p");
    EXPECT_NEAR(r.firstSuccess.ga, (5.0 / 3 + 2.0) / 2, kTol);
    expectInterval(r.firstSuccess.gaCi, 5.0 / 3, 2.0, "ga");
    expectInterval(r.firstSuccess.gaGivenOrderCi, 1.0, 2.0, "ga given order");
    // Figure 7, exact: n = 1: k/n, 1/2 and 1/3; n = 2: 1 - C(n-k, 2)/C(n, 2), 5/6 and 2/3;
    // n = 3 and 4: every scene has its success by then.
    ASSERT_EQ(r.attempts.exactCi.size(), 4u);
    expectInterval(r.attempts.exactCi[0], 1.0 / 3, 0.5, "n=1");
    expectInterval(r.attempts.exactCi[1], 2.0 / 3, 5.0 / 6, "n=2");
    expectInterval(r.attempts.exactCi[2], 1.0, 1.0, "n=3");
    expectInterval(r.attempts.exactCi[3], 1.0, 1.0, "n=4");
  }
  // Tables 3-4: one scene per object and arrangement: a degenerate interval at the percentage.
  const ObjectTable& textured = a.objectTables[0][0];
  expectInterval(textured.single[4][0].percentCi, 50.0, 50.0, "cocacola standing");
  expectInterval(textured.single[7][0].percentCi, 100.0 / 3, 100.0 / 3, "greencup standing");
  // No scene, no interval (the estimates are undefined or empty there).
  const GroupResult& lying = a.results[groupIndex(a, "textured-single-lying")][0];
  EXPECT_FALSE(lying.success.rateCi.defined());
  EXPECT_FALSE(lying.firstSuccess.pCi.defined());
  EXPECT_FALSE(lying.distribution.noGraspShareCi.defined());
  EXPECT_FALSE(lying.attempts.exactCi[0].defined());
  EXPECT_FALSE(textured.single[4][1].percentCi.defined());
}

TEST(IntervalsTest, FourScenesWithOneSuccess) {
  // One grasp per scene, a success in one of four: p = 1/4. The number of draws of that scene
  // is binomial(4, 1/4): 0 with probability 81/256, 1 108/256, 2 54/256, 3 12/256, 4 1/256. The
  // 2.5 % quantile lies in the mass at p = 0; the 97.5 % one at p = 3/4, since P(p <= 1/2) =
  // 243/256 = 0.949 and P(p <= 3/4) = 0.996 (the expected counts, 101.6 at p >= 3/4 and 7.8 at
  // p = 1, are far from the 51 and 49 the quantile positions need).
  std::vector<results::RunScene> scenes;
  for (int object = 1; object <= 4; ++object) {
    scenes.push_back(
        scene(database::SceneConditions::single(database::Texture::kPlain, object, 1)));
  }
  const Analysis a = analyze({test_runs::outcomesRun("four", "M", scenes,
                                                     {{GraspOutcome::kStable},
                                                      {GraspOutcome::kMissed},
                                                      {GraspOutcome::kDropped},
                                                      {GraspOutcome::kInCollision}})});
  const GroupResult& r = a.results[groupIndex(a, "plain-single-standing")][0];
  EXPECT_NEAR(r.firstSuccess.p, 0.25, kTol);
  expectInterval(r.firstSuccess.pCi, 0.0, 0.75, "p");
  // One grasp per scene: the success rate is p.
  expectInterval(r.success.rateCi, 0.0, 0.75, "success rate");
  // ga is defined only on resamples that drew the scene with a success: there it is 1.
  expectInterval(r.firstSuccess.gaCi, 1.0, 1.0, "ga");
}

TEST(IntervalsTest, OneSceneGivesADegenerateInterval) {
  const auto s1 = scene(database::SceneConditions::single(database::Texture::kTextured, 5, 1));
  const Analysis a = analyze({test_runs::outcomesRun(
      "one", "M", {s1}, {{GraspOutcome::kStable, GraspOutcome::kMissed, GraspOutcome::kMissed}})});
  const GroupResult& r = a.results[groupIndex(a, "overall")][0];
  expectInterval(r.success.rateCi, 1.0 / 3, 1.0 / 3, "success rate");
  expectInterval(r.firstSuccess.gaCi, 2.0, 2.0, "ga");
}

TEST(IntervalsTest, NoResamplesNoIntervals) {
  AnalysisOptions options;
  options.bootstrapResamples = 0;
  const Analysis a = analyze({test_runs::twoSceneRun()}, options);
  EXPECT_FALSE(a.intervals);
  EXPECT_TRUE(a.comparisons.empty());
  const GroupResult& r = a.results[groupIndex(a, "overall")][0];
  EXPECT_NEAR(r.success.rate, 3.0 / 7, kTol);  // the estimate is there, its interval not
  EXPECT_FALSE(r.success.rateCi.defined());
  EXPECT_FALSE(r.quality.meanQLiftCi.defined());
  EXPECT_FALSE(r.firstSuccess.pCi.defined());
  EXPECT_TRUE(r.attempts.exactCi.empty());
  EXPECT_FALSE(a.objectTables[0][0].single[4][0].percentCi.defined());
}

TEST(IntervalsTest, TheSameSeedGivesTheSameIntervalsWithAnyThreadCount) {
  AnalysisOptions one;
  one.threads = 1;
  AnalysisOptions three = one;
  three.threads = 3;
  const std::vector<results::RunResults> runs = {test_runs::runA(), test_runs::runB(),
                                                 test_runs::twoSceneRun()};
  const Analysis a = analyze(runs, one);
  const Analysis b = analyze(runs, three);
  const auto eq = [](double u, double v) { return u == v || (std::isnan(u) && std::isnan(v)); };
  const auto same = [&eq](const results::Interval& x, const results::Interval& y) {
    return eq(x.low, y.low) && eq(x.high, y.high);
  };
  int defined = 0;
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const GroupResult& x = a.results[g][c];
      const GroupResult& y = b.results[g][c];
      EXPECT_TRUE(same(x.success.rateCi, y.success.rateCi));
      EXPECT_TRUE(same(x.quality.meanQLiftCi, y.quality.meanQLiftCi));
      EXPECT_TRUE(same(x.firstSuccess.gaCi, y.firstSuccess.gaCi));
      for (std::size_t o = 0; o < kOutcomeCount; ++o) {
        EXPECT_TRUE(same(x.distribution.shareCi[o], y.distribution.shareCi[o]));
      }
      for (std::size_t n = 0; n < x.attempts.exactCi.size(); ++n) {
        EXPECT_TRUE(same(x.attempts.exactCi[n], y.attempts.exactCi[n]));
      }
      defined += x.success.rateCi.defined() ? 1 : 0;
    }
  }
  EXPECT_GT(defined, 10);
  ASSERT_EQ(a.comparisons.size(), b.comparisons.size());
  ASSERT_FALSE(a.comparisons.empty());
  for (std::size_t i = 0; i < a.comparisons.size(); ++i) {
    EXPECT_TRUE(same(a.comparisons[i].rate.differenceCi, b.comparisons[i].rate.differenceCi));
    EXPECT_TRUE(eq(a.comparisons[i].rate.pValue, b.comparisons[i].rate.pValue));
    EXPECT_TRUE(eq(a.comparisons[i].p.pValue, b.comparisons[i].p.pValue));
  }
}

TEST(IntervalsTest, OptionsOutOfRangeAreRefused) {
  for (const double level : {0.0, 1.0, -0.5, std::nan("")}) {
    AnalysisOptions o;
    o.ciLevel = level;
    EXPECT_THROW(analyze({test_runs::twoSceneRun()}, o), std::invalid_argument) << level;
  }
  AnalysisOptions negative;
  negative.bootstrapResamples = -1;
  EXPECT_THROW(analyze({test_runs::twoSceneRun()}, negative), std::invalid_argument);
  // Fewer than kMinBootstrapResamples (but not 0): one resample's value x gives [x, x], which
  // need not contain the estimate.
  for (const int few : {1, 2, 99}) {
    AnalysisOptions o;
    o.bootstrapResamples = few;
    try {
      analyze({test_runs::twoSceneRun()}, o);
      ADD_FAILURE() << few;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()),
                "bootstrapResamples must be 0 (no intervals) or at least 100, got " +
                    std::to_string(few) +
                    " (the interval's ends would be the extremes of a few resamples, which need "
                    "not contain the estimate)");
    }
  }
  AnalysisOptions hundred;
  hundred.bootstrapResamples = kMinBootstrapResamples;
  EXPECT_NO_THROW(analyze({test_runs::twoSceneRun()}, hundred));
  AnalysisOptions noPermutation;
  noPermutation.permutations = 0;
  EXPECT_THROW(analyze({test_runs::twoSceneRun()}, noPermutation), std::invalid_argument);
  AnalysisOptions noThread;
  noThread.threads = 0;
  EXPECT_THROW(analyze({test_runs::twoSceneRun()}, noThread), std::invalid_argument);
}

TEST(IntervalsTest, EachFrontEndNamesTheOptionItsOwnWay) {
  AnalysisOptions o;
  o.ciLevel = 1.5;
  auto problem = checkOptions(o);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->field, "ciLevel");
  EXPECT_EQ(problem->cliOption, "--ci-level");
  EXPECT_EQ(problem->pythonArgument, "ci_level");
  // The number as given (its shortest text), not std::to_string's 1.500000.
  EXPECT_EQ(problem->problem, "must be between 0 and 1 (exclusive), got 1.5");
  o.ciLevel = 0.95;
  o.bootstrapResamples = 1;
  problem = checkOptions(o);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->cliOption, "--bootstrap");
  EXPECT_EQ(problem->pythonArgument, "bootstrap");
  o.bootstrapResamples = 0;
  EXPECT_FALSE(checkOptions(o));
  o.threads = 0;
  problem = checkOptions(o);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->pythonArgument, "threads");
  EXPECT_EQ(problem->problem, "must be at least 1, got 0");
}

TEST(IntervalsTest, RunsOfTheSameFolderNameGetTheirOwnStreams) {
  // Two runs of the same trials, labelled as results::readResultFolders labels
  // benchA/results and benchB/results: the labels key the streams (docs/report.md, "The seed"),
  // so their intervals differ by the bootstrap's noise, and each is what it is alone.
  results::RunResults a = test_runs::runA();
  a.label = "benchA/results";
  results::RunResults b = test_runs::runA();
  b.label = "benchB/results";
  const Analysis both = analyze({a, b});
  ASSERT_EQ(both.columns.size(), 2u);
  EXPECT_EQ(both.columns[0].label, "benchA/results: A");
  EXPECT_EQ(both.columns[1].label, "benchB/results: A");
  const Analysis aloneB = analyze({b});
  int differ = 0;
  int defined = 0;
  for (std::size_t g = 0; g < both.groups.size(); ++g) {
    const results::Interval& x = both.results[g][0].success.rateCi;
    const results::Interval& y = both.results[g][1].success.rateCi;
    const results::Interval& z = aloneB.results[g][0].success.rateCi;
    if (!x.defined()) continue;
    ++defined;
    differ += x.low != y.low || x.high != y.high ? 1 : 0;
    EXPECT_EQ(y.low, z.low);
    EXPECT_EQ(y.high, z.high);
  }
  EXPECT_GT(defined, 3);
  EXPECT_GT(differ, 0);
  // The same label twice cannot be told apart: refused.
  b.label = a.label;
  try {
    analyze({a, b});
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "runs 1 and 2 have the same label 'benchA/results' (results::readResultFolders "
              "labels folders apart)");
  }
}

}  // namespace
}  // namespace visgrab::analysis
