// The session on the shared test database: the grasps of a scene come in the order of the
// runner's trials.csv (so `--grasp N` is the scene's N-th row), also where the grasp files name
// the methods in another order for that scene than for the run; the hand goes in through Include
// redirects of the database's hand files; the scene filter selects as documented.
#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "rw/common/text_file.hpp"
#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/session/grasp_order.hpp"
#include "visgrab/session/scene_loader.hpp"
#include "visgrab/session/scene_selection.hpp"
#include "visgrab/taskio/grasp_file.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

namespace fs = std::filesystem;
using rw::math::Vector3D;
using visgrab::grasp::GraspRequest;

constexpr const char* kFirstScene = "plain/single/cocacola/01";
constexpr const char* kSecondScene = "plain/single/saltbox/01";

const visgrab::database::Database& database() { return visgrab::test::testDatabase(); }

fs::path handsFolder() { return visgrab::test::sourceDir() / "scenes/hands"; }

// The SDH pointing down with its TCP 2 cm above the first object's base (the palm in the
// object: a short trial), method `method`, id `id`.
GraspRequest grasp(const std::string& scene, const std::string& method, const std::string& id) {
  GraspRequest r;
  r.sceneId = scene;
  r.method = method;
  r.id = id;
  r.kind = visgrab::grasp::GraspKind::kPreshape;
  r.preshape = "SDH_CYL";
  const Vector3D base = database().groundTruth(scene).front().X_WO.translation();
  r.X_W_tcp =
      rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0), base + Vector3D(0, 0, 0.02));
  return r;
}

// The method "first" is seen first in the grasp file (in the first scene); in the second scene
// the file lists "second" before "first". The run orders the second scene's trials "first"
// then "second"; counting the methods per scene would put "second" first.
std::vector<GraspRequest> mixedMethods() {
  return {grasp(kFirstScene, "first", "f0"), grasp(kSecondScene, "second", "s0"),
          grasp(kSecondScene, "first", "f1"), grasp(kSecondScene, "second", "s1"),
          grasp(kSecondScene, "first", "f2")};
}

std::vector<std::string> idsOf(const std::vector<visgrab::session::SceneGrasp>& grasps) {
  std::vector<std::string> ids;
  for (const auto& g : grasps) ids.push_back(g.request.id);
  return ids;
}

TEST(GraspOrder, TheScenesGraspsComeInTheOrderOfTrialsCsv) {
  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList(mixedMethods(), tmp.path() / "plan.csv");
  visgrab::runner::RunOptions options;
  options.database = visgrab::test::testDatabasePath();
  options.grasps = {tmp.path() / "plan.csv"};
  options.out = tmp.path() / "results";
  options.hand = handsFolder() / "sdh";
  options.threads = 2;
  const auto summary = visgrab::runner::runBenchmark(options);
  ASSERT_TRUE(summary.rejected.empty());
  const auto results = visgrab::results::readResults(options.out);
  // The truth: the second scene's rows of trials.csv, in file order.
  std::vector<std::string> rows;
  std::vector<int> ranks;
  for (const auto& t : results.trials) {
    if (t.sceneId != kSecondScene) continue;
    rows.push_back(t.graspId);
    ranks.push_back(t.rank);
  }
  ASSERT_EQ(rows, (std::vector<std::string>{"f1", "f2", "s0", "s1"}));

  const auto contents = visgrab::taskio::readGraspSources(options.grasps);
  const auto& entry = database().scene(kSecondScene);
  for (const visgrab::results::RunResults* given :
       {&results, static_cast<decltype(&results)>(nullptr)}) {
    SCOPED_TRACE(given ? "with the results" : "without results");
    const auto grasps = visgrab::session::sceneGrasps(database(), entry, contents, given);
    EXPECT_EQ(idsOf(grasps), rows);
    for (std::size_t i = 0; i < grasps.size(); ++i) {
      EXPECT_EQ(grasps[i].rank, ranks[i]) << rows[i];
      EXPECT_EQ(grasps[i].record.has_value(), given != nullptr);
      // --grasp N picks the N-th row; with --method, the grasp of rank N - 1.
      const auto n = std::to_string(i + 1);
      EXPECT_EQ(visgrab::session::selectGrasp(grasps, n).request.id, rows[i]);
      const auto& byRank = visgrab::session::selectGrasp(grasps, std::to_string(ranks[i] + 1),
                                                         grasps[i].request.method);
      EXPECT_EQ(byRank.request.id, rows[i]);
    }
  }
}

