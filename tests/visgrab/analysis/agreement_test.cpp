#include "visgrab/analysis/agreement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "support/test_support.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/results/results_file.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::analysis::Agreement;
using visgrab::analysis::compareRuns;
using visgrab::analysis::HeldAgreement;
using visgrab::analysis::readAgreementRun;
using visgrab::database::SceneConditions;
using visgrab::database::sceneIdOf;
using visgrab::database::Texture;
using Outcome = rwsim::trial::GraspOutcome;

const std::string kT1 = sceneIdOf(SceneConditions::single(Texture::kTextured, 5, 1));
const std::string kP1 = sceneIdOf(SceneConditions::single(Texture::kPlain, 1, 3));
const std::string kD1 = sceneIdOf(SceneConditions::pairScene(Texture::kTextured, 'e', 1));

/// run.csv of the three scenes, method "top" and database `database`.
std::string runCsv(const std::string& database, const std::string& engine) {
  return "record,id,texture,kind,arrangement,objects,pose,count\n"
         "scene," +
         kT1 + ",textured,single,standing,5,1,\n" + "scene," + kP1 +
         ",plain,single,standing,1,3,\n" + "scene," + kD1 +
         ",textured,double,apart,5 14,1,\n"
         "method,top,,,,,,\n"
         "database," +
         database + ",,,,,,\n" + "engine," + engine + ",,,,,,\n";
}

/// One trials.csv record of method "top".
std::string trial(const std::string& scene, int rank, const std::string& outcome, int code) {
  const bool held = outcome == "stable" || outcome == "slipped";
  return scene + ",top,g" + std::to_string(rank) + "," + std::to_string(rank) + "," + outcome +
         "," + std::to_string(code) + "," + (held ? "0.5" : "0") + ",0,0," + (held ? "5" : "0") +
         ",1.5,\"\"\n";
}

const std::string kTrialsColumns =
    "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,simulated_time,"
    "detail\n";

// The hand-made pair of runs. Shared trials, A's outcome -> B's (H: held, -: not held):
//   #  scene grasp  A                 B                  held A/B
//   1  T1    g0     stable            stable             H H
//   2  T1    g1     stable            slipped            H H   (outcome differs)
//   3  T1    g2     slipped           dropped            H -
//   4  T1    g3     dropped           dropped            - -
//   5  P1    g0     stable            stable             H H
//   6  P1    g1     missed            stable             - H
//   7  P1    g2     stable            stable             H H
//   8  D1    g0     stable            stable             H H
//   9  D1    g1     dropped           missed             - -   (outcome differs)
//  10  D1    g2     timeout           stable             - H
// decided before simulation in either run (counted apart, not in the figures):
//  11  T1    g4     in_collision      in_collision
//  12  P1    g3     invalid_contacts  invalid_contacts
//  13  D1    g3     in_collision      stable             (a different placement)
// unmatched: T1 g5 only in A (stable), P1 g5 only in B (dropped).
//
// Overall over the 10 simulated trials: both held a = 5 (1, 2, 5, 7, 8), only A b = 1 (3),
// only B c = 2 (6, 10), neither d = 2 (4, 9).
//   p_o = (a + d) / n = 7/10 = 0.7
//   p_A = (a + b) / n = 6/10, p_B = (a + c) / n = 7/10
//   p_e = 0.6 * 0.7 + 0.4 * 0.3 = 0.42 + 0.12 = 0.54
//   kappa = (0.7 - 0.54) / (1 - 0.54) = 0.16 / 0.46 = 0.347826...
//   SE = sqrt(p_o (1 - p_o) / (n (1 - p_e)^2)) = sqrt(0.21 / (10 * 0.2116)) = 0.315030...
//   95 %: 0.3478 -/+ 1.96 * 0.3150 = -0.2696 .. 0.9653
// textured, single (T1, cocacola): a 2, b 1, c 0, d 1: p_o 3/4, p_A 3/4, p_B 1/2,
//   p_e = 3/8 + 1/8 = 1/2, kappa = (3/4 - 1/2) / (1/2) = 0.5; SE sqrt(3/16 / (4/4)) = 0.4330
// plain, single (P1, amicelli): a 2, b 0, c 1, d 0: p_o 2/3, p_A 2/3, p_B 1, p_e = 2/3,
//   kappa = 0
// textured, double (D1, pair e): a 1, b 0, c 1, d 1: p_o 2/3, p_A 1/3, p_B 2/3,
//   p_e = 2/9 + 2/9 = 4/9, kappa = (6/9 - 4/9) / (5/9) = 0.4
std::string trialsA() {
  return kTrialsColumns + trial(kT1, 0, "stable", 1) + trial(kT1, 1, "stable", 1) +
         trial(kT1, 2, "slipped", 5) + trial(kT1, 3, "dropped", 4) +
         trial(kT1, 4, "in_collision", 2) + trial(kT1, 5, "stable", 1) +
         trial(kP1, 0, "stable", 1) + trial(kP1, 1, "missed", 3) + trial(kP1, 2, "stable", 1) +
         trial(kP1, 3, "invalid_contacts", 8) + trial(kD1, 0, "stable", 1) +
         trial(kD1, 1, "dropped", 4) + trial(kD1, 2, "timeout", 6) +
         trial(kD1, 3, "in_collision", 2);
}

