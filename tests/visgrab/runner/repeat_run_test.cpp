// Robust verdicts (`visgrab run --repeats N`) on the shared test database: one repeat is the run
// without the option byte for byte; repeat 0 of a repeated run is the plain trial; a noise model
// of zero sigmas repeats repeat 0 exactly; four repeats give the same files on one or two threads
// and as three merged shards; a killed repeated run resumes to the same bytes; grasps.csv counts
// what trials.csv holds; the adaptive rule's trials are a prefix of the fixed run's; bad input is
// a clear error.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <thread>

#include "shard_test_grasps.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/grasp_summary.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/statistics.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/runner/shard_merge.hpp"
#include "visgrab/taskio/grasp_list.hpp"

// A named namespace: this file shares a unity build with the other runner tests.
namespace repeat_run_test {
namespace {

namespace fs = std::filesystem;
using visgrab::results::TrialRecord;
using visgrab::runner::RunOptions;

std::string fileBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The fields of a trial that a simulation decides (repeat and seed left out).
std::string verdict(const TrialRecord& t) {
  return t.sceneId + "|" + t.method + "|" + t.graspId + "|" + std::to_string(t.rank) + "|" +
         std::string(rwsim::trial::outcomeName(t.outcome)) + "|" +
         visgrab::results::formatDouble(t.qLift) + "|" + visgrab::results::formatDouble(t.qGws) +
         "|" + visgrab::results::formatDouble(t.qGwsUnit) + "|" + std::to_string(t.object) + "|" +
         visgrab::results::formatDouble(t.simulatedTime) + "|" + t.detail;
}

class RepeatedRun : public ::testing::Test {
 protected:
  // Two grasps on each of four scenes (three single, one pair) and the plain run to compare with.
  static void SetUpTestSuite() {
    dir_ = std::make_unique<visgrab::test::TempDir>();
    using visgrab::test::kTestSceneIds;
    const auto grasps = visgrab::test::cylinderGrasps(
        {kTestSceneIds[0], kTestSceneIds[2], kTestSceneIds[10], kTestSceneIds[12]}, 2, "top");
    visgrab::taskio::writeGraspList(grasps, graspFile());
    visgrab::runner::runBenchmark(options(plainDir(), 1));
    visgrab::runner::runBenchmark(options(fourDir(), 4));
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static fs::path graspFile() { return dir_->path() / "grasps.txt"; }
  static fs::path plainDir() { return dir_->path() / "plain"; }
  static fs::path fourDir() { return dir_->path() / "four"; }

  static RunOptions options(const fs::path& out, int repeats) {
    RunOptions o;
    o.database = visgrab::test::testDatabasePath();
    o.grasps = {graspFile()};
    o.hand = visgrab::test::sdhHandFile();
    o.out = out;
    o.threads = 1;
    o.repeats = repeats;
    return o;
  }

  static void expectSameFiles(const fs::path& a, const fs::path& b) {
    for (const auto name : {visgrab::results::kTrialsFileName, visgrab::results::kRunFileName,
                            visgrab::results::kGraspsFileName}) {
      EXPECT_EQ(fileBytes(a / name), fileBytes(b / name)) << name;
    }
  }

  visgrab::test::TempDir tmp_;
  static inline std::unique_ptr<visgrab::test::TempDir> dir_;
};

TEST_F(RepeatedRun, OneRepeatIsTheRunWithoutIt) {
  const fs::path one = tmp_.path() / "one";
  visgrab::runner::runBenchmark(options(one, 1));
  EXPECT_EQ(fileBytes(one / "trials.csv"), fileBytes(plainDir() / "trials.csv"));
  EXPECT_EQ(fileBytes(one / "run.csv"), fileBytes(plainDir() / "run.csv"));
  EXPECT_FALSE(fs::exists(one / visgrab::results::kGraspsFileName));
  // Nothing of the repeats in the files of a plain run.
  EXPECT_EQ(fileBytes(one / "trials.csv").find("repeat"), std::string::npos);
  EXPECT_EQ(fileBytes(one / "run.csv").find("repeats"), std::string::npos);
}

TEST_F(RepeatedRun, RepeatZeroIsThePlainTrialAndTheOthersArePerturbed) {
  const auto plain = visgrab::results::readResults(plainDir());
  const auto four = visgrab::results::readResults(fourDir());
  ASSERT_EQ(four.trials.size(), 4 * plain.trials.size());
  EXPECT_EQ(four.repeats.count, 4);
  std::map<std::string, std::string> unperturbed;
  for (const auto& t : plain.trials) unperturbed[t.sceneId + "|" + t.graspId] = verdict(t);
  int differing = 0;
  std::set<std::uint64_t> seeds;
  for (const auto& t : four.trials) {
    const std::string& base = unperturbed.at(t.sceneId + "|" + t.graspId);
    if (t.repeat == 0) {
      EXPECT_EQ(t.seed, 0u);
      EXPECT_EQ(verdict(t), base);
      continue;
    }
    EXPECT_EQ(t.seed, visgrab::runner::repeatSeed(1, t.sceneId, t.method, t.graspId, t.repeat));
    seeds.insert(t.seed);
    differing += verdict(t) != base ? 1 : 0;
  }
  // Every perturbed trial has its own seed, and the perturbations change the simulation (at
  // least its simulated time or qualities) in most of them.
  EXPECT_EQ(seeds.size(), 3 * plain.trials.size());
  EXPECT_GT(differing, static_cast<int>(plain.trials.size()));
}

TEST_F(RepeatedRun, ANoiseModelOfZeroSigmasRepeatsRepeatZeroExactly) {
  const fs::path noise = visgrab::test::writeFile(
      tmp_.path() / "zero.xml",
      "<NoiseModel>\n  <Hand translation=\"0\" rotation=\"0\"/>\n  <Object translation=\"0\" "
      "rotation=\"0\"/>\n  <Friction sigma=\"0\"/>\n  <Mass sigma=\"0\"/>\n</NoiseModel>\n");
  RunOptions o = options(tmp_.path() / "zero", 3);
  o.noise = noise;
  visgrab::runner::runBenchmark(o);
  const auto run = visgrab::results::readResults(o.out);
  std::map<std::string, std::string> first;
  for (const auto& t : run.trials) {
    if (t.repeat == 0) first[t.sceneId + "|" + t.graspId] = verdict(t);
  }
  for (const auto& t : run.trials) {
    EXPECT_EQ(verdict(t), first.at(t.sceneId + "|" + t.graspId)) << "repeat " << t.repeat;
  }
}

TEST_F(RepeatedRun, FourRepeatsAreTheSameOnTwoThreadsAndAsThreeMergedShards) {
  RunOptions two = options(tmp_.path() / "two", 4);
  two.threads = 2;
  visgrab::runner::runBenchmark(two);
  expectSameFiles(two.out, fourDir());
  std::vector<fs::path> shards;
  for (int k = 1; k <= 3; ++k) {
    RunOptions s = options(tmp_.path() / ("shard-" + std::to_string(k)), 4);
    s.shard = visgrab::runner::ShardSpec{k, 3};
    s.threads = 1 + k % 2;
    visgrab::runner::runBenchmark(s);
    shards.push_back(s.out);
  }
  visgrab::runner::mergeShards(shards, tmp_.path() / "merged");
  expectSameFiles(tmp_.path() / "merged", fourDir());
  // A shard of another repeat count does not merge with them.
  RunOptions other = options(tmp_.path() / "other", 2);
  other.shard = visgrab::runner::ShardSpec{3, 3};
  visgrab::runner::runBenchmark(other);
  EXPECT_THROW(
      visgrab::runner::mergeShards({shards[0], shards[1], other.out}, tmp_.path() / "mixed"),
      std::runtime_error);
}

TEST_F(RepeatedRun, GraspsCsvCountsWhatTrialsCsvHolds) {
  const auto run = visgrab::results::readResults(fourDir());
  // Counted here from the trials, independently of summarizeGrasps.
  std::map<std::string, std::pair<int, int>> heldOf;  // key -> (held, repeats)
  for (const auto& t : run.trials) {
    auto& [held, repeats] = heldOf[t.sceneId + "," + t.method + "," + t.graspId];
    held += visgrab::results::isSuccess(t.outcome) ? 1 : 0;
    ++repeats;
  }
  const std::string text = fileBytes(fourDir() / visgrab::results::kGraspsFileName);
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("scene,method,grasp,rank,repeats,held,p,p_ci_low,p_ci_high,unperturbed,"
                       "count_stable,",
                       0),
            0u)
      << line;
  std::size_t rows = 0;
  while (std::getline(lines, line)) {
    const auto f = visgrab::results::splitCsvLine(line);
    const auto& [held, repeats] = heldOf.at(f[0] + "," + f[1] + "," + f[2]);
    EXPECT_EQ(f[4], std::to_string(repeats));
    EXPECT_EQ(f[5], std::to_string(held));
    EXPECT_DOUBLE_EQ(std::stod(f[6]), static_cast<double>(held) / repeats);
    const auto wilson = visgrab::results::wilsonInterval(held, repeats, 0.95);
    EXPECT_DOUBLE_EQ(std::stod(f[7]), wilson.low);
    EXPECT_DOUBLE_EQ(std::stod(f[8]), wilson.high);
    int counted = 0;
    for (std::size_t i = 10; i < f.size(); ++i) counted += std::stoi(f[i]);
    EXPECT_EQ(counted, repeats);
    ++rows;
  }
  EXPECT_EQ(rows, heldOf.size());
}

TEST_F(RepeatedRun, AdaptiveTrialsAreAPrefixOfTheFixedRunsAndStopOnlyWhenAgreed) {
  RunOptions fixed = options(tmp_.path() / "fixed", 6);
  visgrab::runner::runBenchmark(fixed);
  RunOptions adaptive = options(tmp_.path() / "adaptive", 6);
  adaptive.adaptive = true;
  // Stops once repeat 0 and 3 perturbed trials agree (0.3^3 <= 0.05 < 0.3^2).
  adaptive.adaptiveMargin = 0.7;
  ASSERT_EQ(visgrab::results::repeatsToDecide(0.05, 0.7), 3);
  visgrab::runner::runBenchmark(adaptive);
  const auto all = visgrab::results::readResults(fixed.out);
  const auto some = visgrab::results::readResults(adaptive.out);
  std::map<std::string, std::vector<std::string>> fixedTrials;
  for (const auto& t : all.trials) fixedTrials[t.sceneId + "|" + t.graspId].push_back(verdict(t));
  std::map<std::string, std::vector<bool>> held;
  for (const auto& t : some.trials) {
    const std::string key = t.sceneId + "|" + t.graspId;
    const auto& expected = fixedTrials.at(key);
    ASSERT_LT(static_cast<std::size_t>(t.repeat), expected.size());
    EXPECT_EQ(verdict(t), expected[static_cast<std::size_t>(t.repeat)]);
    held[key].push_back(visgrab::results::isSuccess(t.outcome));
  }
  int stopped = 0;
  for (const auto& [key, h] : held) {
    const bool agree = std::all_of(h.begin(), h.begin() + 4, [&](bool x) { return x == h[0]; });
    // The unperturbed and three perturbed trials agreeing stop the grasp; a disagreement in them
    // runs all six.
    EXPECT_EQ(h.size(), agree ? 4u : 6u) << key;
    stopped += agree ? 1 : 0;
  }
  EXPECT_GT(stopped, 0);
  EXPECT_NE(fileBytes(adaptive.out / "run.csv")
                .find("adaptive,\"stop when the unperturbed and 3 perturbed trials agree (alpha "
                      "0.05, margin 0.7)\""),
            std::string::npos);
  // A rule that could never stop a grasp within the repeats is refused.
  RunOptions never = options(tmp_.path() / "never", 4);
  never.adaptive = true;
  never.adaptiveMargin = 0.7;
  try {
    visgrab::runner::runBenchmark(never);
    ADD_FAILURE() << "an adaptive rule that never stops was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("never stops a grasp early: give --repeats 5 or more"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(RepeatedRun, AKilledRepeatedRunResumesToTheSameBytes) {
  const fs::path out = tmp_.path() / "killed";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string db = visgrab::test::testDatabasePath().string();
    const std::string file = graspFile().string();
    const std::string hand = visgrab::test::sdhHandFile().string();
    const std::string o = out.string();
    execl(VISGRAB_BINARY, VISGRAB_BINARY, "run", "--db", db.c_str(), "--grasps", file.c_str(),
          "--hand", hand.c_str(), "--quiet", "--threads", "2", "--repeats", "4", "--out", o.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::size_t lines = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string text = fileBytes(out / "trials.csv");
    lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    if (lines >= 1 + 5) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed";
  ASSERT_GE(lines, 6u);
  // Resumed with other options: refused, naming the difference.
  RunOptions wrong = options(out, 3);
  wrong.resume = true;
  try {
    visgrab::runner::runBenchmark(wrong);
    ADD_FAILURE() << "resumed with another repeat count";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("4 repeats"), std::string::npos) << e.what();
  }
  RunOptions resume = options(out, 4);
  resume.resume = true;
  resume.threads = 2;
  const auto summary = visgrab::runner::runBenchmark(resume);
  EXPECT_GT(summary.resumed, 0);
  expectSameFiles(out, fourDir());
}

TEST_F(RepeatedRun, BadRepeatOptionsAreClearErrors) {
  const std::string common = "run --db " +
                             visgrab::test::shellQuoted(visgrab::test::testDatabasePath()) +
                             " --grasps " + visgrab::test::shellQuoted(graspFile()) +
                             " --quiet --out " + visgrab::test::shellQuoted(tmp_.path() / "bad");
  const auto zero = visgrab::test::runVisgrab(common + " --repeats 0");
  EXPECT_NE(zero.exitCode, 0);
  EXPECT_NE(zero.output.find("--repeats"), std::string::npos) << zero.output;
  // At most 10,000 repeats (the count of a run's trials stays far from int's limit).
  const auto many = visgrab::test::runVisgrab(common + " --repeats 10001");
  EXPECT_EQ(many.exitCode, 2) << many.output;
  EXPECT_NE(many.output.find("--repeats: at most 10000 (a grasp's P to within 0.01; "
                             "docs/noise-model.md), got 10001"),
            std::string::npos)
      << many.output;
  visgrab::runner::RunOptions tooMany;
  tooMany.repeats = 10001;
  EXPECT_THROW(
      {
        try {
          visgrab::runner::runBenchmark(tooMany);
        } catch (const std::invalid_argument& e) {
          EXPECT_STREQ(e.what(), "repeats must be between 1 and 10000, not 10001");
          throw;
        }
      },
      std::invalid_argument);
  const auto noiseAlone = visgrab::test::runVisgrab(common + " --noise x.xml");
  EXPECT_NE(noiseAlone.exitCode, 0);
  EXPECT_NE(noiseAlone.output.find("--noise needs --repeats N"), std::string::npos)
      << noiseAlone.output;
  const auto alpha =
      visgrab::test::runVisgrab(common + " --repeats 3 --adaptive --adaptive-alpha 1.5");
  EXPECT_NE(alpha.exitCode, 0);
  EXPECT_NE(alpha.output.find("--adaptive-alpha needs a number between 0 and 1"), std::string::npos)
      << alpha.output;
  const fs::path negative =
      visgrab::test::writeFile(tmp_.path() / "negative.xml",
                               "<NoiseModel>\n  <Hand translation=\"-0.001\"/>\n</NoiseModel>\n");
  const auto bad = visgrab::test::runVisgrab(common + " --repeats 3 --noise " +
                                             visgrab::test::shellQuoted(negative));
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find(negative.string() + ":2"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(tmp_.path() / "bad" / "trials.csv"));
  // A grasp file where the run would write its per-grasp summary is refused, untouched.
  const fs::path folder = tmp_.path() / "own";
  fs::create_directories(folder);
  fs::copy_file(graspFile(), folder / "grasps.csv");
  RunOptions own = options(folder, 2);
  own.grasps = {folder / "grasps.csv"};
  EXPECT_THROW(visgrab::runner::runBenchmark(own), std::runtime_error);
  EXPECT_EQ(fileBytes(folder / "grasps.csv"), fileBytes(graspFile()));
  EXPECT_FALSE(fs::exists(folder / "trials.csv"));
}

}  // namespace
}  // namespace repeat_run_test
