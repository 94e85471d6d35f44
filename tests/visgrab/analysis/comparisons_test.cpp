// Method against method on hand-made pairs of runs with a known difference, and the robust
// rates of hand-made repeated trials.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "support/test_support.hpp"
#include "test_runs.hpp"
#include "visgrab/analysis/analysis.hpp"
#include "visgrab/analysis/detail/report_tables.hpp"
#include "visgrab/analysis/report.hpp"

namespace visgrab::analysis {
namespace {

using rwsim::trial::GraspOutcome;
using test_runs::scene;

constexpr double kTol = 1e-12;

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Ten textured single standing scenes (objects 1..10, pose 1).
std::vector<results::RunScene> tenScenes() {
  std::vector<results::RunScene> scenes;
  for (int object = 1; object <= 10; ++object) {
    scenes.push_back(
        scene(database::SceneConditions::single(database::Texture::kTextured, object, 1)));
  }
  return scenes;
}

/// Method `method` of run `label` on tenScenes(): two grasps per scene, the first stable, the
/// second `second`.
results::RunResults tenSceneRun(const std::string& label, const std::string& method,
                                GraspOutcome second) {
  const std::vector<GraspOutcome> outcomes = {GraspOutcome::kStable, second};
  return test_runs::outcomesRun(label, method, tenScenes(),
                                std::vector<std::vector<GraspOutcome>>(10, outcomes));
}

const Comparison& overall(const Analysis& a) {
  for (const Comparison& c : a.comparisons) {
    if (a.groups[c.group].key == "overall") return c;
  }
  throw std::logic_error("no overall comparison");
}

TEST(ComparisonsTest, EveryGraspAgainstHalfOfThem) {
  // A holds both grasps of every scene, B one of two: every resample of the scenes gives
  // 1 - 1/2, so the interval is [0.5, 0.5]. A permutation swaps A and B within each scene with
  // probability 1/2; its pooled difference is (sum of +-1 over the scenes) / 20, as large as the
  // observed 0.5 only when all ten signs agree: probability 2/1024, so about 19.5 of the 10,000
  // permutations and p about (1 + 19.5) / 10,001 = 0.002 (4 to 49 of them: p in [0.0005,
  // 0.005], outside it with a probability below 1e-9). p (a success in the scene) is 1 for both:
  // difference 0, every permutation as large, p-value exactly 1.
  results::RunResults a = tenSceneRun("runA", "A", GraspOutcome::kSlipped);
  results::RunResults b = tenSceneRun("runB", "B", GraspOutcome::kMissed);
  a.sources.hand = "/hands/sdh/sdh.grasp.xml";
  b.sources.hand = "/hands/pg70/pg70.grasp.xml";
  a.sources.engine = "";  // older runs: ODE
  b.sources.engine = "ode";
  a.sources.engineSettings = "ODE 0.16.2; step 0.005 s";
  b.sources.engineSettings = "ODE 0.16.2; step 0.001 s";
  const Analysis analysis = analyze({a, b});
  // Shared scenes in the groups that hold them: single standing, single all, textured all,
  // overall.
  ASSERT_EQ(analysis.comparisons.size(), 4u);
  const Comparison& c = overall(analysis);
  EXPECT_EQ(c.columnA, 0u);
  EXPECT_EQ(c.columnB, 1u);
  EXPECT_EQ(c.scenes, 10);
  EXPECT_NEAR(c.rate.a, 1.0, kTol);
  EXPECT_NEAR(c.rate.b, 0.5, kTol);
  EXPECT_NEAR(c.rate.difference, 0.5, kTol);
  EXPECT_NEAR(c.rate.differenceCi.low, 0.5, kTol);
  EXPECT_NEAR(c.rate.differenceCi.high, 0.5, kTol);
  EXPECT_GE(c.rate.pValue, 0.0005);
  EXPECT_LE(c.rate.pValue, 0.005);
  EXPECT_NEAR(c.p.difference, 0.0, kTol);
  EXPECT_NEAR(c.p.differenceCi.low, 0.0, kTol);
  EXPECT_NEAR(c.p.differenceCi.high, 0.0, kTol);
  EXPECT_EQ(c.p.pValue, 1.0);
  EXPECT_EQ(c.runDifferences, (std::vector<std::string>{"hand", "engine settings"}));

  const std::vector<std::string> sentences = detail::comparisonSentences(analysis);
  ASSERT_EQ(sentences.size(), 1u);
  EXPECT_EQ(sentences[0],
            "A succeeds 50.0 points more often than B (95 % CI 50.0 to 50.0). Their runs differ "
            "in hand and engine settings.");
}

TEST(ComparisonsTest, TheBetterMethodComesFirstWhateverTheColumnOrder) {
  // B's column first: A - B is negative in the data, the sentence still names the better one.
  const Analysis analysis = analyze({tenSceneRun("runB", "B", GraspOutcome::kMissed),
                                     tenSceneRun("runA", "A", GraspOutcome::kStable)});
  const Comparison& c = overall(analysis);
  EXPECT_NEAR(c.rate.difference, -0.5, kTol);
  EXPECT_EQ(detail::comparisonSentences(analysis).front(),
            "A succeeds 50.0 points more often than B (95 % CI 50.0 to 50.0).");
  const Table winners = detail::winnersTable(analysis);
  ASSERT_EQ(winners.rows.size(), 1u);
  EXPECT_EQ(winners.rows[0][0].text, "A");
  EXPECT_EQ(winners.rows[0][1].text, "B");
  EXPECT_NEAR(winners.rows[0][3].value, 50.0, kTol);
  EXPECT_EQ(winners.rows[0][5].text, "yes");  // [50, 50] excludes 0
  EXPECT_EQ(winners.rows[0][8].text, "no");   // p: [0, 0]
}

TEST(ComparisonsTest, IdenticalRunsDifferByNothing) {
  const results::RunResults a = tenSceneRun("first", "A", GraspOutcome::kMissed);
  results::RunResults b = a;
  b.label = "second";
  const Analysis analysis = analyze({a, b});
  const Comparison& c = overall(analysis);
  EXPECT_EQ(c.rate.difference, 0.0);
  EXPECT_EQ(c.rate.differenceCi.low, 0.0);
  EXPECT_EQ(c.rate.differenceCi.high, 0.0);
  EXPECT_EQ(c.rate.pValue, 1.0);
  EXPECT_EQ(c.p.pValue, 1.0);
  EXPECT_TRUE(c.runDifferences.empty());
  EXPECT_EQ(detail::comparisonSentences(analysis).front(),
            "first: A and second: A succeed equally often (95 % CI 0.0 to 0.0).");
}

TEST(ComparisonsTest, OnlyTheSharedScenesArePaired) {
  // B ran on the first five scenes only.
  results::RunResults b = tenSceneRun("runB", "B", GraspOutcome::kMissed);
  b.scenes.resize(5);
  b.trials.resize(10);
  const Analysis analysis = analyze({tenSceneRun("runA", "A", GraspOutcome::kStable), b});
  const Comparison& c = overall(analysis);
  EXPECT_EQ(c.scenes, 5);
  EXPECT_NEAR(c.rate.b, 0.5, kTol);
}

TEST(ComparisonsTest, DifferingSourcesNamesEachField) {
  results::RunSources a;
  results::RunSources b;
  EXPECT_TRUE(differingSources(a, b).empty());
  b.engine = "ode";  // the default of older runs
  EXPECT_TRUE(differingSources(a, b).empty());
  b.engine = "mujoco";
  b.databaseHash = "0123456789abcdef";
  EXPECT_EQ(differingSources(a, b), (std::vector<std::string>{"engine", "database"}));
  // A shake run against a lift run (whose record is empty), and two protocols of one name.
  b.protocol = "shake";
  b.protocolHash = "00000000000000aa";
  EXPECT_EQ(differingSources(a, b), (std::vector<std::string>{"engine", "protocol", "database"}));
  a.protocol = "shake";
  a.protocolHash = "00000000000000bb";
  EXPECT_EQ(differingSources(a, b), (std::vector<std::string>{"engine", "protocol", "database"}));
}

TEST(ComparisonsTest, TheReportWritesTheComparisons) {
  test::TempDir dir;
  writeReport({tenSceneRun("runA", "A", GraspOutcome::kSlipped),
               tenSceneRun("runB", "B", GraspOutcome::kMissed)},
              dir.path());
  const std::string csv = readText(dir.path() / "comparisons.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "group,method_a,method_b,scenes,rate_a,rate_b,difference,difference_ci_low,"
            "difference_ci_high,p_value,p_a,p_b,p_difference,p_difference_ci_low,"
            "p_difference_ci_high,p_difference_p_value,run_differences");
  EXPECT_NE(csv.find("\noverall,A,B,10,1,0.5,0.5,0.5,0.5,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",1,1,0,0,0,1,\n"), std::string::npos) << csv;
  const std::string md = readText(dir.path() / "report.md");
  EXPECT_NE(md.find("\n## Method against method\n"), std::string::npos);
  EXPECT_NE(md.find("\n- A succeeds 50.0 points more often than B (95 % CI 50.0 to 50.0).\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| A | B | 10 | 50.0 [50.0, 50.0] |"), std::string::npos) << md;
  const std::string html = readText(dir.path() / "report.html");
  EXPECT_NE(html.find("<li>A succeeds 50.0 points more often than B (95 % CI 50.0 to 50.0).</li>"),
            std::string::npos);
  const std::string success = readText(dir.path() / "success.csv");
  EXPECT_NE(success.find("group,method,scenes,grasps,successes,success_rate,success_rate_ci_low,"
                         "success_rate_ci_high\n"),
            std::string::npos);
  EXPECT_NE(success.find("\noverall,A,10,20,20,1,1,1\n"), std::string::npos) << success;
  EXPECT_NE(success.find("\noverall,B,10,20,10,0.5,0.5,0.5\n"), std::string::npos) << success;
}

/// Method "R" with repeats (repeat 0 first):
///  S1 (textured cocacola, pose 1): g0 stable, slipped, dropped, stable: P = 3/4;
///                                  g1 missed x 4: P = 0;
///  S2 (textured greencup, pose 2): g0 stable x 4: P = 1.
/// One repeat of S1's g1 hit the closing cap (only repeat 0 counts for the analyses).
results::RunResults repeatedRun() {
  const auto s1 = scene(database::SceneConditions::single(database::Texture::kTextured, 5, 1));
  const auto s2 = scene(database::SceneConditions::single(database::Texture::kTextured, 8, 2));
  results::RunResults run = test_runs::outcomesRun(
      "rep", "R", {s1, s2},
      {{GraspOutcome::kStable, GraspOutcome::kMissed}, {GraspOutcome::kStable}});
  const results::TrialRecord g0 = run.trials[0];
  const results::TrialRecord g1 = run.trials[1];
  const results::TrialRecord h0 = run.trials[2];
  using test_runs::repeated;
  for (const auto& [repeat, outcome] : std::vector<std::pair<int, GraspOutcome>>{
           {1, GraspOutcome::kSlipped}, {2, GraspOutcome::kDropped}, {3, GraspOutcome::kStable}}) {
    run.trials.push_back(repeated(g0, repeat, outcome));
    run.trials.push_back(repeated(g1, repeat, GraspOutcome::kMissed));
    run.trials.push_back(repeated(h0, repeat, GraspOutcome::kStable));
  }
  run.trials[4].closingCapped = true;
  return run;
}

TEST(RobustTest, RatesOfHandMadeRepeats) {
  const Analysis a = analyze({repeatedRun()});
  // One row per group (the empty ones undefined); S1 and S2 are in single standing, single all,
  // textured all and overall.
  ASSERT_EQ(a.robust.size(), a.groups.size());
  int withGrasps = 0;
  for (const RobustRate& r : a.robust) {
    SCOPED_TRACE(a.groups[r.group].key);
    if (r.grasps == 0) {
      EXPECT_TRUE(std::isnan(r.rate));
      EXPECT_FALSE(r.rateCi.defined());
      continue;
    }
    ++withGrasps;
    EXPECT_EQ(r.grasps, 3);
    EXPECT_EQ(r.trials, 12);
    // Mean P = (3/4 + 0 + 1) / 3; borderline: only S1's g0.
    EXPECT_NEAR(r.rate, 7.0 / 12, kTol);
    EXPECT_NEAR(r.borderlineShare, 1.0 / 3, kTol);
    // Two scenes: the ends are S1 alone (P 3/4 and 0: 3/8, borderline 1/2) and S2 alone (1, 0).
    EXPECT_NEAR(r.rateCi.low, 3.0 / 8, kTol);
    EXPECT_NEAR(r.rateCi.high, 1.0, kTol);
    EXPECT_NEAR(r.borderlineShareCi.low, 0.0, kTol);
    EXPECT_NEAR(r.borderlineShareCi.high, 0.5, kTol);
  }
  EXPECT_EQ(withGrasps, 4);
  // The paper's analyses see the three unperturbed trials only.
  const GroupResult& overallResult = a.results.back()[0];
  EXPECT_EQ(overallResult.distribution.grasps, 3);
  EXPECT_EQ(overallResult.success.successes, 2);
  EXPECT_EQ(a.columns[0].closingCapped, 0);
}

TEST(RobustTest, RepeatsNeverInflateThePapersAnalyses) {
  results::RunResults unperturbed = repeatedRun();
  std::erase_if(unperturbed.trials, [](const results::TrialRecord& t) { return t.repeat > 0; });
  test::TempDir with;
  test::TempDir without;
  writeReport({repeatedRun()}, with.path());
  writeReport({unperturbed}, without.path());
  for (const char* file : {"distribution.csv", "quality.csv", "attempts.csv", "first_success.csv",
                           "objects.csv", "success.csv"}) {
    EXPECT_EQ(readText(with.path() / file), readText(without.path() / file)) << file;
  }
  EXPECT_FALSE(std::filesystem::exists(without.path() / "robust.csv"));
  const std::string robust = readText(with.path() / "robust.csv");
  EXPECT_EQ(robust.substr(0, robust.find('\n')),
            "group,method,grasps,trials,robust_rate,robust_rate_ci_low,robust_rate_ci_high,"
            "borderline_share,borderline_share_ci_low,borderline_share_ci_high");
  EXPECT_NE(robust.find("\noverall,R,3,12,0.5833333333333334,0.375,1,0.3333333333333333,0,0.5\n"),
            std::string::npos)
      << robust;
  const std::string md = readText(with.path() / "report.md");
  EXPECT_NE(md.find("\n## Robust success over repeats\n"), std::string::npos);
  EXPECT_NE(md.find("| overall | R | 3 | 12 | 0.583 [0.375, 1.000] | 0.333 [0.000, 0.500] |"),
            std::string::npos)
      << md;
  EXPECT_EQ(readText(without.path() / "report.md").find("Robust"), std::string::npos);
}

}  // namespace
}  // namespace visgrab::analysis
