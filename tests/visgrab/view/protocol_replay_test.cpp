// A run made with the shake, replayed: results::replayProtocol finds the shake in the data
// folder by the name and hash run.csv records, and the replay in a scene session with that
// protocol (view::replayTrial, what `visgrab render --grasp`, the report and the viewer draw) is
// the run's trial: the same outcome at the same simulated time as trials.csv says. The lift, which
// the replays used before, gives other trials.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/run_protocol.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/taskio/grasp_list.hpp"
#include "visgrab/view/trial_replay.hpp"

namespace {

namespace fs = std::filesystem;
using rw::math::Vector3D;
using rwsim::trial::GraspOutcome;

constexpr const char* kCanScene = "plain/single/cocacola/01";

// SDH_CYL pointing straight down, its TCP `above` the can's base, `aside` beside its axis.
visgrab::grasp::GraspRequest canGrasp(const std::string& id, double above, double aside) {
  const auto& db = visgrab::test::testDatabase();
  const Vector3D base = db.groundTruth(kCanScene).front().X_WO.translation();
  visgrab::grasp::GraspRequest r;
  r.sceneId = kCanScene;
  r.id = id;
  r.method = "known";
  r.kind = visgrab::grasp::GraspKind::kPreshape;
  r.preshape = "SDH_CYL";
  r.X_W_tcp = rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0),
                                     base + Vector3D(aside, 0.0, above));
  return r;
}

TEST(ProtocolReplay, AShakeRunReplaysWithTheShakeAndGivesTheRunsTrials) {
  visgrab::test::TempDir dir;
  const std::vector<visgrab::grasp::GraspRequest> grasps = {
      canGrasp("middle", 0.06, 0.0), canGrasp("high", 0.10, 0.0), canGrasp("aside", 0.06, 0.03)};
  visgrab::taskio::writeGraspList(grasps, dir.path() / "grasps.txt");
  visgrab::runner::RunOptions options;
  options.database = visgrab::test::testDatabase().root();
  options.grasps = {dir.path() / "grasps.txt"};
  options.out = dir.path() / "shake";
  options.hand = visgrab::test::sourceDir() / "scenes/hands/sdh/sdh.grasp.xml";
  options.protocol = visgrab::test::sourceDir() / "scenes/protocols/shake.xml";
  visgrab::runner::runBenchmark(options);
  const visgrab::results::RunResults run = visgrab::results::readResults(options.out);
  ASSERT_EQ(run.sources.protocol, "shake");
  ASSERT_EQ(run.trials.size(), grasps.size());

  // The data folder's shake, by the recorded name and hash.
  const rwsim::trial::TrialProtocol shake =
      visgrab::results::replayProtocol(run.sources, visgrab::test::sourceDir() / "scenes");
  EXPECT_EQ(shake, rwsim::trial::loadTrialProtocol(options.protocol));

  const auto hand = visgrab::grasp::loadHandGraspSetup(options.hand);
  const auto& entry = visgrab::test::testDatabase().scene(kCanScene);
  visgrab::session::SceneLoader shaking(visgrab::test::testDatabase(), *hand);
  shaking.setProtocol(shake);
  const visgrab::session::SceneSession replays(shaking, entry);
  const visgrab::session::SceneSession lifts(
      visgrab::session::SceneLoader(visgrab::test::testDatabase(), *hand), entry);

  std::map<std::string, visgrab::grasp::GraspRequest> byId;
  for (const auto& g : grasps) byId.emplace(g.id, g);
  int simulated = 0;
  int liftDiffers = 0;
  for (const auto& record : run.trials) {
    SCOPED_TRACE(record.graspId);
    const auto resolved = replays.resolve(byId.at(record.graspId));
    ASSERT_TRUE(resolved.placed()) << resolved.message;
    const visgrab::view::TrialReplay replay =
        visgrab::view::replayTrial(replays.trial(), resolved.parameters, replays.initialState());
    EXPECT_EQ(replay.result.outcome, record.outcome)
        << rwsim::trial::outcomeName(replay.result.outcome) << " replayed, "
        << rwsim::trial::outcomeName(record.outcome) << " in trials.csv";
    EXPECT_EQ(replay.result.simulatedTime, record.simulatedTime);
    EXPECT_EQ(replay.result.qLift, record.qLift);
    std::printf("%s: %s after %g s with the shake\n", record.graspId.c_str(),
                std::string(rwsim::trial::outcomeName(record.outcome)).c_str(),
                record.simulatedTime);
    if (record.outcome == GraspOutcome::kInCollision) continue;
    ++simulated;
    const auto lifted =
        visgrab::view::replayTrial(lifts.trial(), resolved.parameters, lifts.initialState());
    if (lifted.result.outcome != record.outcome ||
        lifted.result.simulatedTime != record.simulatedTime) {
      ++liftDiffers;
    }
  }
  // Every simulated trial of the shake is another trial under the lift.
  EXPECT_GE(simulated, 2);
  EXPECT_EQ(liftDiffers, simulated);
}

}  // namespace
