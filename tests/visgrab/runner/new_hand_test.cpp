// A hand is its files: the parallel gripper of docs/adding-a-hand.md written into a temporary
// folder from the page's XML alone (a workcell, its collision setup, its dynamics, its grasp
// description) runs grasps in the shared test database's scenes,
// which were generated with the SDH. Its outcomes are those its geometry implies: jaws around the
// can hold it, jaws 25 cm beside it close on nothing, the palm pushed into it collides.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/session/scene_loader.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

namespace fs = std::filesystem;
using rw::math::Vector3D;

constexpr const char* kScene = "plain/single/cocacola/01";

// The gripper of docs/adding-a-hand.md, "Jaws", taken from the page's XML blocks (so the
// walk-through is tested as written): a housing 4 cm high, two 8 cm long jaws sliding apart along
// the base's y axis (q = the opening of each: inner faces 2 q + 1 cm apart, 0..5 cm), the TCP
// between the jaws 9 cm above the base, z along the approach, x along the closing direction.
// The page's first xml block that starts with <root and mentions `mark` (the hand's name or one
// of its frames).
std::string docBlock(const std::string& root, const std::string& mark) {
  std::ifstream in(visgrab::test::sourceDir() / "docs/adding-a-hand.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t at = doc.find("```xml\n"); at != std::string::npos;
       at = doc.find("```xml\n", at + 1)) {
    const std::size_t begin = at + 7;
    const std::size_t end = doc.find("```", begin);
    const std::string block = doc.substr(begin, end - begin);
    if (block.rfind("<" + root, 0) == 0 && block.find(mark) != std::string::npos) return block;
  }
  ADD_FAILURE() << "docs/adding-a-hand.md has no xml block starting with <" << root
                << " that mentions " << mark;
  return {};
}

// Writes the gripper's files into `folder` (without its dynamics file when `dynamics` is false).
void writeJaws(const fs::path& folder, bool dynamics = true) {
  visgrab::test::writeFile(folder / "jaws.wc.xml", docBlock("TreeDevice", "Jaws"));
  visgrab::test::writeFile(folder / "jaws.prox.xml", docBlock("CollisionSetup", "Right"));
  if (dynamics) {
    visgrab::test::writeFile(folder / "jaws_dynamics.dwc.xml", docBlock("IncludeData", "Jaws"));
  }
  visgrab::test::writeFile(folder / "jaws.grasp.xml", docBlock("GraspDescription", "Jaws"));
}

// The page's second hand, "Claw": three fingers 120 degrees apart on a palm (cylinder r 7 cm,
// 3 cm thick), each a proximal link (6 cm) and a distal link (4 cm) whose joint follows the
// proximal one (Depend, gain 1); q = the three proximal angles, positive inwards; the TCP on the
// palm's axis 10 cm from its base face.
void writeClaw(const fs::path& folder) {
  visgrab::test::writeFile(folder / "claw.wc.xml", docBlock("TreeDevice", "Claw"));
  visgrab::test::writeFile(folder / "claw.prox.xml", docBlock("CollisionSetup", "F1.Proximal"));
  visgrab::test::writeFile(folder / "claw_dynamics.dwc.xml", docBlock("IncludeData", "Claw"));
  visgrab::test::writeFile(folder / "claw.grasp.xml", docBlock("GraspDescription", "Claw"));
}

// The gripper's folder, written once.
const fs::path& handFolder() {
  static visgrab::test::TempDir dir;
  static const fs::path folder = [] {
    const fs::path f = dir.path() / "jaws";
    writeJaws(f);
    return f;
  }();
  return folder;
}

Vector3D canBase() {
  return visgrab::test::testDatabase().groundTruth(kScene).front().X_WO.translation();
}

// The gripper pointing down (RPY 0 180 0) with its TCP at `tcp`, pre-shape "wide".
visgrab::grasp::GraspRequest downAt(const std::string& id, const Vector3D& tcp) {
  visgrab::grasp::GraspRequest r;
  r.sceneId = kScene;
  r.id = id;
  r.method = "jaws";
  r.kind = visgrab::grasp::GraspKind::kPreshape;
  r.preshape = "wide";
  r.X_W_tcp = rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0), tcp);
  return r;
}

