// Shards of a benchmark run (visgrab::runner, no Slurm): the plan covers every scene's grasps
// exactly once, the merged shards are byte-identical to a one-machine run whatever the thread
// counts (shards without scenes too), a stopped or cut-off shard resumes to the same result, and
// the merge refuses shards that are missing, given twice, of other runs or engines, torn, changed
// or unfinished, naming the folder, and an output folder that holds results.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <string>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/common/stop_signals.hpp"
#include "shard_test_grasps.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/runner/shard_merge.hpp"
#include "visgrab/runner/shard_plan.hpp"
#include "visgrab/runner/shard_record.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::runner::mergeShards;
using visgrab::runner::planShards;
using visgrab::runner::RunOptions;
using visgrab::runner::SceneBlock;
using visgrab::runner::ShardSpec;

std::string fileBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// --- The plan ---------------------------------------------------------------------------------

// Every scene in exactly one block, blocks contiguous and in order, for N = 1..7.
void expectPartition(const std::vector<std::size_t>& grasps) {
  const std::size_t total = std::accumulate(grasps.begin(), grasps.end(), std::size_t{0});
  const std::size_t largest = grasps.empty() ? 0 : *std::max_element(grasps.begin(), grasps.end());
  for (int n = 1; n <= 7; ++n) {
    const auto blocks = planShards(grasps, n);
    ASSERT_EQ(blocks.size(), static_cast<std::size_t>(n));
    std::vector<int> owner(grasps.size(), 0);
    std::size_t covered = 0;
    std::size_t next = 0;
    for (const SceneBlock& b : blocks) {
      ASSERT_EQ(b.begin, next) << "N = " << n << ": blocks not contiguous";
      ASSERT_LE(b.begin, b.end);
      std::size_t inBlock = 0;
      for (std::size_t i = b.begin; i < b.end; ++i) {
        ++owner[i];
        inBlock += grasps[i];
      }
      covered += inBlock;
      next = b.end;
      // Balanced: no block holds more than its share and one scene.
      EXPECT_LE(inBlock * static_cast<std::size_t>(n), total + largest * n) << "N = " << n;
    }
    EXPECT_EQ(next, grasps.size()) << "N = " << n;
    EXPECT_EQ(covered, total) << "N = " << n;
    for (std::size_t i = 0; i < owner.size(); ++i) {
      EXPECT_EQ(owner[i], 1) << "N = " << n << ": scene " << i;
    }
  }
}

TEST(ShardPlan, EveryScenesGraspsAreInExactlyOneShardForOneToSevenShards) {
  expectPartition({});
  expectPartition({0, 0, 0});
  expectPartition({5});
  expectPartition({3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3});
  expectPartition({0, 7, 0, 0, 2, 40, 1, 0, 9, 9, 3, 0});
  expectPartition({100, 1, 1, 1, 1, 1, 1, 1, 1, 1});
}

TEST(ShardPlan, BlocksFollowTheGraspMidpoints) {
  // 4 equal scenes in 2: the first two and the last two.
  auto b = planShards({4, 4, 4, 4}, 2);
  EXPECT_EQ(b[0].end, 2u);
  EXPECT_EQ(b[1].end, 4u);
  // A heavy first scene (midpoint 5 of 14) fills the first of two shards alone.
  b = planShards({10, 1, 1, 1, 1}, 2);
  EXPECT_EQ(b[0].begin, 0u);
  EXPECT_EQ(b[0].end, 1u);
  EXPECT_EQ(b[1].end, 5u);
  // More shards than scenes: some are empty, none holds a scene twice.
  b = planShards({2, 2}, 4);
  EXPECT_EQ(
      b[0].end - b[0].begin + b[1].end - b[1].begin + b[2].end - b[2].begin + b[3].end - b[3].begin,
      2u);
  // Trailing scenes without grasps go to the last shard, leading ones to the first.
  b = planShards({0, 6, 6, 0}, 2);
  EXPECT_EQ(b[0].end, 2u);
  EXPECT_EQ(b[1].end, 4u);
  // No grasps at all: every scene in the first shard.
  b = planShards({0, 0, 0}, 3);
  EXPECT_EQ(b[0].end, 3u);
  EXPECT_EQ(b[2].begin, 3u);
  EXPECT_THROW(planShards({1}, 0), std::invalid_argument);
}

