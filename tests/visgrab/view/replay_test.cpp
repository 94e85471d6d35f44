// Trials replayed on the shared test database with the SDH: the recording gives the same result
// as the benchmark's trial, the placed hand's TCP is at the grasp, the lifted object carries its
// weight on the fingers, and the pictures of the three moments and of a montage have their
// layout and the outcome's colour.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/render/offscreen_renderer.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/view/grasp_pictures.hpp"
#include "visgrab/view/trial_replay.hpp"

namespace {

using rw::math::Vector3D;
using rwsim::trial::GraspOutcome;
using visgrab::view::TrialReplay;

constexpr const char* kScene = "plain/single/cocacola/01";

const visgrab::grasp::HandGraspSetup& hand() {
  static const auto h = visgrab::grasp::loadHandGraspSetup(visgrab::test::sourceDir() /
                                                           "scenes/hands/sdh/sdh.grasp.xml");
  return *h;
}

const visgrab::session::SceneSession& session() {
  static const visgrab::session::SceneSession s(
      visgrab::session::SceneLoader(visgrab::test::testDatabase(), hand()),
      visgrab::test::testDatabase().scene(kScene));
  return s;
}

// Bottom centre of the can (ground truth).
Vector3D canBase() {
  return visgrab::test::testDatabase().groundTruth(kScene).front().X_WO.translation();
}

// SDH_CYL pointing straight down with its TCP at `tcp` (as the runner test's known grasps).
visgrab::session::SceneGrasp graspAt(const std::string& id, const Vector3D& tcp) {
  visgrab::session::SceneGrasp g;
  g.request.sceneId = kScene;
  g.request.id = id;
  g.request.method = "known";
  g.request.kind = visgrab::grasp::GraspKind::kPreshape;
  g.request.preshape = "SDH_CYL";
  g.request.X_W_tcp = rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0), tcp);
  return g;
}

rwsim::simulator::GraspParameters resolved(const visgrab::session::SceneGrasp& g) {
  const auto r = session().resolve(g.request);
  EXPECT_TRUE(r.ok()) << r.message;
  return r.parameters;
}

TEST(TrialReplay, RecordsTheBenchmarksTrialAndItsThreeMoments) {
  const auto grasp = resolved(graspAt("good", canBase() + Vector3D(0, 0, 0.06)));
  const auto& trial = session().trial();
  const auto plain = trial.run(grasp, session().initialState());
  const TrialReplay replay = visgrab::view::replayTrial(trial, grasp, session().initialState());
  // The recording does not change the trial: bit for bit the same result.
  EXPECT_EQ(replay.result.outcome, GraspOutcome::kStable);
  EXPECT_EQ(replay.result.outcome, plain.outcome);
  EXPECT_EQ(replay.result.qLift, plain.qLift);
  EXPECT_EQ(replay.result.qGws, plain.qGws);
  EXPECT_EQ(replay.result.qGwsUnit, plain.qGwsUnit);
  EXPECT_EQ(replay.result.simulatedTime, plain.simulatedTime);

  ASSERT_GE(replay.frames.size(), 10u);
  EXPECT_EQ(replay.placed, 0u);
  EXPECT_LT(replay.closed, replay.lifted);
  EXPECT_EQ(replay.lifted, replay.frames.size() - 1);
  EXPECT_EQ(replay.frames[0].phase, "placed");
  EXPECT_EQ(replay.frames[0].time, 0.0);
  EXPECT_EQ(replay.frames[replay.closed].phase, "close");
  EXPECT_EQ(replay.frames[replay.closed + 1].phase, "lift");
  EXPECT_EQ(replay.frames[replay.lifted].phase, "settle");
  EXPECT_DOUBLE_EQ(replay.frames[replay.lifted].time, plain.simulatedTime);
  const double dt = session().trial().setup().simulator.timeStep;
  for (std::size_t i = 1; i < replay.frames.size(); ++i) {
    EXPECT_GT(replay.frames[i].time, replay.frames[i - 1].time);
    EXPECT_LE(replay.frames[i].time - replay.frames[i - 1].time, 0.02 + dt + 1e-9);
  }

  // Placed: the TCP is at the grasp pose (forward kinematics of the recorded state).
  const auto& tree = session().workcell().frames();
  const auto X_W_tcp =
      rw::kinematics::worldTransform(tree, replay.frames[0].state, trial.tcpFrame());
  EXPECT_LT((X_W_tcp.translation() - grasp.X_W_tcp.translation()).norm(), 1e-9);
  EXPECT_LT((X_W_tcp.linear() - grasp.X_W_tcp.linear()).norm(), 1e-9);

  // After the lift the can is 10 cm up and hangs on the fingers: their forces carry its weight.
  const auto can = replay.result.object;
  ASSERT_TRUE(can.valid());
  const auto& body = session().dynamicWorkcell().body(can);
  const double z0 =
      rw::kinematics::worldTransform(tree, replay.frames[0].state, body.frame).translation().z();
  const double z1 =
      rw::kinematics::worldTransform(tree, replay.frames[replay.lifted].state, body.frame)
          .translation()
          .z();
  EXPECT_NEAR(z1 - z0, 0.10, 0.01);
  Vector3D total = Vector3D::Zero();
  for (const auto& c : replay.frames[replay.lifted].contacts) {
    if (c.body == can) total += c.force;
  }
  const double weight = body.mass.mass * 9.81;
  EXPECT_NEAR(total.z(), weight, 0.15 * weight);
  EXPECT_LT(total.head<2>().norm(), 0.15 * weight);
  EXPECT_FALSE(replay.frames[replay.closed].contacts.empty());
}