// Runs `grasps` with `hand` into `dir` (no grasp may be rejected) and returns the trials by
// grasp id.
std::map<std::string, visgrab::results::TrialRecord> runGrasps(
    const std::vector<visgrab::grasp::GraspRequest>& grasps, const fs::path& hand,
    const fs::path& dir, int threads = 1) {
  visgrab::taskio::writeGraspList(grasps, dir / "plan.csv");
  visgrab::runner::RunOptions options;
  options.database = visgrab::test::testDatabase().root();
  options.grasps = {dir / "plan.csv"};
  options.out = dir / "results";
  options.hand = hand;
  options.threads = threads;
  EXPECT_TRUE(visgrab::runner::runBenchmark(options).rejected.empty());
  std::map<std::string, visgrab::results::TrialRecord> trial;
  for (const auto& t : visgrab::results::readResults(options.out).trials) trial[t.graspId] = t;
  return trial;
}

TEST(NewHand, TheSceneGetsTheGivenHand) {
  const auto hand = visgrab::grasp::loadHandGraspSetup(handFolder());  // the folder is enough
  EXPECT_EQ(hand->deviceName(), "Jaws");
  EXPECT_EQ(hand->dynamicsFile(), (handFolder() / "jaws_dynamics.dwc.xml").lexically_normal());
  const auto& entry = visgrab::test::testDatabase().scene(kScene);
  const auto dwc = visgrab::session::SceneLoader(visgrab::test::testDatabase(), *hand).load(entry);
  ASSERT_EQ(dwc->devices().size(), 1u);
  EXPECT_EQ(dwc->devices()[0].device->name(), "Jaws");
  EXPECT_EQ(dwc->workcell().findDevice("SchunkHand"), nullptr);
  EXPECT_TRUE(dwc->workcell().findFrame("HandMount").valid());
  // The SDH the database was generated with: the scene as it is.
  const auto sdh =
      visgrab::grasp::loadHandGraspSetup(visgrab::test::sourceDir() / "scenes/hands/sdh");
  const auto original =
      visgrab::session::SceneLoader(visgrab::test::testDatabase(), *sdh).load(entry);
  EXPECT_NE(original->workcell().findDevice("SchunkHand"), nullptr);
}

TEST(NewHand, RunsGraspsWithTheOutcomesItsGeometryImplies) {
  // Pointing down, the housing spans 5..9 cm above the TCP and the jaws 3 cm below to 5 cm
  // above it. With the TCP 9 cm above the can's base (the can is 11.5 cm high) the jaws hold the
  // can's upper 8 cm and the housing is clear of its top; 4 cm above the base the housing is in
  // the can.
  const Vector3D high = canBase() + Vector3D(0, 0, 0.09);
  std::vector<visgrab::grasp::GraspRequest> grasps = {
      downAt("around", high),
      downAt("beside", high + Vector3D(0.25, 0, 0)),
      downAt("into", canBase() + Vector3D(0, 0, 0.04)),
  };
  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList(grasps, tmp.path() / "plan.csv");
  visgrab::runner::RunOptions options;
  options.database = visgrab::test::testDatabase().root();
  options.grasps = {tmp.path() / "plan.csv"};
  options.out = tmp.path() / "results";
  options.hand = handFolder();
  options.threads = 2;
  const auto summary = visgrab::runner::runBenchmark(options);
  EXPECT_TRUE(summary.rejected.empty());
  std::map<std::string, std::string> outcome;
  const auto results = visgrab::results::readResults(options.out);
  for (const auto& t : results.trials) {
    outcome[t.graspId] = std::string(rwsim::trial::outcomeName(t.outcome)) + " " + t.detail;
  }
  EXPECT_EQ(outcome["around"].substr(0, 6), "stable") << outcome["around"];
  EXPECT_EQ(outcome["beside"].substr(0, 6), "missed") << outcome["beside"];
  EXPECT_EQ(outcome["into"].substr(0, 12), "in_collision") << outcome["into"];
  EXPECT_EQ(results.sources.hand, fs::absolute(handFolder()).lexically_normal());
}