std::string trialsB() {
  // In another order than A's: matching goes by key, not by line.
  return kTrialsColumns + trial(kD1, 3, "stable", 1) + trial(kD1, 2, "stable", 1) +
         trial(kD1, 1, "missed", 3) + trial(kD1, 0, "stable", 1) + trial(kT1, 0, "stable", 1) +
         trial(kT1, 1, "slipped", 5) + trial(kT1, 2, "dropped", 4) + trial(kT1, 3, "dropped", 4) +
         trial(kT1, 4, "in_collision", 2) + trial(kP1, 0, "stable", 1) +
         trial(kP1, 1, "stable", 1) + trial(kP1, 2, "stable", 1) +
         trial(kP1, 3, "invalid_contacts", 8) + trial(kP1, 5, "dropped", 4);
}

class AgreementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    database_ = dir_.path() / "database";
    visgrab::test::writeFile(database_ / "index.xml", "<index/>\n");
    dirA_ = dir_.path() / "ode-run";
    dirB_ = dir_.path() / "mujoco-run";
    visgrab::test::writeFile(dirA_ / "run.csv", runCsv(database_.string(), "ode"));
    visgrab::test::writeFile(dirA_ / "trials.csv", trialsA());
    visgrab::test::writeFile(dirB_ / "run.csv", runCsv(database_.string(), "mujoco"));
    visgrab::test::writeFile(dirB_ / "trials.csv", trialsB());
  }

  Agreement compare() const {
    return compareRuns(readAgreementRun(dirA_), readAgreementRun(dirB_));
  }

  static const HeldAgreement& group(const Agreement& a, const std::string& key) {
    for (const auto& g : a.groups) {
      if (g.key == key) return g;
    }
    throw std::out_of_range("no group " + key);
  }

  visgrab::test::TempDir dir_;
  fs::path database_, dirA_, dirB_;
};

std::size_t index(Outcome o) { return static_cast<std::size_t>(o); }

