// `visgrab run --shard`, `visgrab merge` and `visgrab slurm` through the binary, without Slurm:
// the written job scripts, run by bash with the array task ids Slurm would give, reproduce a
// one-machine run; --submit chains the merge job on the array's id from `sbatch --parsable`
// (a stand-in sbatch records its arguments); mistakes are clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "shard_test_grasps.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::test::runProgram;
using visgrab::test::runVisgrab;
using visgrab::test::shellQuoted;

std::string fileBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class SlurmCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    using visgrab::test::kTestSceneIds;
    visgrab::taskio::writeGraspList(
        visgrab::test::cylinderGrasps(
            {kTestSceneIds[1], kTestSceneIds[3], kTestSceneIds[11], kTestSceneIds[17]}, 2, "top"),
        grasps());
  }
  fs::path grasps() const { return tmp_.path() / "top.txt"; }
  std::string common() const {
    return " --db " + shellQuoted(visgrab::test::testDatabasePath()) + " --grasps " +
           shellQuoted(grasps()) + " --hand " + shellQuoted(visgrab::test::sdhHandFile());
  }
  visgrab::test::TempDir tmp_;
};

TEST_F(SlurmCommand, DryRunPrintsTheScriptsAndWritesNothing) {
  const fs::path out = tmp_.path() / "sweep";
  const auto r =
      runVisgrab("slurm" + common() + " --grasps " + shellQuoted(grasps()) + " --hand " +
                 shellQuoted(visgrab::test::sourceDir() / "scenes/hands/pg70") +
                 " --shards 3 --cpus-per-task 4 --partition short --time 0:10:00 --account lab "
                 "--mem 2G --sbatch-option=--qos=low --dry-run --out " +
                 shellQuoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // 2 grasp sets x 2 hands x 3 shards.
  EXPECT_TRUE(contains(r.output, "#SBATCH --array=0-11\n")) << r.output;
  EXPECT_TRUE(contains(r.output, "#SBATCH --cpus-per-task=4\n"));
  EXPECT_TRUE(contains(r.output, "#SBATCH --partition=short\n"));
  EXPECT_TRUE(contains(r.output, "#SBATCH --time=0:10:00\n"));
  EXPECT_TRUE(contains(r.output, "#SBATCH --account=lab\n"));
  EXPECT_TRUE(contains(r.output, "#SBATCH --mem=2G\n"));
  EXPECT_TRUE(contains(r.output, "#SBATCH --qos=low\n"));
  EXPECT_TRUE(contains(
      r.output, "#SBATCH --output=" + (out / "slurm/logs").string() + "/trials-%A_%a.out\n"));
  EXPECT_TRUE(contains(r.output, "--threads 4 --resume"));
  EXPECT_TRUE(contains(r.output, "name='top-sdh'"));
  EXPECT_TRUE(contains(r.output, "name='top-pg70'"));
  EXPECT_TRUE(contains(r.output, "name='top-sdh-2'")) << r.output;
  EXPECT_TRUE(contains(r.output, "--dependency=afterok:"));
  EXPECT_TRUE(contains(r.output, " analyze "));
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(SlurmCommand, ScriptsRunWithoutSlurmGiveTheOneMachineResults) {
  const fs::path out = tmp_.path() / "sweep";
  auto r = runVisgrab("slurm" + common() + " --shards 3 --cpus-per-task 2 --no-pictures --out " +
                      shellQuoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const fs::path scripts = out / "slurm";
  EXPECT_TRUE(fs::is_directory(scripts / "logs"));
  // The array's tasks in any order; task 1 twice (a requeued task resumes its finished shard).
  for (const int task : {2, 0, 1, 1}) {
    r = runProgram("/bin/bash", shellQuoted(scripts / "trials.sbatch") + " 2>&1");
    EXPECT_NE(r.exitCode, 0) << "ran without SLURM_ARRAY_TASK_ID";
    r = runProgram("/usr/bin/env", "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " /bin/bash " +
                                       shellQuoted(scripts / "trials.sbatch"));
    ASSERT_EQ(r.exitCode, 0) << task << "\n" << r.output;
  }
  r = runProgram("/usr/bin/env",
                 "SLURM_ARRAY_TASK_ID=3 /bin/bash " + shellQuoted(scripts / "trials.sbatch"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "beyond the 3 tasks")) << r.output;
  r = runProgram("/bin/bash", shellQuoted(scripts / "merge.sbatch"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "report" / "report.md"));

  const fs::path whole = tmp_.path() / "whole";
  r = runVisgrab("run" + common() + " --quiet --threads 2 --out " + shellQuoted(whole));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const auto name : {"trials.csv", "run.csv"}) {
    EXPECT_EQ(fileBytes(out / "results" / "top" / name), fileBytes(whole / name)) << name;
  }
}

TEST_F(SlurmCommand, RepeatOptionsReachEveryShardAndTheMergeWritesGraspsCsv) {
  const fs::path out = tmp_.path() / "sweep";
  const fs::path noise = visgrab::test::writeFile(
      tmp_.path() / "n.xml", "<NoiseModel>\n  <Friction sigma=\"0.2\"/>\n</NoiseModel>\n");
  const std::string repeats = " --repeats 3 --seed 5 --noise " + shellQuoted(noise);
  auto r = runVisgrab("slurm" + common() + repeats + " --shards 2 --no-analyze --out " +
                      shellQuoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string script = fileBytes(out / "slurm" / "trials.sbatch");
  EXPECT_TRUE(contains(script, "'--repeats' '3' '--seed' '5' '--noise' '" + noise.string() + "'"))
      << script;
  for (const int task : {1, 0}) {
    r = runProgram("/usr/bin/env", "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " /bin/bash " +
                                       shellQuoted(out / "slurm" / "trials.sbatch"));
    ASSERT_EQ(r.exitCode, 0) << task << "\n" << r.output;
  }
  r = runProgram("/bin/bash", shellQuoted(out / "slurm" / "merge.sbatch"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const fs::path whole = tmp_.path() / "whole";
  r = runVisgrab("run" + common() + repeats + " --quiet --threads 2 --out " + shellQuoted(whole));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const auto name : {"trials.csv", "run.csv", "grasps.csv"}) {
    EXPECT_EQ(fileBytes(out / "results" / "top" / name), fileBytes(whole / name)) << name;
  }
  // An option of the adaptive rule without --adaptive is refused before anything is written.
  r = runVisgrab("slurm" + common() + repeats + " --adaptive-alpha 0.1 --shards 2 --out " +
                 shellQuoted(tmp_.path() / "bad"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_TRUE(contains(r.output, "--adaptive-alpha and --adaptive-margin need --adaptive"))
      << r.output;
  EXPECT_FALSE(fs::exists(tmp_.path() / "bad"));
}

TEST_F(SlurmCommand, TheProtocolReachesEveryShardAndTheMergeKeepsItsRecord) {
  const fs::path out = tmp_.path() / "sweep";
  const fs::path shake = visgrab::test::sourceDir() / "scenes/protocols/shake.xml";
  auto r = runVisgrab("slurm" + common() + " --protocol shake" + " --shards 2 --no-analyze --out " +
                      shellQuoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string script = fileBytes(out / "slurm" / "trials.sbatch");
  EXPECT_TRUE(contains(script, "'--protocol' '" + shake.string() + "'")) << script;
  for (const int task : {1, 0}) {
    r = runProgram("/usr/bin/env", "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " /bin/bash " +
                                       shellQuoted(out / "slurm" / "trials.sbatch"));
    ASSERT_EQ(r.exitCode, 0) << task << "\n" << r.output;
  }
  r = runProgram("/bin/bash", shellQuoted(out / "slurm" / "merge.sbatch"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const fs::path whole = tmp_.path() / "whole";
  r = runVisgrab("run" + common() + " --protocol " + shellQuoted(shake) +
                 " --quiet --threads 2 --out " + shellQuoted(whole));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const auto name : {"trials.csv", "run.csv"}) {
    EXPECT_EQ(fileBytes(out / "results" / "top" / name), fileBytes(whole / name)) << name;
  }
  EXPECT_TRUE(contains(fileBytes(whole / "run.csv"), "\nprotocol,shake,,,,,,\n"));
  // An unknown protocol is refused before anything is written.
  r = runVisgrab("slurm" + common() + " --protocol wobble --shards 2 --out " +
                 shellQuoted(tmp_.path() / "bad"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "unknown protocol \"wobble\"")) << r.output;
  EXPECT_FALSE(fs::exists(tmp_.path() / "bad"));
}

TEST_F(SlurmCommand, SubmitChainsTheMergeJobOnTheArraysId) {
  const fs::path calls = tmp_.path() / "calls.txt";
  const fs::path sbatch = visgrab::test::writeFile(
      tmp_.path() / "sbatch",
      "#!/bin/sh\necho \"$@\" >> " + shellQuoted(calls) +
          "\nif [ \"$#\" = 2 ]; then echo '4242;cluster'; else echo 4243; fi\n");
  fs::permissions(sbatch, fs::perms::owner_all);
  const fs::path out = tmp_.path() / "sweep";
  auto r = runVisgrab("slurm" + common() + " --shards 2 --submit --sbatch " + shellQuoted(sbatch) +
                      " --out " + shellQuoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "trials job 4242, merge job 4243")) << r.output;
  EXPECT_EQ(fileBytes(calls), "--parsable " + (out / "slurm/trials.sbatch").string() +
                                  "\n--parsable --dependency=afterok:4242 " +
                                  (out / "slurm/merge.sbatch").string() + "\n");
  // An sbatch that prints no job id, or fails: a clear error.
  visgrab::test::writeFile(sbatch, "#!/bin/sh\necho 'sbatch: error: invalid partition'\n");
  r = runVisgrab("slurm" + common() + " --shards 2 --submit --sbatch " + shellQuoted(sbatch) +
                 " --out " + shellQuoted(out));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.output, "expected a job id")) << r.output;
  visgrab::test::writeFile(sbatch, "#!/bin/sh\nexit 3\n");
  r = runVisgrab("slurm" + common() + " --shards 2 --submit --sbatch " + shellQuoted(sbatch) +
                 " --out " + shellQuoted(out));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.output, "failed (exit code 3)")) << r.output;
}

// The walkthrough of docs/cluster.md on one scene: of two shards, the first holds no scene (the
// scene's grasp midpoint is in the second half of the work); the merge equals one run, and a
// second merge into the same folder is refused and changes nothing.
TEST_F(SlurmCommand, AShardWithoutScenesMergesAndTheMergeNeverOverwritesResults) {
  const fs::path one = tmp_.path() / "one.txt";
  visgrab::taskio::writeGraspList(
      visgrab::test::cylinderGrasps({visgrab::test::kTestSceneIds[0]}, 2, "top"), one);
  const std::string inputs = " --db " + shellQuoted(visgrab::test::testDatabasePath()) +
                             " --grasps " + shellQuoted(one) + " --hand " +
                             shellQuoted(visgrab::test::sdhHandFile()) + " --scenes " +
                             std::string(visgrab::test::kTestSceneIds[0]) + " --threads 1 --quiet";
  const fs::path whole = tmp_.path() / "whole";
  auto r = runVisgrab("run" + inputs + " --out " + shellQuoted(whole));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::string shards;
  for (const int k : {1, 2}) {
    const fs::path dir = tmp_.path() / ("sh" + std::to_string(k));
    r = runVisgrab("run" + inputs + " --shard " + std::to_string(k) + " --of 2 --out " +
                   shellQuoted(dir));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    shards += " " + shellQuoted(dir);
  }
  EXPECT_FALSE(contains(fileBytes(tmp_.path() / "sh1" / "run.csv"), "\nscene,"));
  const fs::path merged = tmp_.path() / "merged";
  r = runVisgrab("merge" + shards + " --out " + shellQuoted(merged));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "2 shards merged: 2 trials, 1 scenes")) << r.output;
  for (const auto name : {"trials.csv", "run.csv"}) {
    EXPECT_EQ(fileBytes(merged / name), fileBytes(whole / name)) << name;
  }
  const std::string run = fileBytes(merged / "run.csv");
  r = runVisgrab("merge" + shards + " --out " + shellQuoted(merged));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "error: " + merged.string() +
                                     " already holds results (trials.csv); merge into another "
                                     "folder (--out) or remove it first"))
      << r.output;
  EXPECT_EQ(fileBytes(merged / "run.csv"), run);
}

TEST_F(SlurmCommand, ShardOptionsAndMergeMistakesAreClearErrors) {
  auto r =
      runVisgrab("run" + common() + " --shard 3 --of 2 --out " + shellQuoted(tmp_.path() / "x"));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_TRUE(contains(r.output, "--shard 3 is beyond --of 2")) << r.output;
  r = runVisgrab("run" + common() + " --shard 1 --out " + shellQuoted(tmp_.path() / "x"));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_TRUE(contains(r.output, "--shard K and --of N go together")) << r.output;
  r = runVisgrab("run" + common() + " --shard 0 --of 2 --out " + shellQuoted(tmp_.path() / "x"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_FALSE(fs::exists(tmp_.path() / "x"));
  r = runVisgrab("merge " + shellQuoted(tmp_.path()) + " --out " +
                 shellQuoted(tmp_.path() / "merged"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.output, "not the result folder of a shard")) << r.output;
  r = runVisgrab("slurm" + common() + " --shards 2 --dry-run --submit --out " +
                 shellQuoted(tmp_.path() / "s"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
}

}  // namespace