// The claw of the page's second part, from its XML alone: its three linked fingers hold the can
// from above (TCP 8 cm above the can's base: the palm clears the 11.5 cm can by 3.5 cm, the
// fingers reach down to 5 cm above the base) and close on nothing 25 cm beside it, where they
// meet each other. Both closings end by the rest test, long before the 5 s cap (before the
// dependent joints' fix they never came to rest: every closing ran into the cap, the can was
// pushed over).
TEST(NewHand, TheLinkedClawHoldsTheCanAndItsClosingsEnd) {
  visgrab::test::TempDir tmp;
  const fs::path claw = tmp.path() / "claw";
  writeClaw(claw);
  const auto hand = visgrab::grasp::loadHandGraspSetup(claw);
  EXPECT_EQ(hand->deviceName(), "Claw");
  const Vector3D high = canBase() + Vector3D(0, 0, 0.08);
  const std::vector<visgrab::grasp::GraspRequest> grasps = {
      downAt("around", high), downAt("beside", high + Vector3D(0.25, 0, 0))};
  const auto trial = runGrasps(grasps, claw, tmp.path());
  ASSERT_EQ(trial.size(), 2u);
  EXPECT_EQ(rwsim::trial::outcomeName(trial.at("around").outcome), "stable")
      << trial.at("around").detail;
  EXPECT_EQ(rwsim::trial::outcomeName(trial.at("beside").outcome), "missed")
      << trial.at("beside").detail;
  for (const auto& [id, t] : trial) {
    SCOPED_TRACE(id);
    EXPECT_FALSE(rwsim::trial::closingHitCap(t.detail)) << t.detail;
    // A missed trial ends with its closing; a held one runs on for the lift (0.1 m at 0.5 m/s
    // after a 1 m/s^2 ramp: 0.3 s) and the 0.2 s settling.
    EXPECT_LT(t.simulatedTime, id == "beside" ? 1.0 : 1.5);
  }
}

// The project's three hands run one pre-shape plan ("wide": SDH_WIDE, PG70, R2F85_OPEN, each in
// its two-finger grasp frame, x along the closing direction): the can is held by each, nothing is
// touched 25 cm beside it.
TEST(NewHand, TheProjectsHandsRunOnePreshapePlan) {
  const Vector3D high = canBase() + Vector3D(0, 0, 0.09);
  const std::vector<visgrab::grasp::GraspRequest> grasps = {
      downAt("around", high), downAt("beside", high + Vector3D(0.25, 0, 0))};
  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList(grasps, tmp.path() / "plan.csv");
  for (const char* hand : {"sdh", "pg70", "robotiq2f85"}) {
    SCOPED_TRACE(hand);
    visgrab::runner::RunOptions options;
    options.database = visgrab::test::testDatabase().root();
    options.grasps = {tmp.path() / "plan.csv"};
    options.out = tmp.path() / hand;
    options.hand = visgrab::test::sourceDir() / "scenes/hands" / hand;
    const auto summary = visgrab::runner::runBenchmark(options);
    EXPECT_TRUE(summary.rejected.empty());
    std::map<std::string, rwsim::trial::GraspOutcome> outcome;
    for (const auto& t : visgrab::results::readResults(options.out).trials) {
      outcome[t.graspId] = t.outcome;
    }
    EXPECT_TRUE(visgrab::results::isSuccess(outcome.at("around")))
        << rwsim::trial::outcomeName(outcome.at("around"));
    EXPECT_EQ(outcome.at("beside"), rwsim::trial::GraspOutcome::kMissed);
  }
}

// The 2F-85's pads are kept parallel by its closed four-bar linkages (issue 21): off-centre and
// high grasps of the can, pointing down, against the PG70's outcomes (docs/adding-a-hand.md,
// "Off-centre and high grasps"). World x is the closing axis, y runs along the pads' width;
// heights are above the can's base. Every grasp the PG70 holds, the 2F-85 holds, and stable
// wherever the PG70 is stable, except 15 mm across the pads: the can's contact line then lies
// outside the 2F-85's 22 mm wide pads (the PG70's jaws are 30 mm wide), and it slips.
TEST(NewHand, The2F85HoldsOffCentreAndHighGraspsAsThePg70) {
  struct Case {
    const char* id;
    Vector3D offset;
  };
  const std::vector<Case> cases = {{"centre", Vector3D(0, 0, 0.09)},
                                   {"closing7.5_high20", Vector3D(0.0075, 0, 0.11)},
                                   {"across12_high10", Vector3D(0, 0.012, 0.10)},
                                   {"across15", Vector3D(0, 0.015, 0.09)}};
  std::vector<visgrab::grasp::GraspRequest> grasps;
  for (const Case& c : cases) grasps.push_back(downAt(c.id, canBase() + c.offset));
  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList(grasps, tmp.path() / "plan.csv");
  std::map<std::string, std::map<std::string, rwsim::trial::GraspOutcome>> outcome;
  for (const char* hand : {"pg70", "robotiq2f85"}) {
    visgrab::runner::RunOptions options;
    options.database = visgrab::test::testDatabase().root();
    options.grasps = {tmp.path() / "plan.csv"};
    options.out = tmp.path() / hand;
    options.hand = visgrab::test::sourceDir() / "scenes/hands" / hand;
    EXPECT_TRUE(visgrab::runner::runBenchmark(options).rejected.empty()) << hand;
    for (const auto& t : visgrab::results::readResults(options.out).trials) {
      outcome[hand][t.graspId] = t.outcome;
    }
  }
  using rwsim::trial::GraspOutcome;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.id);
    const GraspOutcome pg70 = outcome["pg70"].at(c.id);
    const GraspOutcome r2f85 = outcome["robotiq2f85"].at(c.id);
    EXPECT_EQ(pg70, GraspOutcome::kStable) << rwsim::trial::outcomeName(pg70);
    EXPECT_TRUE(visgrab::results::isSuccess(r2f85)) << rwsim::trial::outcomeName(r2f85);
    if (std::string(c.id) != "across15") {
      EXPECT_EQ(r2f85, GraspOutcome::kStable) << rwsim::trial::outcomeName(r2f85);
    }
  }
}

