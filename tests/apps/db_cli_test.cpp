// `visgrab db generate | list | show` on a one-scene database made by the command itself.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"

namespace {

using visgrab::test::RunResult;
using visgrab::test::runVisgrab;
using visgrab::test::shellQuoted;

TEST(DbCli, GeneratesListsAndShowsAScene) {
  visgrab::test::TempDir dir;
  const auto db = dir.path() / "db";
  const RunResult made = runVisgrab("db generate --out " + shellQuoted(db) +
                                    " --scenes 'plain,single,cocacola,pose=1' --threads 1");
  ASSERT_EQ(made.exitCode, 0) << made.output;
  EXPECT_NE(made.output.find("1 scenes generated, 0 already complete, 0 failed"), std::string::npos)
      << made.output;
  // Progress on stderr.
  EXPECT_NE(made.output.find("1/1 scenes"), std::string::npos) << made.output;
  for (const char* file :
       {"left.png", "right.png", "calibration.yml", "scene.wc.xml", "scene.dwc.xml"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(db / "scenes/plain/single/cocacola/01" / file))
        << file;
  }
  // Again: nothing left to do.
  const RunResult again = runVisgrab("db generate --out " + shellQuoted(db) +
                                     " --scenes 'plain,single,cocacola,pose=1' --quiet");
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("0 scenes generated, 1 already complete"), std::string::npos)
      << again.output;

  const RunResult list = runVisgrab("db list --db " + shellQuoted(db));
  ASSERT_EQ(list.exitCode, 0) << list.output;
  EXPECT_NE(list.output.find("plain/single/cocacola/01"), std::string::npos) << list.output;
  EXPECT_NE(list.output.find("1 of 1 scenes"), std::string::npos) << list.output;

  const RunResult show =
      runVisgrab("db show --db " + shellQuoted(db) + " plain/single/cocacola/01");
  ASSERT_EQ(show.exitCode, 0) << show.output;
  EXPECT_NE(show.output.find("cocacola"), std::string::npos) << show.output;
  EXPECT_NE(show.output.find("calibration.yml"), std::string::npos) << show.output;
  // Every file of the scene, the disparity, point cloud and ground truth too.
  for (const char* file : {"left.png", "right.png", "scene.wc.xml", "scene.dwc.xml",
                           "disparity.png", "cloud.ply", "depth.png", "mask.png", "poses.yml"}) {
    EXPECT_NE(show.output.find(std::string("plain/single/cocacola/01/") + file), std::string::npos)
        << file << " in\n"
        << show.output;
  }
  EXPECT_EQ(show.output.find("(missing)"), std::string::npos) << show.output;

  // An unknown id names the id and suggests the scene that exists.
  const RunResult unknown =
      runVisgrab("db show --db " + shellQuoted(db) + " plain/single/cocacola/02");
  EXPECT_EQ(unknown.exitCode, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("plain/single/cocacola/02"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("plain/single/cocacola/01"), std::string::npos) << unknown.output;
}

TEST(DbCli, BenchmarkGeneratesTheDatabaseRunsTheGraspsAndWritesTheReport) {
  visgrab::test::TempDir dir;
  const auto grasps = visgrab::test::writeFile(
      dir.path() / "grasps.txt",
      "# one SDH_CYL grasp over the table centre, hand pointing down\n"
      "plain/single/cocacola/01, mine, g1, preshape, 0,0,0.06, 0,0,1,0, SDH_CYL\n"
      "plain/single/cocacola/01, mine, g2, preshape, 0,0,0.06, 0,0,1,0, NO_SUCH_SHAPE\n");
  const RunResult r =
      runVisgrab("benchmark --db " + shellQuoted(dir.path() / "db") +
                 " --scenes 'plain,single,cocacola,pose=1' --grasps " + shellQuoted(grasps) +
                 " --out " + shellQuoted(dir.path() / "out") + " --threads 1 --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("generating it"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 trials run, 0 resumed, 1 grasps rejected"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("NO_SUCH_SHAPE"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "db/index.xml"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "out/results/trials.csv"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "out/report/report.html"));
  // Each stage's time at the end, and in OUT/stages.csv.
  EXPECT_NE(r.output.find("stage times (wall, process CPU):"), std::string::npos) << r.output;
  std::ifstream csv(dir.path() / "out/stages.csv");
  std::vector<std::string> stages;
  std::vector<std::string> notes;
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line, "stage,wall_s,cpu_s,note");
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::string stage, wall, cpu, note;
    std::getline(fields, stage, ',');
    std::getline(fields, wall, ',');
    std::getline(fields, cpu, ',');
    std::getline(fields, note);
    stages.push_back(stage);
    notes.push_back(note);
    EXPECT_GE(std::stod(wall), 0.0) << line;
    EXPECT_GE(std::stod(cpu), 0.0) << line;
    EXPECT_NE(r.output.find("  " + stage + " "), std::string::npos) << stage << "\n" << r.output;
  }
  EXPECT_EQ(stages,
            (std::vector<std::string>{"database", "baseline", "trials", "report", "total"}));
  ASSERT_EQ(notes.size(), 5u);
  EXPECT_EQ(notes[0], "1 scenes generated");
  EXPECT_EQ(notes[1], "not run (--grasps)");
  EXPECT_EQ(notes[2], "\"1 trials run, 0 resumed\"");
}

TEST(DbCli, BadArgumentsAreUsageErrors) {
  visgrab::test::TempDir dir;
  const RunResult noOut = runVisgrab("db generate --scenes cocacola");
  EXPECT_EQ(noOut.exitCode, 2) << noOut.output;
  EXPECT_NE(noOut.output.find("--out DIR is required"), std::string::npos) << noOut.output;
  const RunResult badFilter =
      runVisgrab("db generate --out " + shellQuoted(dir.path() / "x") + " --scenes cocacolla");
  EXPECT_EQ(badFilter.exitCode, 2) << badFilter.output;
  EXPECT_NE(badFilter.output.find("cocacolla"), std::string::npos) << badFilter.output;
  const RunResult badThreads =
      runVisgrab("db generate --out " + shellQuoted(dir.path() / "x") + " --threads zero");
  EXPECT_EQ(badThreads.exitCode, 2) << badThreads.output;
  EXPECT_NE(badThreads.output.find("--threads"), std::string::npos) << badThreads.output;
  const RunResult missing = runVisgrab("db list --db " + shellQuoted(dir.path() / "nothing"));
  EXPECT_EQ(missing.exitCode, 1) << missing.output;
  EXPECT_NE(missing.output.find("nothing"), std::string::npos) << missing.output;
}

}  // namespace