TEST(ShardPlan, ShardSpecMustBeWithinOneToN) {
  EXPECT_NO_THROW(visgrab::runner::checkShardSpec({1, 1}));
  EXPECT_NO_THROW(visgrab::runner::checkShardSpec({7, 7}));
  EXPECT_THROW(visgrab::runner::checkShardSpec({0, 3}), std::invalid_argument);
  EXPECT_THROW(visgrab::runner::checkShardSpec({4, 3}), std::invalid_argument);
  EXPECT_THROW(visgrab::runner::checkShardSpec({1, 0}), std::invalid_argument);
}

// --- The record ---------------------------------------------------------------------------

visgrab::runner::ShardRecord sampleRecord() {
  visgrab::runner::ShardRecord r;
  r.shard = {2, 5};
  r.finished = true;
  r.inputs = {"0123456789abcdef", "fedcba9876543210", "00000000000000ff", "plain/*"};
  r.trials = 42;
  r.trialsHash = "1111111111111111";
  r.runHash = "2222222222222222";
  return r;
}

TEST(ShardRecord, RoundTrips) {
  const auto r = sampleRecord();
  const auto back =
      visgrab::runner::parseShardRecord(visgrab::runner::formatShardRecord(r), "shard.txt");
  EXPECT_EQ(back.shard.index, 2);
  EXPECT_EQ(back.shard.count, 5);
  EXPECT_TRUE(back.finished);
  EXPECT_EQ(back.inputs, r.inputs);
  EXPECT_EQ(back.trials, 42u);
  EXPECT_EQ(back.trialsHash, r.trialsHash);
  EXPECT_EQ(back.runHash, r.runHash);
  // FNV-1a 64 of "a" (the published test vector).
  EXPECT_EQ(visgrab::runner::contentHash("a"), "af63dc4c8601ec8c");
}

TEST(ShardRecord, TheFingerprintFollowsEveryInputsContent) {
  const visgrab::test::TempDir tmp;
  const fs::path db = tmp.path() / "db";
  visgrab::test::writeFile(db / "index.xml", "<index/>\n");
  visgrab::test::writeFile(tmp.path() / "grasps" / "a.txt", "a\n");
  visgrab::test::writeFile(tmp.path() / "grasps" / ".hidden", "ignored\n");
  const fs::path b = visgrab::test::writeFile(tmp.path() / "b.txt", "b\n");
  const fs::path hand = visgrab::test::writeFile(tmp.path() / "hand" / "h.grasp.xml", "<h/>\n");
  const auto fingerprint = [&] {
    return visgrab::runner::fingerprintRun(db, {tmp.path() / "grasps", b}, hand, "plain");
  };
  const auto before = fingerprint();
  EXPECT_EQ(fingerprint(), before);
  // Dot files are not grasp files (taskio::readGraspFolder skips them).
  visgrab::test::writeFile(tmp.path() / "grasps" / ".hidden", "changed\n");
  EXPECT_EQ(fingerprint(), before);
  visgrab::test::writeFile(b, "b changed\n");
  auto after = fingerprint();
  EXPECT_NE(after.grasps, before.grasps);
  EXPECT_EQ(after.database, before.database);
  EXPECT_EQ(visgrab::runner::describeDifference(before, after), "the grasp files");
  visgrab::test::writeFile(hand, "<h2/>\n");
  visgrab::test::writeFile(db / "index.xml", "<index2/>\n");
  after = fingerprint();
  EXPECT_NE(after.hand, before.hand);
  EXPECT_NE(after.database, before.database);
  EXPECT_EQ(visgrab::runner::describeDifference(before, after),
            "the database (index), the grasp files, the hand");
  // A hand given as its folder: every file of the folder.
  const auto folder = visgrab::runner::fingerprintRun(db, {b}, hand.parent_path(), "");
  visgrab::test::writeFile(hand.parent_path() / "h.wc.xml", "<wc/>\n");
  EXPECT_NE(visgrab::runner::fingerprintRun(db, {b}, hand.parent_path(), "").hand, folder.hand);
  EXPECT_THROW(visgrab::runner::fingerprintRun(db, {tmp.path() / "missing.txt"}, hand, ""),
               rw::common::LoadError);
}