// RobWork's own Robotiq 2-finger 85 model (RW_COMPAT_DATA) as a hand: the folder
// scenes/hands/robwork-robotiq mounts RobWork's unchanged device file on a Movable frame and adds
// a TCP, a dynamics file and a grasp description. The gripper's datasheet stroke is 85 mm: the
// pads' centres (RobWork's junction frames LeftMotorEnd / RightMotorEnd) are 85 mm apart open and
// meet closed, on the TCP's x axis; the pads lie 10.5 mm short of the TCP open (the TCP is where
// they meet a 50 mm object). It holds the can from above and closes on nothing beside it.
TEST(NewHand, RobWorksRobotiqRunsAsAHand) {
  REQUIRE_COMPAT_DATA(data);  // the hand's workcell reads ${RW_COMPAT_DATA} itself
  static_cast<void>(data);
  const fs::path folder = visgrab::test::sourceDir() / "scenes/hands/robwork-robotiq";
  const auto hand = visgrab::grasp::loadHandGraspSetup(folder);
  EXPECT_EQ(hand->deviceName(), "RobotiqFingerControl");
  EXPECT_EQ(hand->dof(), 3);
  const auto& tree = hand->workcell().frames();
  EXPECT_EQ(tree.frame(hand->placementFrame()).name(), "RobotiqMount");
  EXPECT_EQ(hand->tcpFrameName(), "RobotiqTCP");
  const auto* wide = hand->findPreshape("wide");
  ASSERT_NE(wide, nullptr);
  for (const bool open : {true, false}) {
    SCOPED_TRACE(open ? "open" : "closed");
    rw::kinematics::State state = hand->defaultState();
    hand->device().setQ(open ? wide->qOpen : wide->qClosed, state);
    const auto pad = [&](const char* name) -> Vector3D {
      return rw::kinematics::relativeTransform(tree, state, hand->tcpFrame(),
                                               hand->workcell().findFrame(name))
          .translation();
    };
    const Vector3D right = pad("RobotiqFingerControl.RightMotorEnd");
    const Vector3D left = pad("RobotiqFingerControl.LeftMotorEnd");
    EXPECT_NEAR(right.x() - left.x(), open ? 0.085 : 0.0, 0.001);
    EXPECT_NEAR(right.y(), 0.0, 1e-9);
    EXPECT_NEAR(left.y(), 0.0, 1e-9);
    if (open) {
      EXPECT_NEAR(right.z(), -0.0105, 0.0002);
    }
    EXPECT_NEAR(right.z(), left.z(), 1e-6);
  }

  const Vector3D high = canBase() + Vector3D(0, 0, 0.09);
  const std::vector<visgrab::grasp::GraspRequest> grasps = {
      downAt("around", high), downAt("beside", high + Vector3D(0.25, 0, 0))};
  visgrab::test::TempDir tmp;
  const auto trial = runGrasps(grasps, folder, tmp.path(), 2);
  ASSERT_EQ(trial.size(), 2u);
  EXPECT_EQ(rwsim::trial::outcomeName(trial.at("around").outcome), "stable")
      << trial.at("around").detail;
  EXPECT_EQ(rwsim::trial::outcomeName(trial.at("beside").outcome), "missed")
      << trial.at("beside").detail;
  for (const auto& [id, t] : trial) {
    EXPECT_FALSE(rwsim::trial::closingHitCap(t.detail)) << id << ": " << t.detail;
  }
}