TEST(GraspOrder, RanksCountPerSceneAndMethodAndUnknownScenesAreKept) {
  std::vector<GraspRequest> requests = mixedMethods();
  requests.push_back(grasp(kFirstScene, "second", "s2"));
  GraspRequest unknown = requests.front();
  unknown.sceneId = "plain/single/nothing/01";
  requests.push_back(unknown);
  const std::vector<const visgrab::database::SceneEntry*> selected = {
      &database().scene(kSecondScene), &database().scene(kFirstScene)};
  const auto order = visgrab::session::benchmarkOrder(database(), selected, requests);
  EXPECT_EQ(order.methods, (std::vector<std::string>{"first", "second"}));
  ASSERT_EQ(order.scenes.size(), 2u);
  EXPECT_EQ(order.scenes[0].entry->id, kSecondScene);
  std::vector<std::string> second;
  std::vector<int> ranks;
  for (const auto& g : order.scenes[0].grasps) {
    second.push_back(g.request->id);
    ranks.push_back(g.rank);
  }
  EXPECT_EQ(second, (std::vector<std::string>{"f1", "f2", "s0", "s1"}));
  EXPECT_EQ(ranks, (std::vector<int>{0, 1, 0, 1}));
  ASSERT_EQ(order.scenes[1].grasps.size(), 2u);
  EXPECT_EQ(order.scenes[1].grasps[1].request->id, "s2");
  EXPECT_EQ(order.scenes[1].grasps[1].rank, 0);
  ASSERT_EQ(order.unknownScene.size(), 1u);
  EXPECT_EQ(order.unknownScene[0]->sceneId, "plain/single/nothing/01");
  // A scene not selected contributes neither grasps nor methods.
  const auto onlyFirst = visgrab::session::benchmarkOrder(
      database(), {&database().scene(kFirstScene)}, mixedMethods());
  EXPECT_EQ(onlyFirst.methods, (std::vector<std::string>{"first"}));
}

TEST(SceneLoader, RedirectsTheDatabasesHandFilesToTheGivenHand) {
  const auto sdh = visgrab::grasp::loadHandGraspSetup(handsFolder() / "sdh");
  // The database was generated with the project's SDH: its scenes load as they are.
  EXPECT_TRUE(visgrab::session::handRedirects(visgrab::test::testDatabasePath(), *sdh).empty());
  const auto pg70 = visgrab::grasp::loadHandGraspSetup(handsFolder() / "pg70");
  const auto redirects = visgrab::session::handRedirects(visgrab::test::testDatabasePath(), *pg70);
  const fs::path dbHand = visgrab::test::testDatabasePath() / "hands/sdh";
  ASSERT_EQ(redirects.size(), 2u);
  EXPECT_EQ(redirects.at((dbHand / "sdh.wc.xml").lexically_normal()), pg70->workcellFile());
  EXPECT_EQ(redirects.at((dbHand / "sdh_dynamics.dwc.xml").lexically_normal()),
            pg70->dynamicsFile());
  const visgrab::session::SceneLoader loader(database(), *pg70);
  const auto dwc = loader.load(database().scene(kFirstScene));
  EXPECT_TRUE(dwc->findDevice("PG70").valid());
  EXPECT_FALSE(dwc->findDevice("SchunkHand").valid());
}