// Expects `what()` of the exception `run` throws to contain `needle`.
template <class F>
void expectInvalidArgument(F run, const std::string& needle) {
  try {
    run();
    ADD_FAILURE() << "no exception; expected one naming " << needle;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(HeldAgreement, KappaOfAHandWorkedTable) {
  const HeldAgreement h = visgrab::analysis::heldAgreement(5, 1, 2, 2);
  EXPECT_EQ(h.trials, 10);
  EXPECT_DOUBLE_EQ(h.observedAgreement, 0.7);
  EXPECT_DOUBLE_EQ(h.heldShareA, 0.6);
  EXPECT_DOUBLE_EQ(h.heldShareB, 0.7);
  EXPECT_NEAR(h.expectedAgreement, 0.54, 1e-12);
  EXPECT_NEAR(h.kappa, 0.16 / 0.46, 1e-12);
  EXPECT_NEAR(h.kappaStandardError, std::sqrt(0.21 / (10 * 0.46 * 0.46)), 1e-12);
  EXPECT_NEAR(h.kappaLow, 0.16 / 0.46 - 1.959963984540054 * 0.31502992926498785, 1e-9);
  EXPECT_NEAR(h.kappaHigh, 0.16 / 0.46 + 1.959963984540054 * 0.31502992926498785, 1e-9);
}

TEST(HeldAgreement, PerfectAgreementIsOneAndTheIntervalIsClipped) {
  // a 3, d 1: p_o 1, p_A = p_B = 3/4, p_e = 9/16 + 1/16 = 5/8, kappa 1, SE 0.
  const HeldAgreement h = visgrab::analysis::heldAgreement(3, 0, 0, 1);
  EXPECT_DOUBLE_EQ(h.kappa, 1.0);
  EXPECT_DOUBLE_EQ(h.kappaStandardError, 0.0);
  EXPECT_DOUBLE_EQ(h.kappaHigh, 1.0);
  // T1's table: kappa 0.5 + 1.96 * 0.433 > 1 is clipped to 1.
  EXPECT_DOUBLE_EQ(visgrab::analysis::heldAgreement(2, 1, 0, 1).kappaHigh, 1.0);
}

TEST(HeldAgreement, KappaIsUndefinedWithoutTrialsOrWhenChanceAgreementIsOne) {
  EXPECT_TRUE(std::isnan(visgrab::analysis::heldAgreement(0, 0, 0, 0).kappa));
  EXPECT_TRUE(std::isnan(visgrab::analysis::heldAgreement(0, 0, 0, 0).observedAgreement));
  // Every trial held in both: p_o = p_e = 1.
  const HeldAgreement all = visgrab::analysis::heldAgreement(4, 0, 0, 0);
  EXPECT_DOUBLE_EQ(all.observedAgreement, 1.0);
  EXPECT_TRUE(std::isnan(all.kappa));
  EXPECT_THROW(visgrab::analysis::heldAgreement(-1, 0, 0, 0), std::invalid_argument);
}

TEST_F(AgreementTest, CountsSharedAndUnmatchedTrials) {
  const Agreement a = compare();
  EXPECT_EQ(a.trialsA, 14);
  EXPECT_EQ(a.trialsB, 14);
  EXPECT_EQ(a.shared, 13);
  EXPECT_EQ(a.onlyInA, 1);
  EXPECT_EQ(a.onlyInB, 1);
  EXPECT_EQ(a.engineA, "ode");
  EXPECT_EQ(a.engineB, "mujoco");
  EXPECT_EQ(a.database, database_);
}

TEST_F(AgreementTest, ConfusionMatrixHasAsOutcomesInRowsAndBsInColumns) {
  const Agreement a = compare();
  std::array<std::array<int, visgrab::analysis::kAgreementOutcomeCount>,
             visgrab::analysis::kAgreementOutcomeCount>
      expected{};
  expected[index(Outcome::kStable)][index(Outcome::kStable)] = 4;                    // 1, 5, 7, 8
  expected[index(Outcome::kStable)][index(Outcome::kSlipped)] = 1;                   // 2
  expected[index(Outcome::kSlipped)][index(Outcome::kDropped)] = 1;                  // 3
  expected[index(Outcome::kDropped)][index(Outcome::kDropped)] = 1;                  // 4
  expected[index(Outcome::kDropped)][index(Outcome::kMissed)] = 1;                   // 9
  expected[index(Outcome::kMissed)][index(Outcome::kStable)] = 1;                    // 6
  expected[index(Outcome::kTimeout)][index(Outcome::kStable)] = 1;                   // 10
  expected[index(Outcome::kInCollision)][index(Outcome::kInCollision)] = 1;          // 11
  expected[index(Outcome::kInvalidContacts)][index(Outcome::kInvalidContacts)] = 1;  // 12
  expected[index(Outcome::kInCollision)][index(Outcome::kStable)] = 1;               // 13
  EXPECT_EQ(a.confusion, expected);
}

TEST_F(AgreementTest, OverallHeldAgreementLeavesTheDecidedTrialsOut) {
  const HeldAgreement& h = compare().groups.front();
  EXPECT_EQ(h.key, "overall");
  EXPECT_EQ(h.trials, 10);
  EXPECT_EQ(h.bothHeld, 5);
  EXPECT_EQ(h.onlyAHeld, 1);
  EXPECT_EQ(h.onlyBHeld, 2);
  EXPECT_EQ(h.neitherHeld, 2);
  EXPECT_EQ(h.sameOutcome, 5);  // 1, 4, 5, 7, 8
  EXPECT_DOUBLE_EQ(h.observedAgreement, 0.7);
  EXPECT_NEAR(h.kappa, 0.347826086956522, 1e-12);
  EXPECT_NEAR(h.kappaStandardError, 0.315029929264988, 1e-12);
  EXPECT_DOUBLE_EQ(h.heldShareA, 0.6);
  EXPECT_DOUBLE_EQ(h.heldShareB, 0.7);
  // 11, 12 and 13; 11 and 12 alike (the same placement decides them alike), 13 not.
  EXPECT_EQ(h.decidedBeforeSimulation, 3);
  EXPECT_EQ(h.decidedSame, 2);
}

TEST_F(AgreementTest, PerConditionAndPerObjectFigures) {
  const Agreement a = compare();
  std::vector<std::string> keys;
  for (const auto& g : a.groups) keys.push_back(g.key);
  // No plain double scene: that group is left out. Objects by id, then pairs.
  EXPECT_EQ(keys, (std::vector<std::string>{"overall", "textured-single-all", "textured-double-all",
                                            "plain-single-all", "amicelli", "cocacola", "pair-e"}));
  const HeldAgreement& ts = group(a, "textured-single-all");
  EXPECT_EQ(ts.kind, "condition");
  EXPECT_EQ(ts.trials, 4);
  EXPECT_DOUBLE_EQ(ts.observedAgreement, 0.75);
  EXPECT_DOUBLE_EQ(ts.kappa, 0.5);
  EXPECT_NEAR(ts.kappaStandardError, std::sqrt(3.0 / 16.0), 1e-12);
  EXPECT_EQ(ts.decidedBeforeSimulation, 1);
  const HeldAgreement& ps = group(a, "plain-single-all");
  EXPECT_EQ(ps.trials, 3);
  EXPECT_NEAR(ps.kappa, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(ps.heldShareB, 1.0);
  const HeldAgreement& td = group(a, "textured-double-all");
  EXPECT_EQ(td.trials, 3);
  EXPECT_NEAR(td.kappa, 0.4, 1e-12);
  EXPECT_EQ(td.decidedBeforeSimulation, 1);
  EXPECT_EQ(td.decidedSame, 0);
  // The objects' groups are their scenes' here.
  const HeldAgreement& coke = group(a, "cocacola");
  EXPECT_EQ(coke.kind, "object");
  EXPECT_DOUBLE_EQ(coke.kappa, 0.5);
  const HeldAgreement& pair = group(a, "pair-e");
  EXPECT_EQ(pair.kind, "pair");
  EXPECT_EQ(pair.name, "pair e (cocacola, saltcylinder)");
  EXPECT_NEAR(pair.kappa, 0.4, 1e-12);
}

TEST_F(AgreementTest, ListsHeldAndOutcomeDisagreementsWithRenderCommands) {
  const Agreement a = compare();
  ASSERT_EQ(a.disagreements.size(), 6u);  // 2, 3, 6, 9, 10, 13 (in A's order)
  const auto& d = a.disagreements;
  EXPECT_EQ(d[0].graspId, "g1");  // 2: stable vs slipped
  EXPECT_FALSE(d[0].heldDiffers);
  EXPECT_TRUE(d[0].simulatedInBoth);
  EXPECT_EQ(d[1].outcomeA, Outcome::kSlipped);  // 3
  EXPECT_EQ(d[1].outcomeB, Outcome::kDropped);
  EXPECT_TRUE(d[1].heldDiffers);
  EXPECT_EQ(d[2].sceneId, kP1);  // 6
  EXPECT_TRUE(d[2].heldDiffers);
  EXPECT_FALSE(d[3].heldDiffers);                   // 9: dropped vs missed
  EXPECT_EQ(d[4].outcomeA, Outcome::kTimeout);      // 10
  EXPECT_EQ(d[5].outcomeA, Outcome::kInCollision);  // 13
  EXPECT_TRUE(d[5].heldDiffers);
  EXPECT_FALSE(d[5].simulatedInBoth);

  const std::string csv = visgrab::analysis::disagreementsCsv(a);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "scene,method,grasp,rank,outcome_a,outcome_b,disagreement,simulated_in_both,render_a,"
            "render_b");
  const std::string render = visgrab::analysis::renderCommand(dirB_, d[1], "x.png");
  EXPECT_EQ(render, "visgrab render --results " + dirB_.string() + " --scene " + kT1 +
                        " --method top --grasp g2 --out x.png");
  EXPECT_NE(csv.find(render.substr(0, render.find(" --out"))), std::string::npos) << csv;
}

TEST_F(AgreementTest, TablesForPandasAndMarkdown) {
  const Agreement a = compare();
  const std::string summary = visgrab::analysis::agreementCsv(a);
  EXPECT_EQ(summary.substr(0, summary.find('\n')),
            "kind,key,name,trials,both_held,only_a_held,only_b_held,neither_held,"
            "observed_agreement,expected_agreement,kappa,kappa_se,kappa_low,kappa_high,"
            "held_share_a,held_share_b,same_outcome,decided_before_simulation,decided_same");
  EXPECT_NE(summary.find("\noverall,overall,overall,10,5,1,2,2,0.7,"), std::string::npos)
      << summary;
  const std::string confusion = visgrab::analysis::confusionCsv(a);
  EXPECT_EQ(confusion.substr(0, confusion.find('\n')),
            "outcome_a,stable,slipped,dropped,missed,in_collision,invalid_contacts,"
            "simulation_failure,timeout");
  EXPECT_NE(confusion.find("\nstable,4,1,0,0,0,0,0,0\n"), std::string::npos) << confusion;
  EXPECT_NE(confusion.find("\nin_collision,1,0,0,0,1,0,0,0\n"), std::string::npos) << confusion;
  const std::string md = visgrab::analysis::agreementMarkdown(a);
  EXPECT_NE(md.find("Cohen's kappa 0.348"), std::string::npos) << md;
  EXPECT_NE(md.find("## Disagreements (6)"), std::string::npos) << md;
  const std::string text = visgrab::analysis::agreementSummary(a);
  EXPECT_NE(text.find("13 shared (1 only in A, 1 only in B: ignored)"), std::string::npos) << text;
  EXPECT_NE(text.find("agreement 70.0 %, kappa 0.348"), std::string::npos) << text;
}

TEST_F(AgreementTest, AFolderThatIsNotARunIsNamed) {
  const fs::path empty = dir_.path() / "not-a-run";
  fs::create_directories(empty);
  expectInvalidArgument([&] { readAgreementRun(empty); },
                        empty.string() +
                            ": not a result folder of `visgrab run` (no run.csv and "
                            "trials.csv)");
  visgrab::test::writeFile(empty / "trials.csv", kTrialsColumns);
  expectInvalidArgument([&] { readAgreementRun(empty); }, empty.string() + ": not a result folder");
  expectInvalidArgument([&] { readAgreementRun(dir_.path() / "missing"); },
                        (dir_.path() / "missing").string() + ": not a folder");
}

TEST_F(AgreementTest, RunsWithoutSharedTrialsAreAnError) {
  const fs::path other = dir_.path() / "other-run";
  visgrab::test::writeFile(other / "run.csv", runCsv(database_.string(), "ode"));
  visgrab::test::writeFile(other / "trials.csv", kTrialsColumns + trial(kT1, 9, "stable", 1));
  expectInvalidArgument([&] { compareRuns(readAgreementRun(dirA_), readAgreementRun(other)); },
                        dirA_.string() + " and " + other.string() + " share no trial");
}

TEST_F(AgreementTest, RunsOnDifferentDatabasesAreAnError) {
  const fs::path otherDb = dir_.path() / "other-database";
  visgrab::test::writeFile(otherDb / "index.xml", "<index other=\"1\"/>\n");
  const fs::path other = dir_.path() / "other-run";
  visgrab::test::writeFile(other / "run.csv", runCsv(otherDb.string(), "mujoco"));
  visgrab::test::writeFile(other / "trials.csv", trialsB());
  expectInvalidArgument([&] { compareRuns(readAgreementRun(dirA_), readAgreementRun(other)); },
                        dirA_.string() + " and " + other.string() + " ran on different databases");
}

TEST_F(AgreementTest, ACopiedDatabaseIsTheSameDatabase) {
  // A copy at another path has the same index: the content decides, not the path.
  const fs::path copy = dir_.path() / "copy";
  visgrab::test::writeFile(copy / "index.xml", "<index/>\n");
  EXPECT_TRUE(visgrab::analysis::sameDatabase(database_, copy));
  EXPECT_TRUE(visgrab::analysis::sameDatabase(database_, fs::path()));
  EXPECT_FALSE(visgrab::analysis::sameDatabase(dir_.path() / "gone-a", dir_.path() / "gone-b"));
  EXPECT_TRUE(visgrab::analysis::sameDatabase(dir_.path() / "gone", dir_.path() / "gone"));
}

// Runs that recorded their database's index hash (run.csv's database_hash) are compared by it:
// the same path with different hashes (the database generated again between the runs) is two
// databases; different paths with one hash (a moved database) is one.
TEST_F(AgreementTest, RecordedIndexHashesDecideWherePathsCannot) {
  visgrab::results::RunSources a;
  a.database = database_;
  a.databaseHash = "0123456789abcdef";
  visgrab::results::RunSources b = a;
  b.databaseHash = "fedcba9876543210";
  EXPECT_FALSE(visgrab::analysis::sameDatabase(a, b));
  b.databaseHash = a.databaseHash;
  b.database = dir_.path() / "moved-away";
  EXPECT_TRUE(visgrab::analysis::sameDatabase(a, b));
  // One run without the record: the paths decide, as for older runs.
  b.databaseHash.clear();
  EXPECT_FALSE(visgrab::analysis::sameDatabase(a, b));
  b.database = database_;
  EXPECT_TRUE(visgrab::analysis::sameDatabase(a, b));

  // Through compareRuns: the same recorded path, other hashes, is refused naming both hashes.
  const fs::path other = dir_.path() / "regenerated-run";
  std::string text = runCsv(database_.string(), "mujoco");
  text += "database_hash,fedcba9876543210,,,,,,\n";
  visgrab::test::writeFile(other / "run.csv", text);
  visgrab::test::writeFile(other / "trials.csv", trialsB());
  std::string textA = runCsv(database_.string(), "ode");
  textA += "database_hash,0123456789abcdef,,,,,,\n";
  visgrab::test::writeFile(dirA_ / "run.csv", textA);
  expectInvalidArgument([&] { compareRuns(readAgreementRun(dirA_), readAgreementRun(other)); },
                        "their recorded index hashes differ, 0123456789abcdef and "
                        "fedcba9876543210");
}

/// Two runs of one grasp with two repeats each: repeat 0 held in both, repeat 1 held only in A.
/// Each repeat pairs with the same repeat of the other run: 2 shared trials, one disagreement
/// (matching by grasp alone would pair both of A's trials with B's first one: no disagreement).
TEST(AgreementRepeats, EachRepeatPairsWithTheSameRepeat) {
  visgrab::results::RunResults a;
  const auto c =
      visgrab::database::SceneConditions::single(visgrab::database::Texture::kTextured, 5, 1);
  a.scenes = {{visgrab::database::sceneIdOf(c), c}};
  a.methods = {"m"};
  visgrab::results::TrialRecord t;
  t.sceneId = a.scenes[0].id;
  t.conditions = c;
  t.method = "m";
  t.graspId = "g";
  t.outcome = rwsim::trial::GraspOutcome::kStable;
  t.object = 5;
  a.trials = {t, t};
  a.trials[1].repeat = 1;
  a.trials[1].seed = 7;
  visgrab::results::RunResults b = a;
  b.trials[1].outcome = rwsim::trial::GraspOutcome::kMissed;
  const Agreement agreement = compareRuns({"A", a}, {"B", b});
  EXPECT_EQ(agreement.shared, 2);
  EXPECT_EQ(agreement.disagreements.size(), 1u);
}

}  // namespace
