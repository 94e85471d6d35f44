// The command lines of both apps: every option of every command is in its --help (walking the
// CLI11 apps the programs parse with, and reading the binaries' help), and the rules for `=`
// and repeated options are the same everywhere.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "command_line.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#ifdef VISGRAB_VIEWER_BINARY
#include "viewer_options.hpp"
#endif

namespace {

using visgrab::test::RunResult;

// Every command and group under `app` (depth first), `app` included.
void collectCommands(const CLI::App& app, std::vector<const CLI::App*>& out) {
  out.push_back(&app);
  for (const CLI::App* sub : app.get_subcommands({})) collectCommands(*sub, out);
}

// `cmd`'s words after the program name: "db list".
std::string wordsAfterProgram(const CLI::App& cmd) {
  const std::string path = visgrab::app::commandPath(cmd);
  const auto space = path.find(' ');
  return space == std::string::npos ? std::string() : path.substr(space + 1);
}

// Checks that `help` (the text `program ... --help` printed) names every option of `cmd` with
// its value type and default, every command under it, and describes each.
void expectHelpListsEverything(const CLI::App& cmd, const std::string& help,
                               const std::string& what) {
  for (const CLI::Option* opt : cmd.get_options()) {
    EXPECT_FALSE(opt->get_description().empty()) << what << ": " << opt->get_name();
    if (opt->get_positional()) {
      EXPECT_NE(help.find("  " + opt->get_name()), std::string::npos)
          << what << ": positional " << opt->get_name() << "\n"
          << help;
      continue;
    }
    for (const std::string& name : opt->get_lnames()) {
      std::string shown = "--" + name;
      if (opt->get_expected_max() > 0 && !opt->get_type_name().empty()) {
        shown += " " + opt->get_type_name();
      }
      EXPECT_NE(help.find(shown), std::string::npos) << what << ": " << shown << "\n" << help;
    }
    if (!opt->get_default_str().empty()) {
      EXPECT_NE(help.find("=" + opt->get_default_str()), std::string::npos)
          << what << ": the default of " << opt->get_name() << "\n"
          << help;
    }
  }
  for (const CLI::App* sub : cmd.get_subcommands({})) {
    EXPECT_NE(help.find("  " + sub->get_name() + " "), std::string::npos)
        << what << ": command " << sub->get_name() << "\n"
        << help;
  }
}

TEST(CommandLineHelp, EveryVisgrabCommandListsEveryOptionInItsHelp) {
  const auto cli = visgrab::app::makeCommandLine();
  std::vector<const CLI::App*> commands;
  collectCommands(cli->root(), commands);
  std::vector<std::string> leaves;
  for (const CLI::App* cmd : commands) {
    if (cmd->get_subcommands({}).empty()) leaves.push_back(wordsAfterProgram(*cmd));
  }
  EXPECT_EQ(leaves, (std::vector<std::string>{
                        "wc info", "wc check", "sim", "grasp", "db generate", "db from-acronym",
                        "db list", "db show", "db stereo-accuracy", "run", "benchmark", "analyze",
                        "merge", "slurm", "baseline", "render", "agreement", "import"}));
  for (const CLI::App* cmd : commands) {
    const std::string words = wordsAfterProgram(*cmd);
    const RunResult help = visgrab::test::runVisgrab(words + " --help");
    ASSERT_EQ(help.exitCode, 0) << words << "\n" << help.output;
    EXPECT_NE(help.output.find("usage: " + visgrab::app::commandPath(*cmd)), std::string::npos)
        << help.output;
    expectHelpListsEverything(*cmd, help.output, "visgrab " + words);
    // -h is the same everywhere.
    const RunResult h = visgrab::test::runVisgrab(words + " -h");
    EXPECT_EQ(h.exitCode, 0) << words;
    EXPECT_EQ(h.output, help.output) << words;
  }
}

TEST(CommandLineHelp, TheHelpCheckFindsAMissingOption) {
  // The check above fails for an option the help does not show.
  CLI::App app("test", "prog");
  app.add_option("--shown", "shown")->type_name("N");
  app.add_option("--missing", "missing")->type_name("DIR");
  EXPECT_NONFATAL_FAILURE(
      expectHelpListsEverything(app, "  -h,--help  help\n  --shown N  shown\n", "prog"),
      "--missing DIR");
}

TEST(CommandLineRules, EqualsAndRepeatsAreTheSameForEveryCommand) {
  visgrab::test::TempDir dir;
  const std::string missing = visgrab::test::shellQuoted(dir.path() / "no-db");
  // --x=v is --x v: both reach the command (which finds no database: bad input, exit 1).
  for (const std::string& args : {"db list --db " + missing, "db list --db=" + missing}) {
    const RunResult r = visgrab::test::runVisgrab(args);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("no-db"), std::string::npos) << r.output;
  }
  // An option given twice is a usage error, a flag too ...
  const RunResult twice = visgrab::test::runVisgrab("db list --db a --db=b");
  EXPECT_EQ(twice.exitCode, 2) << twice.output;
  EXPECT_NE(twice.output.find("--db is given 2 times"), std::string::npos) << twice.output;
  const RunResult flag = visgrab::test::runVisgrab("db list --db a --json --json");
  EXPECT_EQ(flag.exitCode, 2) << flag.output;
  EXPECT_NE(flag.output.find("--json is given 2 times"), std::string::npos) << flag.output;
  // ... but a repeatable one collects its values (the run then finds no database: exit 1).
  const RunResult grasps =
      visgrab::test::runVisgrab("run --db " + missing + " --grasps a --grasps=b --out " + missing);
  EXPECT_EQ(grasps.exitCode, 1) << grasps.output;
  // Several positionals reach the command (whose first folder does not exist: exit 1).
  const RunResult results =
      visgrab::test::runVisgrab("analyze " + missing + " " + missing + "2 --out " + missing + "3");
  EXPECT_EQ(results.exitCode, 1) << results.output;
  EXPECT_NE(results.output.find("no-db: error: no such result folder"), std::string::npos)
      << results.output;
  // A missing value names what was expected.
  const RunResult value = visgrab::test::runVisgrab("db list --db");
  EXPECT_EQ(value.exitCode, 2) << value.output;
  EXPECT_NE(value.output.find("--db: expected DIR|MANIFEST"), std::string::npos) << value.output;
}

