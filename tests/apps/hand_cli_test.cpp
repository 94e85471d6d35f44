// --hand DIR on the commands that simulate, with the project's three hands in a scene of the
// shared test database (generated with the SDH): `visgrab grasp --db --scene --hand --preshape`
// and `visgrab render --hand`; the command-line mistakes.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "rwsim/trial/grasp_outcome.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#include "visgrab/render/png_io.hpp"
#include "visgrab/results/results_file.hpp"

namespace {

using visgrab::test::RunResult;
using visgrab::test::runVisgrab;
using visgrab::test::shellQuoted;

constexpr const char* kScene = "plain/single/cocacola/01";

std::string hand(const char* name) {
  return shellQuoted(visgrab::test::sourceDir() / "scenes/hands" / name);
}

// The hand pointing down (RPY 0 180 0) with its TCP 9 cm above the can's base: every two-finger
// pre-shape "wide" holds the 11.5 cm can from above.
std::string graspArgs(const char* handName, const std::string& preshape = "wide") {
  const auto base = visgrab::test::testDatabase().groundTruth(kScene).front().X_WO.translation();
  char pose[128];
  std::snprintf(pose, sizeof pose, "%.6f %.6f %.6f 0 180 0", base.x(), base.y(), base.z() + 0.09);
  return "grasp --db " + shellQuoted(visgrab::test::testDatabasePath()) + " --scene " + kScene +
         " --hand " + hand(handName) + " --pose " + pose + " --preshape " + preshape;
}

// A grasp file with graspArgs' grasp: grasp 1 of method "plan", the pre-shape "wide" with the
// hand pointing down (quaternion 0 0 1 0) 9 cm above the can's base.
void writePlan(const std::filesystem::path& file) {
  const auto base = visgrab::test::testDatabase().groundTruth(kScene).front().X_WO.translation();
  char line[256];
  std::snprintf(line, sizeof line, "%s, plan, 1, preshape, %.6f,%.6f,%.6f, 0,0,1,0, wide\n", kScene,
                base.x(), base.y(), base.z() + 0.09);
  visgrab::test::writeFile(file, line);
}

TEST(HandCli, GraspRunsEachHandInADatabaseScene) {
  for (const char* name : {"franka", "pg70", "robotiq2f85", "sdh"}) {
    const RunResult r = runVisgrab(graspArgs(name));
    ASSERT_EQ(r.exitCode, 0) << name << "\n" << r.output;
    const bool held = r.output.find("outcome: stable") != std::string::npos ||
                      r.output.find("outcome: slipped") != std::string::npos;
    EXPECT_TRUE(held) << name << "\n" << r.output;
  }
  const RunResult r = runVisgrab(graspArgs("robotiq2f85"));
  EXPECT_NE(r.output.find("hand Robotiq2F85, TCP Robotiq2F85.TCP"), std::string::npos) << r.output;
}

// `visgrab grasp` resolves its grasp as the benchmark does (grasp::resolve, the hand's
// pre-shape at the given TCP pose): the same grasp given to `visgrab run` in a grasp file ends
// with the same outcome and the same Q_lift and Q_GWS.
TEST(HandCli, GraspAndRunTakeTheSameDoor) {
  const RunResult single = runVisgrab(graspArgs("pg70") + " --json");
  ASSERT_EQ(single.exitCode, 0) << single.output;
  const auto number = [&](const std::string& key) {
    const auto at = single.output.find("\"" + key + "\":");
    EXPECT_NE(at, std::string::npos) << single.output;
    return std::strtod(single.output.c_str() + at + key.size() + 3, nullptr);
  };
  const auto text = [&](const std::string& key) {
    const auto at = single.output.find("\"" + key + "\": \"");
    EXPECT_NE(at, std::string::npos) << single.output;
    const auto from = at + key.size() + 5;
    return single.output.substr(from, single.output.find('"', from) - from);
  };
  visgrab::test::TempDir dir;
  writePlan(dir.path() / "plan.csv");
  const RunResult run = runVisgrab("run --db " + shellQuoted(visgrab::test::testDatabasePath()) +
                                   " --grasps " + shellQuoted(dir.path() / "plan.csv") + " --out " +
                                   shellQuoted(dir.path() / "out") + " --hand pg70 --quiet");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const auto results = visgrab::results::readResults(dir.path() / "out");
  ASSERT_EQ(results.trials.size(), 1u);
  const auto& t = results.trials.front();
  EXPECT_EQ(std::string(rwsim::trial::outcomeName(t.outcome)), text("outcome"));
  // The file's quaternion (0, 0, 1, 0) is the exact half turn about y; --pose's RPY 0 180 0
  // leaves sin(pi) = 1.2e-16 in the rotation, which the lift carries into the last digits.
  EXPECT_NEAR(t.qLift, number("q_lift"), 1e-6);
  EXPECT_NEAR(t.qGws, number("q_gws"), 1e-6);
}

// `run --hand franka`: the Franka Hand by name (the data folder's hands/franka), the plan's
// pre-shape "wide" (fully open, 80 mm) from above holds the can.
TEST(HandCli, RunTakesTheFrankaByName) {
  visgrab::test::TempDir dir;
  writePlan(dir.path() / "plan.csv");
  const RunResult run = runVisgrab("run --db " + shellQuoted(visgrab::test::testDatabasePath()) +
                                   " --grasps " + shellQuoted(dir.path() / "plan.csv") + " --out " +
                                   shellQuoted(dir.path() / "out") + " --hand franka --quiet");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const auto results = visgrab::results::readResults(dir.path() / "out");
  ASSERT_EQ(results.trials.size(), 1u);
  const auto outcome = results.trials.front().outcome;
  EXPECT_TRUE(outcome == rwsim::trial::GraspOutcome::kStable ||
              outcome == rwsim::trial::GraspOutcome::kSlipped)
      << rwsim::trial::outcomeName(outcome);
}

TEST(HandCli, RenderDrawsTheGivenHand) {
  visgrab::test::TempDir dir;
  writePlan(dir.path() / "plan.csv");
  const RunResult r = runVisgrab(
      "render --db " + shellQuoted(visgrab::test::testDatabasePath()) + " --scene " + kScene +
      " --hand " + hand("robotiq2f85") + " --grasps " + shellQuoted(dir.path() / "plan.csv") +
      " --grasp 1 --size 160x120 --out " + shellQuoted(dir.path() / "r.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("stable, hand Robotiq2F85"), std::string::npos) << r.output;
  EXPECT_EQ(visgrab::render::readPng(dir.path() / "r.png").width, 3 * (160 + 2));
  // A pre-shape the hand does not have is bad input, not an "invalid contacts" picture.
  std::string badLine = kScene;
  badLine.append(", plan, 1, preshape, 0,0,0.2, 0,0,1,0, NOPE\n");
  visgrab::test::writeFile(dir.path() / "bad.csv", badLine);
  const RunResult bad = runVisgrab("render --db " + shellQuoted(visgrab::test::testDatabasePath()) +
                                   " --scene " + kScene + " --hand " + hand("pg70") + " --grasps " +
                                   shellQuoted(dir.path() / "bad.csv") + " --grasp 1 --out " +
                                   shellQuoted(dir.path() / "bad.png"));
  EXPECT_EQ(bad.exitCode, 1) << bad.output;
  EXPECT_NE(bad.output.find("NOPE"), std::string::npos) << bad.output;
}

TEST(HandCli, Mistakes) {
  RunResult r = runVisgrab(graspArgs("pg70", "bogus"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("no pre-shape 'bogus' (PG70, PG70_SMALL)"), std::string::npos)
      << r.output;
  r = runVisgrab("grasp --db " + shellQuoted(visgrab::test::testDatabasePath()) + " --scene " +
                 kScene + " --hand SchunkHand --pose 0 0 0.2 0 180 0 --preshape wide");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--hand with --db names a hand"), std::string::npos) << r.output;
  r = runVisgrab(graspArgs("pg70") + " --tcp PG70.TCPPG70");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--tcp goes with --hand NAME only"), std::string::npos) << r.output;
  r = runVisgrab("grasp --db " + shellQuoted(visgrab::test::testDatabasePath()) +
                 " --pose 0 0 0.2 0 "
                 "180 0 --preshape wide");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--db DIR and --scene ID go together"), std::string::npos) << r.output;
  visgrab::test::TempDir empty;
  r = runVisgrab("run --db " + shellQuoted(visgrab::test::testDatabasePath()) + " --grasps " +
                 shellQuoted(empty.path()) + " --out " + shellQuoted(empty.path() / "out") +
                 " --hand " + shellQuoted(empty.path()));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("holds no grasp description"), std::string::npos) << r.output;
}

// `run --hand NAME` takes a hand of DATA/hands by name, as Python's Hand("pg70") does; an
// unknown name lists the known ones and writes nothing.
TEST(HandCli, RunTakesAHandByName) {
  visgrab::test::TempDir tmp;
  {
    std::FILE* f = std::fopen((tmp.path() / "g.csv").c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "%s, m, g1, preshape, 0,0,0.5, 1,0,0,0, NOPE\n", kScene);
    std::fclose(f);
  }
  const std::string common = "run --db " + shellQuoted(visgrab::test::testDatabasePath()) +
                             " --grasps " + shellQuoted(tmp.path() / "g.csv") + " --out ";
  RunResult r = runVisgrab(common + shellQuoted(tmp.path() / "a") + " --hand pg70");
  EXPECT_EQ(r.exitCode, 1) << r.output;  // its only grasp was rejected: no trial ran
  // The pre-shape is looked up in the PG70's description: the name chose that hand.
  EXPECT_NE(r.output.find("g.csv:1: error: grasp g1: unknown pre-shape \"NOPE\" for hand "
                          "\"PG70\" (known: PG70, PG70_SMALL)"),
            std::string::npos)
      << r.output;
  // A mistyped name is a command-line mistake (exit 2), as --protocol's and --engine's are.
  r = runVisgrab(common + shellQuoted(tmp.path() / "b") + " --hand pg7");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--hand: unknown hand \"pg7\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(known: franka, pg70, robotiq2f85, robwork-robotiq, sdh)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "b"));
}

// A run with nothing to run is a failure a script notices (exit 1): a grasp file without grasps
// (an empty import, say), or one whose grasps are all of scenes outside --scenes.
TEST(HandCli, ARunWithoutAGraspOfItsScenesExitsOne) {
  visgrab::test::TempDir tmp;
  const auto empty = visgrab::test::writeFile(tmp.path() / "empty.csv", "# no grasps\n");
  const std::string db = shellQuoted(visgrab::test::testDatabasePath());
  RunResult r = runVisgrab("run --db " + db + " --grasps " + shellQuoted(empty) + " --out " +
                           shellQuoted(tmp.path() / "a") + " --quiet");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("visgrab run: the grasp files hold no grasp of the run's scenes; no "
                          "trial ran"),
            std::string::npos)
      << r.output;
  const auto other = visgrab::test::writeFile(
      tmp.path() / "other.csv",
      std::string(kScene) + ", m, g1, preshape, 0,0,0.5, 1,0,0,0, SDH_CYL\n");
  r = runVisgrab("run --db " + db + " --grasps " + shellQuoted(other) +
                 " --scenes textured,tomato --out " + shellQuoted(tmp.path() / "b") + " --quiet");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("hold no grasp of the run's scenes"), std::string::npos) << r.output;
  // Without --scenes the run covers the database's 20 scenes: it runs, and says that the 19
  // without a grasp count as scenes where the method suggested none.
  r = runVisgrab("run --db " + db + " --grasps " + shellQuoted(other) + " --out " +
                 shellQuoted(tmp.path() / "c") + " --quiet");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("note: the grasps are of 1 of the run's 20 scenes; the analyses count "
                          "the other 19 as scenes where a method suggested no grasp"),
            std::string::npos)
      << r.output;
}

}  // namespace