// The message of parsing `text`, expected to fail.
std::string recordError(const std::string& text) {
  try {
    visgrab::runner::parseShardRecord(text, "s/shard.txt");
  } catch (const rw::common::LoadError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ShardRecord, MalformedRecordsNameTheLine) {
  const std::string good = visgrab::runner::formatShardRecord(sampleRecord());
  EXPECT_NE(recordError("visgrab shard 9\n").find("s/shard.txt:1"), std::string::npos);
  std::string bad = good;
  bad.replace(bad.find("shard 2 of 5"), 12, "shard 6 of 5");
  EXPECT_NE(recordError(bad).find("s/shard.txt:2"), std::string::npos) << recordError(bad);
  EXPECT_NE(recordError(bad).find("1 <= K <= N"), std::string::npos);
  bad = good;
  bad.replace(bad.find("state finished"), 14, "state done");
  EXPECT_NE(recordError(bad).find("s/shard.txt:3"), std::string::npos) << recordError(bad);
  bad = good + "colour blue\n";
  EXPECT_NE(recordError(bad).find("unknown key \"colour\""), std::string::npos);
  bad = good + "trials 3\n";
  EXPECT_NE(recordError(bad).find("given twice"), std::string::npos);
  bad = good.substr(0, good.size() - 1);
  EXPECT_NE(recordError(bad).find("cut off"), std::string::npos);
  bad = good;
  bad.erase(bad.find("run.csv"));
  EXPECT_NE(recordError(bad).find("no \"run.csv\" line"), std::string::npos) << recordError(bad);
}

// --- Shards of a run on the shared test database ------------------------------------------

class ShardedRun : public ::testing::Test {
 protected:
  // The grasps (two methods, a grasp of an unknown scene, one of an unknown pre-shape and a line
  // that does not parse), and the one-machine run to compare with.
  static void SetUpTestSuite() {
    dir_ = std::make_unique<visgrab::test::TempDir>();
    using visgrab::test::kTestSceneIds;
    auto grasps =
        visgrab::test::cylinderGrasps({kTestSceneIds[0], kTestSceneIds[2], kTestSceneIds[6],
                                       kTestSceneIds[10], kTestSceneIds[12], kTestSceneIds[16]},
                                      2, "top");
    auto other = visgrab::test::cylinderGrasps({kTestSceneIds[12], kTestSceneIds[2]}, 1, "other");
    grasps.insert(grasps.end(), other.begin(), other.end());
    auto unknownScene = grasps.front();
    unknownScene.sceneId = "plain/single/cocacola/09";
    unknownScene.id = "lost";
    grasps.push_back(unknownScene);
    auto unknownPreshape = grasps.back();
    unknownPreshape.sceneId = std::string(kTestSceneIds[16]);
    unknownPreshape.id = "odd";
    unknownPreshape.method = "other";
    unknownPreshape.preshape = "NO_SUCH_PRESHAPE";
    grasps.push_back(unknownPreshape);
    const std::string text = visgrab::taskio::formatGraspList(grasps) + "this is no grasp\n";
    visgrab::test::writeFile(graspFile(), text);
    RunOptions whole = options(dir_->path() / "whole");
    whole.threads = 2;
    const auto summary = visgrab::runner::runBenchmark(whole);
    ASSERT_GT(summary.trials, 10);
    ASSERT_EQ(summary.rejected.size(), 3u);
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static fs::path graspFile() { return dir_->path() / "grasps.txt"; }
  static fs::path wholeDir() { return dir_->path() / "whole"; }

  static RunOptions options(const fs::path& out) {
    RunOptions o;
    o.database = visgrab::test::testDatabasePath();
    o.grasps = {graspFile()};
    o.hand = visgrab::test::sdhHandFile();
    o.out = out;
    o.threads = 1;
    return o;
  }

  // Runs shard k of n into `out` with `threads` workers.
  static void runShard(const fs::path& out, int k, int n, int threads) {
    RunOptions o = options(out);
    o.shard = ShardSpec{k, n};
    o.threads = threads;
    visgrab::runner::runBenchmark(o);
  }

  // The shards 1..n of the test's run (computed once per n), thread counts alternating 1, 2.
  static std::vector<fs::path> shards(int n) {
    std::vector<fs::path> dirs;
    for (int k = 1; k <= n; ++k) {
      const fs::path d = dir_->path() / ("of" + std::to_string(n)) / ("shard-" + std::to_string(k));
      if (!fs::exists(d / visgrab::runner::kShardRecordFileName)) runShard(d, k, n, 1 + k % 2);
      dirs.push_back(d);
    }
    return dirs;
  }

  // A copy of `from` under a new name.
  fs::path copyOf(const fs::path& from, const std::string& name) const {
    const fs::path to = tmp_.path() / name;
    fs::copy(from, to, fs::copy_options::recursive);
    return to;
  }

  // The message of merging `dirs`, expected to fail.
  std::string mergeError(const std::vector<fs::path>& dirs) const {
    try {
      mergeShards(dirs, tmp_.path() / "merged");
    } catch (const std::exception& e) {
      return e.what();
    }
    return "(merged without an error)";
  }

  static void expectSameAsWhole(const fs::path& merged) {
    for (const auto name : {visgrab::results::kTrialsFileName, visgrab::results::kRunFileName}) {
      EXPECT_EQ(fileBytes(merged / name), fileBytes(wholeDir() / name)) << name;
    }
  }

  visgrab::test::TempDir tmp_;
  static inline std::unique_ptr<visgrab::test::TempDir> dir_;
};

TEST_F(ShardedRun, MergedShardsAreByteIdenticalToTheOneMachineRun) {
  const auto dirs = shards(3);
  // Any order of the folders on the command line.
  const auto summary = mergeShards({dirs[2], dirs[0], dirs[1]}, tmp_.path() / "merged");
  EXPECT_EQ(summary.shards, 3);
  expectSameAsWhole(tmp_.path() / "merged");
  // Marked unfinished while its files were written (shard_merge.cpp), not after.
  EXPECT_FALSE(fs::exists(tmp_.path() / "merged" / "unfinished.txt"));
  EXPECT_TRUE(visgrab::results::readResults(tmp_.path() / "merged").finished);
  // Each shard holds whole scenes: its run.csv lists its scenes, and its trials are of them.
  std::size_t trials = 0;
  std::vector<std::string> scenes;
  for (const auto& d : dirs) {
    const auto part = visgrab::results::readResults(d);
    trials += part.trials.size();
    for (const auto& s : part.scenes) scenes.push_back(s.id);
    for (const auto& t : part.trials) {
      EXPECT_TRUE(std::any_of(part.scenes.begin(), part.scenes.end(),
                              [&](const auto& s) { return s.id == t.sceneId; }))
          << d << ": trial of scene " << t.sceneId;
    }
    EXPECT_NE(fileBytes(d / "shard.txt").find("state finished"), std::string::npos);
  }
  const auto whole = visgrab::results::readResults(wholeDir());
  EXPECT_EQ(trials, whole.trials.size());
  std::vector<std::string> wholeScenes;
  for (const auto& s : whole.scenes) wholeScenes.push_back(s.id);
  EXPECT_EQ(scenes, wholeScenes);
}

TEST_F(ShardedRun, SevenShardsSomeEmptyMergeToTheOneMachineRun) {
  // Six of the 20 scenes have grasps: some of the seven shards hold only scenes without grasps,
  // or none.
  const auto dirs = shards(7);
  int empty = 0;
  for (const auto& d : dirs) {
    if (visgrab::results::readResults(d).trials.empty()) ++empty;
  }
  EXPECT_GE(empty, 1);
  mergeShards(dirs, tmp_.path() / "merged");
  expectSameAsWhole(tmp_.path() / "merged");
}

TEST_F(ShardedRun, ShardsDoNotDependOnTheThreadCount) {
  const auto dirs = shards(3);
  // shards() ran shard 2 on one thread; again on two.
  const fs::path again = tmp_.path() / "again";
  runShard(again, 2, 3, 2);
  for (const auto name : {"trials.csv", "run.csv", "shard.txt"}) {
    EXPECT_EQ(fileBytes(again / name), fileBytes(dirs[1] / name)) << name;
  }
}

TEST_F(ShardedRun, OneShardIsTheWholeRunWithARecord) {
  const auto dirs = shards(1);
  expectSameAsWhole(dirs[0]);
  mergeShards(dirs, tmp_.path() / "merged");
  expectSameAsWhole(tmp_.path() / "merged");
}

TEST_F(ShardedRun, MergeRefusesAMissingShard) {
  const auto dirs = shards(3);
  const std::string e = mergeError({dirs[0], dirs[2]});
  EXPECT_NE(e.find("shard 2 of 3 missing"), std::string::npos) << e;
  EXPECT_FALSE(fs::exists(tmp_.path() / "merged"));
}

TEST_F(ShardedRun, MergeRefusesAShardGivenTwice) {
  const auto dirs = shards(3);
  const fs::path copy = copyOf(dirs[1], "copy-of-2");
  const std::string e = mergeError({dirs[0], dirs[1], copy, dirs[2]});
  EXPECT_NE(e.find("are both shard 2 of 3"), std::string::npos) << e;
  EXPECT_NE(e.find(copy.string()), std::string::npos) << e;
}

TEST_F(ShardedRun, MergeRefusesShardsOfAnotherRun) {
  const auto dirs = shards(3);
  // The same shard of a run with other grasps (a real run, fewer grasps).
  const fs::path otherGrasps = tmp_.path() / "other.txt";
  visgrab::taskio::writeGraspList(
      visgrab::test::cylinderGrasps({visgrab::test::kTestSceneIds[0]}, 1, "top"), otherGrasps);
  RunOptions o = options(tmp_.path() / "other-run");
  o.grasps = {otherGrasps};
  o.shard = ShardSpec{2, 3};
  visgrab::runner::runBenchmark(o);
  std::string e = mergeError({dirs[0], o.out, dirs[2]});
  EXPECT_NE(e.find("different runs: the grasp files differ"), std::string::npos) << e;
  EXPECT_NE(e.find(o.out.string()), std::string::npos) << e;
  // Another scene filter is another run too.
  o.grasps = {graspFile()};
  o.out = tmp_.path() / "filtered";
  o.scenes = "plain";
  o.shard = ShardSpec{3, 3};
  visgrab::runner::runBenchmark(o);
  e = mergeError({dirs[0], dirs[1], o.out});
  EXPECT_NE(e.find("the scene filter"), std::string::npos) << e;
  // A shard of a run cut into another number of shards.
  e = mergeError({dirs[0], dirs[1], dirs[2], shards(1)[0]});
  EXPECT_NE(e.find("different numbers of shards"), std::string::npos) << e;
}

TEST_F(ShardedRun, MergeRefusesAShardOfAnotherProtocol) {
  const auto dirs = shards(3);
  RunOptions o = options(tmp_.path() / "shaken");
  o.protocol = visgrab::test::sourceDir() / "scenes/protocols/shake.xml";
  o.shard = ShardSpec{2, 3};
  visgrab::runner::runBenchmark(o);
  std::string e = mergeError({dirs[0], o.out, dirs[2]});
  EXPECT_NE(e.find("ran other trial protocols"), std::string::npos) << e;
  EXPECT_NE(e.find(o.out.string()), std::string::npos) << e;

  // The same protocol (same name and hash) from another file: a run's shards name one file, as
  // they name one database, grasp list and hand (run.csv's protocol_file).
  const fs::path copy = tmp_.path() / "copy/shake.xml";
  fs::create_directories(copy.parent_path());
  fs::copy_file(o.protocol, copy);
  std::vector<fs::path> shaken{{}, o.out, {}};
  for (const int k : {1, 3}) {
    RunOptions s = options(tmp_.path() / ("shaken-" + std::to_string(k)));
    s.protocol = k == 1 ? o.protocol : copy;
    s.shard = ShardSpec{k, 3};
    visgrab::runner::runBenchmark(s);
    shaken[k - 1] = s.out;
  }
  e = mergeError(shaken);
  EXPECT_NE(e.find("name other input paths in run.csv (database, grasps, hand or protocol file)"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find(shaken[2].string()), std::string::npos) << e;
}

TEST_F(ShardedRun, MergeRefusesATornOrChangedShardFile) {
  const auto dirs = shards(3);
  const fs::path torn = copyOf(dirs[1], "torn");
  {
    std::ofstream out(torn / "trials.csv", std::ios::app | std::ios::binary);
    out << "plain/single/cocacola/01,top,g9,0,succ";
  }
  std::string e = mergeError({dirs[0], torn, dirs[2]});
  EXPECT_NE(e.find("shard folder " + torn.string() + ": trials.csv ends in a torn line"),
            std::string::npos)
      << e;
  // The last trial cut off at a line break: complete lines, but not what the shard wrote.
  const fs::path cut = copyOf(dirs[1], "cut");
  std::string text = fileBytes(cut / "trials.csv");
  text.erase(text.rfind('\n', text.size() - 2) + 1);
  visgrab::test::writeFile(cut / "trials.csv", text);
  e = mergeError({dirs[0], cut, dirs[2]});
  EXPECT_NE(e.find("shard folder " + cut.string() + ": trials.csv has changed"), std::string::npos)
      << e;
  // A missing run.csv.
  const fs::path noRun = copyOf(dirs[1], "no-run");
  fs::remove(noRun / "run.csv");
  e = mergeError({dirs[0], noRun, dirs[2]});
  EXPECT_NE(e.find("run.csv is missing"), std::string::npos) << e;
}

TEST_F(ShardedRun, MergeRefusesAFolderThatIsNoShardOrTheOutput) {
  const auto dirs = shards(3);
  std::string e = mergeError({dirs[0], wholeDir(), dirs[2]});
  EXPECT_NE(e.find("not the result folder of a shard"), std::string::npos) << e;
  EXPECT_NE(e.find(wholeDir().string()), std::string::npos) << e;
  const fs::path copy = copyOf(dirs[0], "one");
  try {
    mergeShards({copy, dirs[1], dirs[2]}, copy);
    ADD_FAILURE() << "merged into a shard";
  } catch (const std::runtime_error& err) {
    EXPECT_NE(std::string(err.what()).find("also the output folder"), std::string::npos);
  }
}

TEST_F(ShardedRun, MergeRefusesAnOutputFolderThatHoldsResults) {
  const auto dirs = shards(3);
  const fs::path out = tmp_.path() / "merged";
  mergeShards(dirs, out);
  visgrab::test::writeFile(out / "report.md", "an old report\n");
  const std::string trials = fileBytes(out / "trials.csv");
  // Merging again (or another run) into it would leave the old report beside new results.
  std::string e = mergeError(dirs);
  EXPECT_NE(e.find(out.string() + " already holds results (trials.csv); merge into another folder "
                                  "(--out) or remove it first"),
            std::string::npos)
      << e;
  EXPECT_EQ(fileBytes(out / "trials.csv"), trials);
  // run.csv alone is results too.
  fs::remove(out / "trials.csv");
  e = mergeError(dirs);
  EXPECT_NE(e.find(out.string() + " already holds results (run.csv)"), std::string::npos) << e;
  // A folder without results (here: only the old report) is written into.
  fs::remove(out / "run.csv");
  mergeShards(dirs, out);
  expectSameAsWhole(out);
}

// A run whose work is one scene (--scenes selects it alone), cut into three shards: shard 2 holds
// the scene (its grasps' midpoint, 1 of 2 grasps, is at 1/2 of the run: block floor(1 * 3 / 2) = 1,
// the second), shards 1 and 3 hold no scene at all.
TEST(ShardWithoutScenes, IsAValidShardAndTheMergeEqualsOneRun) {
  visgrab::test::TempDir tmp;
  const fs::path grasps = tmp.path() / "one-scene.txt";
  visgrab::taskio::writeGraspList(
      visgrab::test::cylinderGrasps({visgrab::test::kTestSceneIds[0]}, 2, "top"), grasps);
  const auto options = [&](const fs::path& out) {
    RunOptions o;
    o.database = visgrab::test::testDatabasePath();
    o.grasps = {grasps};
    o.hand = visgrab::test::sdhHandFile();
    o.out = out;
    o.scenes = std::string(visgrab::test::kTestSceneIds[0]);
    o.threads = 1;
    return o;
  };
  visgrab::runner::runBenchmark(options(tmp.path() / "whole"));
  std::vector<fs::path> dirs;
  for (int k = 1; k <= 3; ++k) {
    RunOptions o = options(tmp.path() / ("shard-" + std::to_string(k)));
    o.shard = ShardSpec{k, 3};
    visgrab::runner::runBenchmark(o);
    dirs.push_back(o.out);
  }
  const auto whole = visgrab::results::readResults(tmp.path() / "whole");
  ASSERT_FALSE(whole.sources.engineSettings.empty());
  for (const int k : {1, 3}) {
    const auto part = visgrab::results::readResults(dirs[static_cast<std::size_t>(k - 1)]);
    EXPECT_TRUE(part.scenes.empty()) << "shard " << k;
    EXPECT_TRUE(part.trials.empty()) << "shard " << k;
    // The engine settings a scene gives, recorded without a scene of its own.
    EXPECT_EQ(part.sources.engineSettings, whole.sources.engineSettings) << "shard " << k;
  }
  const fs::path merged = tmp.path() / "merged";
  const auto summary = mergeShards({dirs[2], dirs[0], dirs[1]}, merged);
  EXPECT_EQ(summary.trials, whole.trials.size());
  for (const auto name : {visgrab::results::kTrialsFileName, visgrab::results::kRunFileName}) {
    EXPECT_EQ(fileBytes(merged / name), fileBytes(tmp.path() / "whole" / name)) << name;
  }

  // An empty shard without the engine_settings record (as an older visgrab wrote it; shard.txt's
  // hash updated to match): the merge says which settings differ, and --resume repairs it.
  std::string run = fileBytes(dirs[0] / "run.csv");
  const auto at = run.find("engine_settings,");
  ASSERT_NE(at, std::string::npos) << run;
  run.erase(at, run.find('\n', at) + 1 - at);
  visgrab::test::writeFile(dirs[0] / "run.csv", run);
  auto record = visgrab::runner::readShardRecord(dirs[0]);
  record.runHash = visgrab::runner::contentHash(run);
  visgrab::runner::writeShardRecord(dirs[0], record);
  try {
    mergeShards(dirs, tmp.path() / "merged-2");
    ADD_FAILURE() << "merged a shard without engine settings";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("ran ode with different engine settings: none (no engine_settings record in "
                     "run.csv) and \"" +
                     whole.sources.engineSettings + "\""),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("run it again with --resume"), std::string::npos) << m;
    EXPECT_EQ(m.find("ode and ode"), std::string::npos) << m;
  }
  RunOptions again = options(dirs[0]);
  again.shard = ShardSpec{1, 3};
  again.resume = true;
  visgrab::runner::runBenchmark(again);
  mergeShards(dirs, tmp.path() / "merged-3");
  EXPECT_EQ(fileBytes(tmp.path() / "merged-3" / "run.csv"),
            fileBytes(tmp.path() / "whole" / "run.csv"));

  // A shard recorded as another engine's (its run.csv edited, the hash updated): the engines are
  // named.
  run = fileBytes(dirs[2] / "run.csv");
  run.insert(run.find("engine_settings,"), "engine,mujoco,,,,,,\n");
  visgrab::test::writeFile(dirs[2] / "run.csv", run);
  record = visgrab::runner::readShardRecord(dirs[2]);
  record.runHash = visgrab::runner::contentHash(run);
  visgrab::runner::writeShardRecord(dirs[2], record);
  try {
    mergeShards(dirs, tmp.path() / "merged-4");
    ADD_FAILURE() << "merged shards of two engines";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dirs[2].string() +
                                         " ran on different engines: ode and mujoco; a run's "
                                         "shards must all run on one engine"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(ShardedRun, AStoppedAndCutOffShardResumesToTheSameMergedResult) {
  const auto dirs = shards(3);
  const fs::path stopped = tmp_.path() / "stopped";
  // Shard 1 of 3 stopped after its second trial (a SIGTERM to the task: the stop request).
  std::atomic<bool> stop{false};
  RunOptions o = options(stopped);
  o.shard = ShardSpec{1, 3};
  o.stop = &stop;
  EXPECT_THROW(visgrab::runner::runBenchmark(o,
                                             [&](const visgrab::runner::RunProgress& p) {
                                               if (p.trialsDone >= 2) stop = true;
                                             }),
               rw::common::StopRequested);
  EXPECT_NE(fileBytes(stopped / "shard.txt").find("state running"), std::string::npos);
  std::string e = mergeError({stopped, dirs[1], dirs[2]});
  EXPECT_NE(e.find("shard folder " + stopped.string() + ": shard 1 of 3 has not finished"),
            std::string::npos)
      << e;
  // A kill in the middle of a write: the last line cut.
  {
    std::ofstream out(stopped / "trials.csv", std::ios::app | std::ios::binary);
    out << "plain/single/cocacola/01,top,g1,1,suc";
  }
  // A requeued task resumes it, with another thread count.
  o.stop = nullptr;
  o.resume = true;
  o.threads = 2;
  const auto summary = visgrab::runner::runBenchmark(o);
  EXPECT_GE(summary.resumed, 2);
  EXPECT_EQ(fileBytes(stopped / "trials.csv"), fileBytes(dirs[0] / "trials.csv"));
  mergeShards({stopped, dirs[1], dirs[2]}, tmp_.path() / "merged");
  expectSameAsWhole(tmp_.path() / "merged");
  // Resuming a finished shard changes nothing.
  visgrab::runner::runBenchmark(o);
  EXPECT_EQ(fileBytes(stopped / "shard.txt"), fileBytes(dirs[0] / "shard.txt"));
}

TEST_F(ShardedRun, ResumingAnotherShardsFolderFails) {
  const auto dirs = shards(3);
  const fs::path copy = copyOf(dirs[0], "first");
  RunOptions o = options(copy);
  o.shard = ShardSpec{2, 3};
  o.resume = true;
  try {
    visgrab::runner::runBenchmark(o);
    ADD_FAILURE() << "resumed shard 1's folder as shard 2";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("holds shard 1 of 3, not shard 2 of 3"), std::string::npos)
        << e.what();
  }
  // Resumed as a whole run.
  o.shard.reset();
  try {
    visgrab::runner::runBenchmark(o);
    ADD_FAILURE() << "resumed shard 1's folder as the whole run";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("holds shard 1 of 3 of a run; resume it with --shard 1 "
                                         "--of 3"),
              std::string::npos)
        << e.what();
  }
  // Nothing was changed.
  EXPECT_EQ(fileBytes(copy / "shard.txt"), fileBytes(dirs[0] / "shard.txt"));
  EXPECT_EQ(fileBytes(copy / "trials.csv"), fileBytes(dirs[0] / "trials.csv"));
}

}  // namespace