// The trial set-up carries the hand's jaw frame. The SDH's, worked from its files: ParallelTCP
// is Base turned 90 degrees about z at (0, 0, 0.177), TCP is Base at (0, 0, 0.15); the jaw frame
// lies in ParallelTCP at (0, 0.01905, 0.00398) with its axes. In the TCP: turned 90 degrees
// about z (jaw x = TCP y, fingers 2 and 3 close along Base y), at Rz(90)(0, 0.01905, 0.00398) +
// (0, 0, 0.027) = (-0.01905, 0, 0.03098).
TEST(SceneLoader, TheTrialSetUpCarriesTheHandsJawFrameAndAJawProtocolNeedsOne) {
  const auto sdh = visgrab::grasp::loadHandGraspSetup(handsFolder() / "sdh");
  visgrab::session::SceneLoader loader(database(), *sdh);
  const auto dwc = loader.load(database().scene(kFirstScene));
  const auto setup = visgrab::session::trialSetup(*sdh, *dwc);
  ASSERT_TRUE(setup.X_tcp_jaw.has_value());
  EXPECT_LT((setup.X_tcp_jaw->linear() * Vector3D::UnitX() - Vector3D::UnitY()).norm(), 1e-9);
  EXPECT_LT((setup.X_tcp_jaw->linear() * Vector3D::UnitZ() - Vector3D::UnitZ()).norm(), 1e-9);
  EXPECT_LT((setup.X_tcp_jaw->translation() - Vector3D(-0.01905, 0, 0.03098)).norm(), 1e-9);
  const auto shake =
      rwsim::trial::loadTrialProtocol(visgrab::test::sourceDir() / "scenes/protocols/shake.xml");
  ASSERT_TRUE(shake.usesJawFrame());
  EXPECT_NO_THROW(loader.setProtocol(shake));

  // The SDH's description without its <JawFrame> element: the shake is refused when it is set,
  // naming the protocol and the hand's description; the lift is not.
  std::string text = rw::common::readTextFileOrThrow(handsFolder() / "sdh/sdh.grasp.xml");
  const auto jaw = text.find("<JawFrame");
  ASSERT_NE(jaw, std::string::npos);
  text.erase(jaw, text.find("/>", jaw) + 2 - jaw);
  const auto bare =
      visgrab::grasp::loadHandGraspSetupFromString(text, handsFolder() / "sdh/nojaw.grasp.xml");
  ASSERT_EQ(bare->jawFrame(), nullptr);
  visgrab::session::SceneLoader bareLoader(database(), *bare);
  EXPECT_FALSE(visgrab::session::trialSetup(*bare, *dwc).X_tcp_jaw.has_value());
  try {
    bareLoader.setProtocol(shake);
    ADD_FAILURE() << "the shake was set for a hand without a jaw frame";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "the protocol \"shake\" gives an axis in the jaw frame, but the hand of " +
                  bare->description().file +
                  " declares no jaw frame (<JawFrame> in its grasp description, "
                  "docs/grasp-utilities.md): give a hand description that declares one (as "
                  "every hand in scenes/hands does) or a protocol whose axes are in frame "
                  "\"tcp\" or \"world\"");
  }
  EXPECT_NO_THROW(bareLoader.setProtocol(rwsim::trial::TrialProtocol::lift()));
}

TEST(SceneSelection, SelectsByTheFilterAndNamesABadWord) {
  const auto all = visgrab::session::selectScenes(database(), "");
  EXPECT_EQ(all.size(), visgrab::test::kTestSceneIds.size());
  const auto plain = visgrab::session::selectScenes(database(), "plain,single,cocacola");
  ASSERT_EQ(plain.size(), 1u);
  EXPECT_EQ(plain[0]->id, kFirstScene);
  try {
    visgrab::session::selectScenes(database(), "plain,nonsense");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scene filter: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nonsense"), std::string::npos) << e.what();
  }
}

}  // namespace
