#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::test::RunResult;
using visgrab::test::runVisgrab;
using visgrab::test::shellQuoted;

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

constexpr const char* kScene = "textured/single/cocacola/01";

/// A result folder of method "top" on `database` whose grasps g0..g3 ended as `outcomes`
/// (name and RobWork code each).
fs::path writeRun(const fs::path& dir, const fs::path& database, const std::string& engine,
                  const std::vector<std::pair<std::string, int>>& outcomes) {
  visgrab::test::writeFile(dir / "run.csv",
                           "record,id,texture,kind,arrangement,objects,pose,count\n"
                           "scene," +
                               std::string(kScene) +
                               ",textured,single,standing,5,1,\n"
                               "method,top,,,,,,\n"
                               "database," +
                               database.string() + ",,,,,,\nengine," + engine + ",,,,,,\n");
  std::string trials =
      "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,"
      "simulated_time,detail\n";
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    // Appended piece by piece (GCC 12 warns falsely, -Warray-bounds, on the long + chain).
    const std::string n = std::to_string(i);
    trials.append(kScene).append(",top,g").append(n).append(",").append(n).append(",");
    trials.append(outcomes[i].first).append(",").append(std::to_string(outcomes[i].second));
    trials.append(",0,0,0,0,1,\"\"\n");
  }
  visgrab::test::writeFile(dir / "trials.csv", trials);
  return dir;
}

class AgreementCli : public ::testing::Test {
 protected:
  void SetUp() override {
    database_ = dir_.path() / "database";
    visgrab::test::writeFile(database_ / "index.xml", "<index/>\n");
    // A: H H - - X, B: H - H - X (X: in collision, decided before simulation).
    // a = 1, b = 1, c = 1, d = 1: p_o 1/2, p_A = p_B = 1/2, p_e 1/2, kappa 0.
    runA_ = writeRun(
        dir_.path() / "a", database_, "ode",
        {{"stable", 1}, {"stable", 1}, {"dropped", 4}, {"missed", 3}, {"in_collision", 2}});
    runB_ = writeRun(
        dir_.path() / "b", database_, "mujoco",
        {{"stable", 1}, {"missed", 3}, {"slipped", 5}, {"missed", 3}, {"in_collision", 2}});
  }

  visgrab::test::TempDir dir_;
  fs::path database_, runA_, runB_;
};

TEST_F(AgreementCli, PrintsTheSummaryAndWritesTheFourFiles) {
  const fs::path out = dir_.path() / "agreement";
  const RunResult r = runVisgrab("agreement " + shellQuoted(runA_) + " " + shellQuoted(runB_) +
                                 " --out " + shellQuoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("5 shared (0 only in A, 0 only in B: ignored)"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("agreement 50.0 %, kappa 0.000"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("held share: A 50.0 %, B 50.0 %"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("in either run: 1 (1 with the same outcome"), std::string::npos)
      << r.output;

  const std::string summary = readText(out / "agreement.csv");
  EXPECT_NE(summary.find("\noverall,overall,overall,4,1,1,1,1,0.5,0.5,0,"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("\ncondition,textured-single-all,"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\nobject,cocacola,cocacola,4,"), std::string::npos) << summary;
  const std::string confusion = readText(out / "confusion.csv");
  EXPECT_NE(confusion.find("\nstable,1,0,0,1,0,0,0,0\n"), std::string::npos) << confusion;
  EXPECT_NE(confusion.find("\ndropped,0,1,0,0,0,0,0,0\n"), std::string::npos) << confusion;
  const std::string disagreements = readText(out / "disagreements.csv");
  // g1 stable vs missed, g2 dropped vs slipped: both held vs not held.
  EXPECT_NE(disagreements.find(std::string("\n") + kScene +
                               ",top,g1,1,stable,missed,held,true,"
                               "visgrab render --results "),
            std::string::npos)
      << disagreements;
  EXPECT_NE(disagreements.find(std::string("\n") + kScene + ",top,g2,2,dropped,slipped,held,"),
            std::string::npos)
      << disagreements;
  const std::string md = readText(out / "agreement.md");
  EXPECT_NE(md.find("# Agreement between two runs"), std::string::npos) << md;
  EXPECT_NE(md.find("## Disagreements (2)"), std::string::npos) << md;
}

TEST_F(AgreementCli, BadRunsExitOneNamingTheFolder) {
  const fs::path notARun = dir_.path() / "nothing";
  fs::create_directories(notARun);
  const RunResult r = runVisgrab("agreement " + shellQuoted(runA_) + " " + shellQuoted(notARun));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(notARun.string() + ": not a result folder"), std::string::npos)
      << r.output;

  const fs::path otherDb = dir_.path() / "other-database";
  visgrab::test::writeFile(otherDb / "index.xml", "<index other=\"1\"/>\n");
  const fs::path c = writeRun(dir_.path() / "c", otherDb, "mujoco", {{"stable", 1}});
  const RunResult d = runVisgrab("agreement " + shellQuoted(runA_) + " " + shellQuoted(c));
  EXPECT_EQ(d.exitCode, 1) << d.output;
  EXPECT_NE(d.output.find("ran on different databases"), std::string::npos) << d.output;
}

TEST_F(AgreementCli, BadArgumentsExitTwo) {
  EXPECT_EQ(runVisgrab("agreement " + shellQuoted(runA_)).exitCode, 2);
  EXPECT_EQ(runVisgrab("agreement " + shellQuoted(runA_) + " " + shellQuoted(runB_) + " " +
                       shellQuoted(runB_))
                .exitCode,
            2);
  EXPECT_EQ(runVisgrab("agreement " + shellQuoted(runA_) + " " + shellQuoted(runB_) + " --bogus")
                .exitCode,
            2);
}

TEST_F(AgreementCli, HelpListsTheCommand) {
  const RunResult r = runVisgrab("--help");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("agreement"), std::string::npos) << r.output;
  const RunResult h = runVisgrab("agreement --help");
  ASSERT_EQ(h.exitCode, 0) << h.output;
  EXPECT_NE(h.output.find("RUN_A"), std::string::npos) << h.output;
  EXPECT_NE(h.output.find("--out"), std::string::npos) << h.output;
}

}  // namespace