TEST(TrialReplay, StopsWhereTheTrialStops) {
  // The palm 2 cm above the table, through the can: in collision, nothing simulated.
  const auto through = resolved(graspAt("through", canBase() + Vector3D(0, 0, 0.02)));
  const TrialReplay collided =
      visgrab::view::replayTrial(session().trial(), through, session().initialState());
  EXPECT_EQ(collided.result.outcome, GraspOutcome::kInCollision);
  ASSERT_EQ(collided.frames.size(), 1u);
  EXPECT_EQ(collided.closed, 0u);
  EXPECT_EQ(collided.lifted, 0u);
  // 25 cm beside the can: the fingers close on nothing and the trial ends after closing.
  const auto beside = resolved(graspAt("beside", canBase() + Vector3D(0.25, 0, 0.06)));
  const TrialReplay missed =
      visgrab::view::replayTrial(session().trial(), beside, session().initialState());
  EXPECT_EQ(missed.result.outcome, GraspOutcome::kMissed);
  EXPECT_EQ(missed.closed, missed.lifted);
  EXPECT_EQ(missed.frames[missed.lifted].phase, "close");
  EXPECT_THROW(visgrab::view::replayTrial(session().trial(), beside, session().initialState(), 0.0),
               std::invalid_argument);
}

// Counts pixels of exactly `rgb` in rows [top, bottom).
int countColour(const visgrab::visual::RgbImage& image, int top, int bottom,
                const std::array<int, 3>& rgb) {
  int n = 0;
  for (int r = top; r < bottom; ++r) {
    for (int c = 0; c < image.width; ++c) {
      const std::size_t i = 3 * (static_cast<std::size_t>(r) * image.width + c);
      if (image.pixels[i] == rgb[0] && image.pixels[i + 1] == rgb[1] &&
          image.pixels[i + 2] == rgb[2]) {
        ++n;
      }
    }
  }
  return n;
}

TEST(GraspPictures, StripAndMontageLayout) {
  visgrab::render::OffscreenRenderer offscreen;
  const visgrab::view::WorkcellDrawing drawing(session().workcell(), offscreen.renderer(),
                                               hand().deviceName());
  visgrab::view::PictureOptions options;
  options.width = 200;
  options.height = 150;
  const auto good = graspAt("good", canBase() + Vector3D(0, 0, 0.06));
  const auto picture =
      visgrab::view::trialStrip(offscreen.renderer(), drawing, session(), good, options);
  EXPECT_EQ(picture.outcome, GraspOutcome::kStable);
  EXPECT_TRUE(picture.note.empty());
  // Three framed panels (1 px border) under a 36 px title, each over a 30 px caption.
  EXPECT_EQ(picture.image.width, 3 * (200 + 2));
  EXPECT_EQ(picture.image.height, 36 + 150 + 30 + 2);
  // The title's swatch is the report's colour of "stable" (#1a9641 is (26, 150, 65)).
  EXPECT_GT(countColour(picture.image, 0, 36, {26, 150, 65}), 20);

  // A record that disagrees with the replay is reported.
  auto disagreeing = good;
  disagreeing.record = visgrab::results::TrialRecord{};
  disagreeing.record->outcome = GraspOutcome::kDropped;
  EXPECT_NE(
      visgrab::view::trialStrip(offscreen.renderer(), drawing, session(), disagreeing, options)
          .note.find("results say dropped"),
      std::string::npos);

  // Montage: overview + 2 tiles in 2 columns = 2 rows, legend and title.
  std::vector<visgrab::view::MontageTile> tiles(2);
  tiles[0].label = "1";
  tiles[0].grasp = resolved(good);
  tiles[0].outcome = GraspOutcome::kStable;
  tiles[1].label = "2";
  tiles[1].outcome = GraspOutcome::kInvalidContacts;
  const auto montage = visgrab::view::graspMontage(offscreen.renderer(), drawing, session(), tiles,
                                                   "test", options, 2);
  EXPECT_EQ(montage.width, 2 * (200 + 2));
  EXPECT_EQ(montage.height, 36 + 2 * (150 + 30 + 2) + 30);
}

TEST(OutcomeCaption, HeldGraspsShowBothGwsColumns) {
  using rwsim::trial::GraspOutcome;
  EXPECT_EQ(visgrab::view::outcomeCaption(GraspOutcome::kStable, 0.93, 0.421, 0.012),
            "stable   Q_lift 0.930   Q_GWS 0.4210   Q_GWS,unit 0.0120");
  // Results written before Q_GWS,unit existed have no Q_GWS.
  EXPECT_EQ(visgrab::view::outcomeCaption(GraspOutcome::kSlipped, 0.5, std::nan(""), 0.01),
            "slipped   Q_lift 0.500   Q_GWS -   Q_GWS,unit 0.0100");
  EXPECT_EQ(visgrab::view::outcomeCaption(GraspOutcome::kMissed, 0.0, 0.0, 0.0), "missed");
}

}  // namespace