// A scene that is not generated (written by hand, as an original one) includes its gripper from
// a folder that is not hands/<hand>/: it runs as it is with that gripper, and another hand is an
// error that names the scene, not a silent run with the wrong hand.
TEST(NewHand, ASceneHoldingItsHandDirectlyIsUsedAsItIs) {
  visgrab::test::TempDir tmp;
  const fs::path gripper = tmp.path() / "gripper";
  writeJaws(gripper);
  visgrab::test::writeFile(tmp.path() / "scene.wc.xml", R"(<WorkCell name="S">
  <Frame name="Table" refframe="WORLD"><RPY>0 0 0</RPY><Pos>0 0 0</Pos>
    <CollisionModel name="Top"><RPY>0 0 0</RPY><Pos>0 0 -0.02</Pos><Box x="1" y="1" z="0.04"/>
    </CollisionModel>
  </Frame>
  <Frame name="HandMount" refframe="WORLD"><RPY>0 0 0</RPY><Pos>0 0 0.5</Pos></Frame>
  <Include file="gripper/jaws.wc.xml"/>
</WorkCell>
)");
  const fs::path materials = visgrab::test::sourceDir() / "scenes/materials.xml";
  visgrab::test::writeFile(tmp.path() / "scene.dwc.xml",
                           "<DynamicWorkcell workcell=\"scene.wc.xml\">\n"
                           "  <Gravity>0 0 -9.81</Gravity>\n  <Include file=\"" +
                               materials.generic_string() +
                               "\"/>\n"
                               "  <FixedBody frame=\"Table\"><MaterialID>Table</MaterialID></"
                               "FixedBody>\n"
                               "  <Include file=\"gripper/jaws_dynamics.dwc.xml\"/>\n"
                               "</DynamicWorkcell>\n");
  visgrab::database::SceneEntry entry;
  entry.id = "hand-written";
  entry.workcell = tmp.path() / "scene.wc.xml";
  entry.dynamicWorkcell = tmp.path() / "scene.dwc.xml";
  const auto jaws = visgrab::grasp::loadHandGraspSetup(gripper);
  const auto dwc = visgrab::session::SceneLoader(visgrab::test::testDatabase(), *jaws).load(entry);
  EXPECT_TRUE(dwc->findDevice("Jaws").valid());
  const auto sdh =
      visgrab::grasp::loadHandGraspSetup(visgrab::test::sourceDir() / "scenes/hands/sdh");
  try {
    visgrab::session::SceneLoader(visgrab::test::testDatabase(), *sdh).load(entry);
    FAIL() << "put the SDH into a scene that cannot take it";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("scene hand-written has no device 'SchunkHand'"),
              std::string::npos)
        << e.what();
  }
}

// A hand that cannot run (its dynamics file missing) is the run's error, once, not a rejection
// of every grasp.
TEST(NewHand, AHandThatCannotRunFailsTheRun) {
  visgrab::test::TempDir tmp;
  const fs::path gripper = tmp.path() / "jaws";
  writeJaws(gripper, false);
  visgrab::taskio::writeGraspList({downAt("around", canBase() + Vector3D(0, 0, 0.09))},
                                  tmp.path() / "plan.csv");
  visgrab::runner::RunOptions options;
  options.database = visgrab::test::testDatabase().root();
  options.grasps = {tmp.path() / "plan.csv"};
  options.out = tmp.path() / "results";
  options.hand = gripper;
  try {
    visgrab::runner::runBenchmark(options);
    FAIL() << "ran with a hand without dynamics";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot run in scene plain/single/cocacola/01"), std::string::npos) << what;
    EXPECT_NE(what.find("jaws_dynamics.dwc.xml is missing"), std::string::npos) << what;
  }
}

TEST(NewHand, AFolderWithoutOneGraspDescriptionIsAnError) {
  visgrab::test::TempDir tmp;
  try {
    visgrab::grasp::loadHandGraspSetup(tmp.path());
    FAIL() << "loaded a hand from an empty folder";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("holds no grasp description"), std::string::npos)
        << e.what();
  }
  visgrab::test::writeFile(tmp.path() / "a.grasp.xml", docBlock("GraspDescription", "Jaws"));
  visgrab::test::writeFile(tmp.path() / "b.grasp.xml", docBlock("GraspDescription", "Jaws"));
  try {
    visgrab::grasp::loadHandGraspSetup(tmp.path());
    FAIL() << "loaded a hand from a folder with two descriptions";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("a.grasp.xml, b.grasp.xml"), std::string::npos)
        << e.what();
  }
}

}  // namespace