// A result folder `dir` whose trials.csv (version 4, docs/report.md) holds `records` after the
// column line.
void writeTrials(const std::filesystem::path& dir, const std::string& records) {
  visgrab::test::writeFile(dir / "trials.csv",
                           "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,"
                           "object,simulated_time,closing_capped,detail\n" +
                               records);
}

// Scene i of method s2EGA1: grasp g0 stable (RobWork code 1) when i is even, else missed (3).
std::string fourScenes() {
  std::string records;
  for (int i = 1; i <= 4; ++i) {
    const std::string scene = "textured/single/cocacola/0" + std::to_string(i);
    records += scene + (i % 2 == 0 ? ",s2EGA1,g0,0,stable,1,0.9,0.5,0.25,5,1.2,0,\"\"\n"
                                   : ",s2EGA1,g0,0,missed,3,0,0,0,0,1.2,0,\"\"\n");
  }
  return records;
}

TEST(AnalyzeCommand, FoldersOfTheSameNameAreToldApart) {
  visgrab::test::TempDir dir;
  // The layout `visgrab benchmark` writes: BENCH/results.
  const auto a = dir.path() / "benchA" / "results";
  const auto b = dir.path() / "benchB" / "results";
  writeTrials(a, fourScenes());
  writeTrials(b, fourScenes());
  const auto out = dir.path() / "report";
  const RunResult r = visgrab::test::runVisgrab(
      "analyze " + visgrab::test::shellQuoted(a) + " " + visgrab::test::shellQuoted(b) +
      " --no-pictures --quiet --threads 1 --out " + visgrab::test::shellQuoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(out / "report.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("| benchA/results: s2EGA1 | benchB/results: s2EGA1 |"), std::string::npos)
      << md;
  EXPECT_EQ(md.find("| results: s2EGA1"), std::string::npos) << md;
  // One folder given twice (here under two paths) is refused.
  const RunResult twice = visgrab::test::runVisgrab(
      "analyze " + visgrab::test::shellQuoted(a) + " " +
      visgrab::test::shellQuoted(dir.path() / "benchA" / "." / "results") + " --out " +
      visgrab::test::shellQuoted(dir.path() / "twice"));
  EXPECT_EQ(twice.exitCode, 1) << twice.output;
  EXPECT_NE(twice.output.find("results is given twice (also as "), std::string::npos)
      << twice.output;
}

TEST(AnalyzeCommand, BadResultFoldersAndOptionsSayWhatIsWrong) {
  visgrab::test::TempDir dir;
  const auto analyze = [&dir](const std::filesystem::path& results, const std::string& options) {
    return visgrab::test::runVisgrab("analyze " + visgrab::test::shellQuoted(results) +
                                     " --no-pictures --quiet " + options + " --out " +
                                     visgrab::test::shellQuoted(dir.path() / "report"));
  };
  const auto expectError = [](const RunResult& r, int code, const std::string& what) {
    EXPECT_EQ(r.exitCode, code) << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
  };
  const auto missing = dir.path() / "nonexist";
  expectError(analyze(missing, ""), 1,
              missing.string() + ": error: no such result folder (the folder does not exist)");
  const auto file = visgrab::test::writeFile(dir.path() / "base.csv", "a\n");
  expectError(analyze(file, ""), 1, file.string() + ": error: is a file, not a result folder");
  const auto empty = dir.path() / "empty";
  visgrab::test::writeFile(empty / "trials.csv", "");
  expectError(analyze(empty, ""), 1,
              (empty / "trials.csv").string() +
                  ":1: error: empty file (expected the column line 'scene,method,");
  const auto nan = dir.path() / "nan";
  writeTrials(nan, "textured/single/cocacola/01,s2EGA1,g0,0,stable,1,nan,0.5,0.25,5,1.2,0,\"\"\n");
  expectError(
      analyze(nan, ""), 1,
      (nan / "trials.csv").string() + ":2: error: column q_lift: 'nan' is not a finite number");
  // Too few resamples: a usage error (exit 2) saying why; 0 and 100 are fine.
  const auto good = dir.path() / "good";
  writeTrials(good, fourScenes());
  for (const std::string few : {"1", "2", "99"}) {
    expectError(analyze(good, "--bootstrap " + few), 2,
                "--bootstrap: must be 0 (no intervals) or at least 100, got " + few +
                    " (the interval's ends would be the extremes of a few resamples");
  }
  EXPECT_EQ(analyze(good, "--bootstrap 0").exitCode, 0);
  EXPECT_EQ(analyze(good, "--bootstrap 100").exitCode, 0);
}

#ifdef VISGRAB_VIEWER_BINARY
TEST(CommandLineHelp, TheViewerListsEveryOptionInItsHelp) {
  visgrab::viewer::ViewerOptions options;
  const auto app = visgrab::viewer::makeViewerApp(options);
  const RunResult help = visgrab::test::runProgram(VISGRAB_VIEWER_BINARY, "--help");
  ASSERT_EQ(help.exitCode, 0) << help.output;
  expectHelpListsEverything(*app, help.output, "visgrab-viewer");
  EXPECT_EQ(visgrab::test::runProgram(VISGRAB_VIEWER_BINARY, "-h").output, help.output);
}

TEST(CommandLineRules, TheViewerFollowsTheSameRules) {
  // --x=v is --x v (here: the database is missing, exit 1, before any window).
  visgrab::test::TempDir dir;
  const std::string missing = visgrab::test::shellQuoted(dir.path() / "no-db");
  for (const std::string& args : {"--db " + missing, "--db=" + missing}) {
    const RunResult r = visgrab::test::runProgram(VISGRAB_VIEWER_BINARY, args);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
  }
  const RunResult twice = visgrab::test::runProgram(VISGRAB_VIEWER_BINARY, "--db a --db=b");
  EXPECT_EQ(twice.exitCode, 2) << twice.output;
  EXPECT_NE(twice.output.find("--db is given 2 times"), std::string::npos) << twice.output;
  // --grasps is repeatable: both files reach the loader, which names the first missing one.
  const RunResult grasps = visgrab::test::runProgram(
      VISGRAB_VIEWER_BINARY,
      "--db " + visgrab::test::shellQuoted(dir.path()) + " --grasps a.csv --grasps=b.csv");
  EXPECT_EQ(grasps.exitCode, 1) << grasps.output;
}

TEST(ViewerOptions, ParsesEveryOption) {
  const auto o = visgrab::viewer::parseViewerOptions(
      {"--db", "d", "--scene=s", "--results", "r", "--grasps", "g1", "--grasps=g2", "--hand", "h",
       "--grasp", "3", "--method", "m", "--screenshot", "x.png", "--size=640x480"});
  EXPECT_EQ(o.database->string(), "d");
  EXPECT_EQ(*o.scene, "s");
  EXPECT_EQ(o.results->string(), "r");
  ASSERT_EQ(o.grasps.size(), 2u);
  EXPECT_EQ(o.grasps[1].string(), "g2");
  EXPECT_EQ(o.hand->string(), "h");
  EXPECT_EQ(*o.grasp, "3");
  EXPECT_EQ(o.method, "m");
  EXPECT_EQ(o.screenshot->string(), "x.png");
  EXPECT_EQ(o.width, 640);
  EXPECT_EQ(o.height, 480);
  EXPECT_THROW(visgrab::viewer::parseViewerOptions({"--size", "8x8"}), visgrab::viewer::UsageError);
  EXPECT_THROW(
      visgrab::viewer::parseViewerOptions({"--method", "", "--grasp", "1", "--scene", "s"}),
      visgrab::viewer::UsageError);
}
#endif

}  // namespace
