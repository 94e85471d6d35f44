#include "visgrab/results/results_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "support/test_support.hpp"
#include "visgrab/results/results_file.hpp"

namespace visgrab::results {
namespace {

using database::SceneConditions;
using database::Texture;
using rwsim::trial::GraspOutcome;

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

RunResults runInfo() {
  RunResults run;
  for (const int object : {3, 7}) {
    const SceneConditions c = SceneConditions::single(Texture::kPlain, object, 2);
    run.scenes.push_back({database::sceneIdOf(c), c});
  }
  run.methods = {"zeta", "alpha"};  // the run's order, not alphabetical
  run.rejected = {{"zeta", 1}};
  return run;
}

/// Every (scene, method, rank) of runInfo(), 3 grasps each, in a fixed order.
std::vector<TrialRecord> allTrials() {
  std::vector<TrialRecord> trials;
  const RunResults run = runInfo();
  for (const RunScene& scene : run.scenes) {
    for (const std::string& method : run.methods) {
      for (int rank = 0; rank < 3; ++rank) {
        TrialRecord t;
        t.sceneId = scene.id;
        t.method = method;
        t.graspId = "g" + std::to_string(rank);
        t.rank = rank;
        t.outcome = rank == 1 ? GraspOutcome::kStable : GraspOutcome::kMissed;
        t.qLift = rank == 1 ? 0.875 : 0.0;
        t.detail = "trial " + scene.id + " " + method;
        trials.push_back(t);
      }
    }
  }
  return trials;
}

TEST(ResultsWriterTest, AppendsOneLinePerTrialAndResumes) {
  test::TempDir dir;
  const std::vector<TrialRecord> trials = allTrials();
  {
    ResultsWriter writer(dir.path());
    writer.writeRun(runInfo());
    EXPECT_EQ(writer.resumedCount(), 0u);
    for (int i = 0; i < 5; ++i) writer.append(trials[i]);
    EXPECT_TRUE(writer.contains(trials[4].sceneId, trials[4].method, trials[4].graspId));
    EXPECT_FALSE(writer.contains(trials[5].sceneId, trials[5].method, trials[5].graspId));
    EXPECT_THROW(writer.append(trials[2]), std::logic_error);
    // Written as it goes: another reader sees the five trials before the writer is closed.
    EXPECT_EQ(readResults(dir.path()).trials.size(), 5u);
  }
  ResultsWriter resumed(dir.path());
  EXPECT_EQ(resumed.resumedCount(), 5u);
  EXPECT_FALSE(resumed.droppedTornLine());
  EXPECT_TRUE(resumed.contains(trials[0].sceneId, trials[0].method, trials[0].graspId));
  for (std::size_t i = 5; i < trials.size(); ++i) resumed.append(trials[i]);
  EXPECT_EQ(readResults(dir.path()).trials.size(), trials.size());
}

TEST(ResultsWriterTest, RepeatsAreTrialsOfTheirOwnAndTheFileKindMustMatch) {
  test::TempDir dir;
  const std::vector<TrialRecord> trials = allTrials();
  ResultsWriter::Options repeated;
  repeated.repeated = true;
  {
    ResultsWriter writer(dir.path(), repeated);
    RunResults run = runInfo();
    run.repeats.count = 2;
    run.repeats.noise = "test";
    writer.writeRun(run);
    TrialRecord again = trials[0];
    again.repeat = 1;
    again.seed = 42;
    again.outcome = GraspOutcome::kDropped;
    writer.append(trials[0]);
    writer.append(again);
    EXPECT_THROW(writer.append(again), std::logic_error);
    EXPECT_TRUE(writer.contains(again.sceneId, again.method, again.graspId, 1));
    EXPECT_FALSE(writer.contains(again.sceneId, again.method, again.graspId, 2));
    EXPECT_EQ(writer.outcomeOf(again.sceneId, again.method, again.graspId, 0),
              GraspOutcome::kMissed);
    EXPECT_EQ(writer.outcomeOf(again.sceneId, again.method, again.graspId, 1),
              GraspOutcome::kDropped);
    EXPECT_EQ(writer.outcomeOf(again.sceneId, again.method, again.graspId, 2), std::nullopt);
  }
  EXPECT_EQ(readText(dir.path() / "trials.csv").rfind("scene,method,grasp,rank,repeat,seed,", 0),
            0u);
  // Resumed as a run without repeats: refused, the file untouched.
  const std::string before = readText(dir.path() / "trials.csv");
  try {
    ResultsWriter plain(dir.path());
    ADD_FAILURE() << "a repeated file resumed as a plain run";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("holds trials of a run with repeats"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(readText(dir.path() / "trials.csv"), before);
  // A plain writer takes no repeat.
  test::TempDir other;
  ResultsWriter plain(other.path());
  TrialRecord again = trials[0];
  again.repeat = 1;
  EXPECT_THROW(plain.append(again), std::logic_error);
}

TEST(ResultsWriterTest, ResumingAVersion1FileRewritesItInTheCurrentFormat) {
  // A run started before q_gws_unit existed: its trials keep their unit-force value (now
  // q_gws_unit) and an unknown q_gws; new trials are appended in the current format.
  test::TempDir dir;
  const std::vector<TrialRecord> trials = allTrials();
  test::writeFile(dir.path() / "trials.csv",
                  "# visgrab trials 1\n"
                  "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,object,"
                  "simulated_time,detail\n" +
                      trials[0].sceneId + ",zeta,g1,1,stable,1,0.875,0.03125,3,1.5,\"old\"\n");
  {
    ResultsWriter writer(dir.path());
    EXPECT_EQ(writer.resumedCount(), 1u);
    EXPECT_TRUE(writer.contains(trials[0].sceneId, "zeta", "g1"));
    TrialRecord fresh = trials[0];
    fresh.qGws = 0.5;
    fresh.qGwsUnit = 0.25;
    writer.append(fresh);
  }
  const std::string text = readText(dir.path() / "trials.csv");
  EXPECT_EQ(text.rfind(trialsHeader(), 0), 0u) << text;
  const TrialsFile back = parseTrials(text, "trials.csv");
  ASSERT_EQ(back.trials.size(), 2u);
  EXPECT_TRUE(std::isnan(back.trials[0].qGws));
  EXPECT_EQ(back.trials[0].qGwsUnit, 0.03125);
  EXPECT_EQ(back.trials[0].detail, "old");
  EXPECT_EQ(back.trials[1].qGws, 0.5);
  EXPECT_EQ(back.trials[1].qGwsUnit, 0.25);
}

TEST(ResultsWriterTest, TornLastLineIsCutOffOnResume) {
  test::TempDir dir;
  const std::vector<TrialRecord> trials = allTrials();
  {
    ResultsWriter writer(dir.path());
    writer.append(trials[0]);
    writer.append(trials[1]);
  }
  {
    // A kill while the third line was being written.
    std::ofstream out(dir.path() / "trials.csv", std::ios::app | std::ios::binary);
    const std::string line = formatTrialLine(trials[2]);
    out << line.substr(0, line.size() / 2);
  }
  ResultsWriter writer(dir.path());
  EXPECT_TRUE(writer.droppedTornLine());
  EXPECT_EQ(writer.resumedCount(), 2u);
  EXPECT_FALSE(writer.contains(trials[2].sceneId, trials[2].method, trials[2].graspId));
  writer.append(trials[2]);
  const std::string text = readText(dir.path() / "trials.csv");
  EXPECT_EQ(text, trialsHeader() + formatTrialLine(trials[0]) + formatTrialLine(trials[1]) +
                      formatTrialLine(trials[2]));
}

TEST(ResultsWriterTest, TornMultiLineRecordIsCutOffOnResume) {
  // Trials whose details span lines: a kill after the quoted line break of the third leaves an
  // open quote on a line of its own.
  test::TempDir dir;
  std::vector<TrialRecord> trials = allTrials();
  for (std::size_t i = 0; i < 3; ++i) trials[i].detail = "first line\nsecond, \"quoted\"\r\nthird";
  {
    ResultsWriter writer(dir.path());
    writer.append(trials[0]);
    writer.append(trials[1]);
  }
  const std::string complete = readText(dir.path() / "trials.csv");
  EXPECT_EQ(std::count(complete.begin(), complete.end(), '\n'), 7);
  const std::string third = formatTrialLine(trials[2]);
  for (const std::size_t cut : {third.find("second"), third.find("third") + 2, third.size() - 1}) {
    test::writeFile(dir.path() / "trials.csv", complete + third.substr(0, cut));
    {
      ResultsWriter writer(dir.path());
      EXPECT_TRUE(writer.droppedTornLine()) << cut;
      EXPECT_EQ(writer.resumedCount(), 2u) << cut;
      EXPECT_EQ(writer.trials()[1].detail, trials[1].detail);
      EXPECT_FALSE(writer.contains(trials[2].sceneId, trials[2].method, trials[2].graspId));
      writer.append(trials[2]);
    }
    EXPECT_EQ(readText(dir.path() / "trials.csv"), complete + third) << cut;
    EXPECT_EQ(readResults(dir.path()).trials.size(), 3u);
  }
}

TEST(ResultsWriterTest, ResumingAVersion2FileRewritesItInTheCurrentFormat) {
  // Version 2 escaped line breaks with backslashes; its trials keep their text, and the file
  // becomes RFC 4180 before anything is appended (it never mixes formats).
  test::TempDir dir;
  const std::vector<TrialRecord> trials = allTrials();
  test::writeFile(dir.path() / "trials.csv",
                  "# visgrab trials 2\n"
                  "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,"
                  "simulated_time,detail\n" +
                      trials[0].sceneId + ",zeta,g1,1,stable,1,0.875,0.5,0.25,3,1.5,\"a\\nb\"\n" +
                      trials[0].sceneId + ",zeta,g2,2,sta");
  {
    ResultsWriter writer(dir.path());
    EXPECT_EQ(writer.resumedCount(), 1u);
    EXPECT_TRUE(writer.droppedTornLine());
    writer.append(trials[0]);
  }
  const std::string text = readText(dir.path() / "trials.csv");
  EXPECT_EQ(text, trialsHeader() + trials[0].sceneId +
                      ",zeta,g1,1,stable,1,0.875,0.5,0.25,3,1.5,0,\"a\nb\"\n" +
                      formatTrialLine(trials[0]));
  const TrialsFile back = parseTrials(text, "trials.csv");
  EXPECT_EQ(back.version, kTrialsFormatVersion);
  ASSERT_EQ(back.trials.size(), 2u);
  EXPECT_EQ(back.trials[0].detail, "a\nb");
  EXPECT_EQ(back.lines, (std::vector<int>{2, 4}));
}

TEST(ResultsWriterTest, TornHeaderStartsTheFileAfresh) {
  test::TempDir dir;
  for (const std::string torn : {"# visgrab tri", "scene,method,gr", ""}) {
    test::writeFile(dir.path() / "trials.csv", torn);
    {
      ResultsWriter writer(dir.path());
      EXPECT_EQ(writer.resumedCount(), 0u);
      writer.append(allTrials()[0]);
    }
    EXPECT_EQ(readText(dir.path() / "trials.csv"),
              trialsHeader() + formatTrialLine(allTrials()[0]));
  }
}

TEST(ResultsWriterTest, CorruptExistingFileIsAnErrorWithItsLine) {
  test::TempDir dir;
  test::writeFile(dir.path() / "trials.csv", trialsHeader() + "a,b,c\n");
  try {
    ResultsWriter writer(dir.path());
    FAIL();
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("trials.csv:2: error: 3 fields"), std::string::npos)
        << e.what();
  }
}

TEST(ResultsWriterTest, FinalizeGivesTheSameBytesForAnyAppendOrder) {
  const std::vector<TrialRecord> trials = allTrials();
  std::vector<TrialRecord> reversed(trials.rbegin(), trials.rend());
  std::vector<TrialRecord> interleaved;
  for (std::size_t i = 0; i < trials.size(); i += 2) interleaved.push_back(trials[i]);
  for (std::size_t i = 1; i < trials.size(); i += 2) interleaved.push_back(trials[i]);

  auto finalBytes = [](const std::vector<TrialRecord>& order, bool resumeHalfway) {
    test::TempDir dir;
    {
      ResultsWriter writer(dir.path());
      writer.writeRun(runInfo());
      for (std::size_t i = 0; i < order.size() / 2; ++i) writer.append(order[i]);
      if (!resumeHalfway) {
        for (std::size_t i = order.size() / 2; i < order.size(); ++i) writer.append(order[i]);
        writer.finalize();
        EXPECT_THROW(writer.append(order[0]), std::logic_error);
      }
    }
    if (resumeHalfway) {
      ResultsWriter writer(dir.path());  // order from run.csv
      for (std::size_t i = order.size() / 2; i < order.size(); ++i) writer.append(order[i]);
      writer.finalize();
    }
    return readText(dir.path() / "trials.csv");
  };
  const std::string a = finalBytes(trials, false);
  EXPECT_EQ(finalBytes(reversed, false), a);
  EXPECT_EQ(finalBytes(interleaved, true), a);
  // The canonical order: scene (run order), method (run order: zeta before alpha), rank.
  std::string expected = trialsHeader();
  for (const TrialRecord& t : trials) expected += formatTrialLine(t);
  EXPECT_EQ(a, expected);
}

TEST(ResultsWriterTest, ConcurrentAppendsKeepLinesWhole) {
  test::TempDir dir;
  std::vector<TrialRecord> trials;
  for (int i = 0; i < 400; ++i) {
    TrialRecord t;
    t.sceneId = "s" + std::to_string(i % 7);
    t.method = "m";
    t.graspId = "g" + std::to_string(i);
    t.rank = i;
    t.outcome = GraspOutcome::kDropped;
    t.detail = std::string(200, 'x');
    trials.push_back(t);
  }
  {
    ResultsWriter writer(dir.path());
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k) {
      threads.emplace_back([&, k] {
        for (std::size_t i = static_cast<std::size_t>(k); i < trials.size(); i += 4) {
          writer.append(trials[i]);
        }
      });
    }
    for (auto& thread : threads) thread.join();
    EXPECT_EQ(writer.trials().size(), trials.size());
  }
  const RunResults back = readResults(dir.path());
  EXPECT_EQ(back.trials.size(), trials.size());
}

}  // namespace
}  // namespace visgrab::results
