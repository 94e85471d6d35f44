// One file of parallel-jaw grasps (kind jaw, docs/grasp-format.md "Parallel-jaw grasps") run with
// every hand that declares a jaw frame, through the benchmark run on the test database's can: the
// same jaw grasps, placed by each hand's own jaw frame, hold the can with every hand and touch
// nothing beside it.
#include <gtest/gtest.h>

#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

using rw::math::Vector3D;

constexpr const char* kCanScene = "plain/single/cocacola/01";

// A jaw grasp from above (jaw z = world -z, closing along world x) with the pads' centre at
// `centre`, 66 mm wide (the can's diameter).
visgrab::grasp::GraspRequest jawDownAt(const std::string& id, const Vector3D& centre) {
  visgrab::grasp::GraspRequest r;
  r.sceneId = kCanScene;
  r.id = id;
  r.method = "net";
  r.kind = visgrab::grasp::GraspKind::kJaw;
  r.X_W_jaw = rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0), centre);
  r.width = 0.066;
  r.score = 0.9;
  return r;
}

// The pads' centre on the can's axis 9 cm above its base (the can is 11.5 cm tall; every hand's
// palm is then clear of its top: the PG70's housing, the closest, is 36 mm above the pads'
// centre), and the same 25 cm beside it.
TEST(JawPlan, OneFileOfJawGraspsRunsOnEveryParallelJawHand) {
  const Vector3D base =
      visgrab::test::testDatabase().groundTruth(kCanScene).front().X_WO.translation();
  const Vector3D centre = base + Vector3D(0, 0, 0.09);
  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList(
      {jawDownAt("around", centre), jawDownAt("beside", centre + Vector3D(0.25, 0, 0))},
      tmp.path() / "jaw.csv");
  for (const char* hand : {"franka", "pg70", "robotiq2f85", "sdh"}) {
    SCOPED_TRACE(hand);
    visgrab::runner::RunOptions options;
    options.database = visgrab::test::testDatabase().root();
    options.grasps = {tmp.path() / "jaw.csv"};
    options.out = tmp.path() / hand;
    options.hand = visgrab::test::sourceDir() / "scenes/hands" / hand;
    const auto summary = visgrab::runner::runBenchmark(options);
    EXPECT_TRUE(summary.rejected.empty());
    std::map<std::string, rwsim::trial::GraspOutcome> outcome;
    for (const auto& t : visgrab::results::readResults(options.out).trials) {
      outcome[t.graspId] = t.outcome;
    }
    ASSERT_EQ(outcome.size(), 2u);
    EXPECT_TRUE(visgrab::results::isSuccess(outcome.at("around")))
        << rwsim::trial::outcomeName(outcome.at("around"));
    EXPECT_EQ(outcome.at("beside"), rwsim::trial::GraspOutcome::kMissed)
        << rwsim::trial::outcomeName(outcome.at("beside"));
  }
}

// A grasp wider than a hand's stroke is rejected by the run with the reason, not clipped.
TEST(JawPlan, AGraspWiderThanTheStrokeIsRejected) {
  const Vector3D base =
      visgrab::test::testDatabase().groundTruth(kCanScene).front().X_WO.translation();
  auto wide = jawDownAt("wide", base + Vector3D(0, 0, 0.09));
  wide.width = 0.084;  // 1 mm beyond the PG70's stroke
  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList({wide}, tmp.path() / "jaw.csv");
  visgrab::runner::RunOptions options;
  options.database = visgrab::test::testDatabase().root();
  options.grasps = {tmp.path() / "jaw.csv"};
  options.out = tmp.path() / "pg70";
  options.hand = visgrab::test::sourceDir() / "scenes/hands/pg70";
  const auto summary = visgrab::runner::runBenchmark(options);
  ASSERT_EQ(summary.rejected.size(), 1u);
  EXPECT_NE(summary.rejected.front().format().find(
                "width 0.084 m is outside what hand \"PG70\" opens to (0 to its stroke 0.083 m)"),
            std::string::npos)
      << summary.rejected.front().format();
}

}  // namespace
