// The benchmark run on the shared generated test database with grasps whose outcome is known from
// the objects' ground-truth poses: each grasp representation, rejected input, and a run killed with
// SIGKILL (refused by the analyses until it is finished) and resumed against an uninterrupted one
// (byte-equal results).
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
#include <numbers>
#include <thread>

#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

namespace fs = std::filesystem;
namespace db = visgrab::database;
using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;

// Scenes of the shared test database (kTestSceneIds).
const std::vector<db::SceneConditions>& scenes() {
  static const std::vector<db::SceneConditions> s{
      db::SceneConditions::single(db::Texture::kPlain, 5, 1),       // cocacola standing
      db::SceneConditions::single(db::Texture::kPlain, 13, 1),      // saltbox standing
      db::SceneConditions::pairScene(db::Texture::kPlain, 'e', 1),  // cocacola + saltcylinder
      db::SceneConditions::single(db::Texture::kTextured, 11, 2),   // peachcan standing
      db::SceneConditions::single(db::Texture::kPlain, 10, 3),      // marmelade standing
  };
  return s;
}

// The shared test database (tests/support/test_database.hpp), which holds the scenes above.
const db::Database& database() { return visgrab::test::testDatabase(); }

fs::path handFile() { return visgrab::test::sourceDir() / "scenes/hands/sdh/sdh.grasp.xml"; }

// The SDH pointing straight down with its TCP at `p` (RobWork RPY 0 180 0, as the simulator
// tests' centred grasp).
Transform3D downAt(const Vector3D& p) {
  return rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0), p);
}

// Position of object `id`'s frame (bottom centre) in scene `scene`.
Vector3D objectBase(const db::SceneConditions& scene, int id) {
  for (const auto& pose : database().groundTruth(db::sceneIdOf(scene))) {
    if (pose.object == id) return pose.X_WO.translation();
  }
  throw std::runtime_error("no such object");
}

GraspRequest preshape(const db::SceneConditions& scene, const std::string& id,
                      const Vector3D& tcp) {
  GraspRequest r;
  r.sceneId = db::sceneIdOf(scene);
  r.id = id;
  r.method = "known";
  r.kind = GraspKind::kPreshape;
  r.preshape = "SDH_CYL";
  r.X_W_tcp = downAt(tcp);
  return r;
}

std::string fileBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::map<std::string, std::string> outcomesById(const fs::path& results) {
  std::map<std::string, std::string> out;
  for (const auto& t : visgrab::results::readResults(results).trials) {
    out[t.graspId] = std::string(rwsim::trial::outcomeName(t.outcome));
  }
  return out;
}

// Grasps whose outcome is clear from the object's pose, in every representation, on four
// single-object scenes (a can, a box, a tin on the textured table, a jar): the SDH's cylinder
// pre-shape around the middle of the object (raw, pre-shape and pose + q), the palm through
// the object, the grasp 25 cm beside it, and contacts no hand reaches.
TEST(BenchmarkRun, KnownGraspsGiveTheirOutcomesInEveryRepresentation) {
  std::vector<GraspRequest> grasps;
  std::vector<std::string> ids;
  for (const std::size_t i : {0u, 1u, 3u, 4u}) {  // the single-object scenes
    const auto& scene = scenes()[i];
    const int object = scene.objects[0];
    const Vector3D base = objectBase(scene, object);
    const std::string tag = std::to_string(i) + "_";
    // Fingers around the object's middle (all are 11-12.5 cm high), palm above it.
    const Vector3D middle = base + Vector3D(0, 0, 0.06);
    grasps.push_back(preshape(scene, tag + "good", middle));
    // The palm 2 cm above the table: through the object.
    grasps.push_back(preshape(scene, tag + "through", base + Vector3D(0, 0, 0.02)));
    // 25 cm beside the object, nothing between the fingers.
    grasps.push_back(preshape(scene, tag + "beside", middle + Vector3D(0.25, 0, 0)));
    // The good grasp as raw parameters: SDH_CYL of reference §7.1, tau by the hand's rule.
    GraspRequest raw = preshape(scene, tag + "raw", middle);
    raw.kind = GraspKind::kRaw;
    raw.qOpen = rw::math::Q{{-1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174}};
    raw.qClosed = rw::math::Q{{0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349}};
    grasps.push_back(raw);
    // Pose + q: q open around the object (fingers 0.6 rad out); the hand's rule
    // closes the proximal joints 30 degrees further, past the object's surface.
    GraspRequest poseQ = raw;
    poseQ.id = tag + "pose_q";
    poseQ.kind = GraspKind::kPoseAndQ;
    poseQ.qOpen = rw::math::Q{{-0.6, 0.2, 0.0, -0.6, 0.2, -0.6, 0.2}};
    poseQ.qClosed = rw::math::Q();
    grasps.push_back(poseQ);
    // Contacts 40 cm apart: no hand reaches them.
    GraspRequest far;
    far.sceneId = db::sceneIdOf(scene);
    far.id = tag + "far_contacts";
    far.method = "known";
    far.kind = GraspKind::kContacts;
    far.contacts = {{middle + Vector3D(-0.2, 0, 0), Vector3D(1, 0, 0)},
                    {middle + Vector3D(0.2, 0, 0), Vector3D(-1, 0, 0)}};
    far.approach = -Vector3D::UnitZ();
    grasps.push_back(far);
    ids.push_back(tag);
  }

  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList(grasps, tmp.path() / "known.txt");
  visgrab::runner::RunOptions options;
  options.database = database().root();
  options.grasps = {tmp.path() / "known.txt"};
  options.out = tmp.path() / "results";
  options.hand = handFile();
  options.threads = 2;
  const auto summary = visgrab::runner::runBenchmark(options);
  EXPECT_EQ(summary.trials, static_cast<int>(grasps.size()));
  EXPECT_TRUE(summary.rejected.empty());
  const auto outcome = outcomesById(options.out);
  ASSERT_EQ(outcome.size(), grasps.size());
  for (const auto& tag : ids) {
    for (const std::string good : {"good", "raw", "pose_q"}) {
      const std::string& o = outcome.at(tag + good);
      EXPECT_TRUE(o == "stable" || o == "slipped") << tag + good << ": " << o;
    }
    EXPECT_EQ(outcome.at(tag + "raw"), outcome.at(tag + "good")) << tag;
    EXPECT_EQ(outcome.at(tag + "through"), "in_collision") << tag;
    EXPECT_EQ(outcome.at(tag + "beside"), "missed") << tag;
    EXPECT_EQ(outcome.at(tag + "far_contacts"), "invalid_contacts") << tag;
  }
}

TEST(BenchmarkRun, MalformedGraspsAreRejectedAndTheOthersRun) {
  visgrab::test::TempDir tmp;
  const auto& box = scenes()[1];
  const Vector3D base = objectBase(box, 13);
  std::vector<GraspRequest> grasps{preshape(box, "ok1", base + Vector3D(0, 0, 0.07)),
                                   preshape(box, "ok2", base + Vector3D(0.25, 0, 0.07))};
  GraspRequest unknownShape = preshape(box, "bad_shape", base + Vector3D(0, 0, 0.07));
  unknownShape.preshape = "NO_SUCH_SHAPE";
  grasps.push_back(unknownShape);
  GraspRequest unknownScene = preshape(box, "bad_scene", base);
  unknownScene.sceneId = "plain/single/saltbox/09";
  grasps.push_back(unknownScene);
  GraspRequest shortQ = preshape(box, "short_q", base + Vector3D(0, 0, 0.07));
  shortQ.kind = GraspKind::kPoseAndQ;
  shortQ.qOpen = rw::math::Q{{0.1, 0.2}};
  grasps.push_back(shortQ);
  visgrab::taskio::writeGraspList(grasps, tmp.path() / "mixed.txt");
  // Plus lines the reader itself rejects: a bad number and a non-unit quaternion.
  {
    std::ofstream out(tmp.path() / "mixed.txt", std::ios::app);
    out << db::sceneIdOf(box) << ",known,bad_number,preshape,0.0,0.0,zero,1,0,0,0,SDH_CYL\n";
    out << db::sceneIdOf(box) << ",known,bad_quaternion,preshape,0,0,0.1,0.5,0.5,0.5,0.6,SDH_CYL\n";
  }
  visgrab::runner::RunOptions options;
  options.database = database().root();
  options.grasps = {tmp.path() / "mixed.txt"};
  options.out = tmp.path() / "results";
  options.hand = handFile();
  const auto summary = visgrab::runner::runBenchmark(options);
  EXPECT_EQ(summary.trials, 2);
  ASSERT_EQ(summary.rejected.size(), 5u);
  for (const auto& d : summary.rejected) {
    EXPECT_NE(d.file.find("mixed.txt"), std::string::npos) << d.format();
    EXPECT_GT(d.line, 0) << d.format();
    // The location is given once, by the diagnostic (not again inside its message).
    EXPECT_EQ(d.message.find("mixed.txt"), std::string::npos) << d.format();
  }
  const auto shape =
      std::find_if(summary.rejected.begin(), summary.rejected.end(),
                   [](const auto& d) { return d.message.find("NO_SUCH") != d.message.npos; });
  ASSERT_NE(shape, summary.rejected.end());
  EXPECT_EQ(shape->message.rfind("grasp bad_shape: unknown pre-shape \"NO_SUCH_SHAPE\"", 0), 0u)
      << shape->format();
  const auto run = visgrab::results::readResults(options.out);
  int rejected = 0;
  for (const auto& [method, n] : run.rejected) rejected += n;
  EXPECT_EQ(rejected, 5);  // 3 under the method, the 2 unparsable lines under the file
}

TEST(BenchmarkRun, AKilledRunResumesToTheSameResults) {
  visgrab::test::TempDir tmp;
  std::vector<GraspRequest> grasps;
  for (const auto& scene : scenes()) {
    const int object = scene.objects[0];
    const Vector3D base = objectBase(scene, object);
    for (int k = 0; k < 6; ++k) {
      const double a = k * std::numbers::pi / 3.0;
      grasps.push_back(preshape(scene, "g" + std::to_string(k),
                                base + Vector3D(0.03 * std::cos(a), 0.03 * std::sin(a), 0.06)));
    }
  }
  visgrab::taskio::writeGraspList(grasps, tmp.path() / "grasps.txt");
  const std::string common = "run --db " + visgrab::test::shellQuoted(database().root()) +
                             " --grasps " + visgrab::test::shellQuoted(tmp.path() / "grasps.txt") +
                             " --hand " + visgrab::test::shellQuoted(handFile()) + " --quiet";
  // Uninterrupted, one thread.
  const auto whole = visgrab::test::runVisgrab(common + " --threads 1 --out " +
                                               visgrab::test::shellQuoted(tmp.path() / "a"));
  ASSERT_EQ(whole.exitCode, 0) << whole.output;
  // Killed once some trials are written, then resumed with two threads.
  const fs::path killedOut = tmp.path() / "b";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string out = killedOut.string();
    const std::string db = database().root().string();
    const std::string file = (tmp.path() / "grasps.txt").string();
    const std::string hand = handFile().string();
    execl(VISGRAB_BINARY, VISGRAB_BINARY, "run", "--db", db.c_str(), "--grasps", file.c_str(),
          "--hand", hand.c_str(), "--quiet", "--threads", "2", "--out", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::size_t lines = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string text = fileBytes(killedOut / "trials.csv");
    lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    if (lines >= 1 + 6) break;  // the column line and at least 6 trials
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed";
  ASSERT_GE(lines, 7u);
  // The killed run's folder says it is unfinished: the analyses refuse it, naming the folder
  // and the way out, unless asked to read the trials it has, and then the report says so.
  EXPECT_TRUE(fs::exists(killedOut / "unfinished.txt"));
  EXPECT_FALSE(visgrab::results::readResults(killedOut).finished);
  const auto refused =
      visgrab::test::runVisgrab("analyze " + visgrab::test::shellQuoted(killedOut) + " --out " +
                                visgrab::test::shellQuoted(tmp.path() / "partial") + " --quiet");
  EXPECT_EQ(refused.exitCode, 1) << refused.output;
  EXPECT_NE(refused.output.find(killedOut.string() + ": the run has not finished"),
            std::string::npos)
      << refused.output;
  EXPECT_NE(refused.output.find("--resume finishes it, --allow-unfinished uses the trials it has"),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "partial" / "report.md"));
  const auto refusedAgreement =
      visgrab::test::runVisgrab("agreement " + visgrab::test::shellQuoted(tmp.path() / "a") + " " +
                                visgrab::test::shellQuoted(killedOut));
  EXPECT_EQ(refusedAgreement.exitCode, 1) << refusedAgreement.output;
  EXPECT_NE(refusedAgreement.output.find("the run has not finished"), std::string::npos)
      << refusedAgreement.output;
  const auto partial = visgrab::test::runVisgrab(
      "analyze " + visgrab::test::shellQuoted(killedOut) + " --out " +
      visgrab::test::shellQuoted(tmp.path() / "partial") + " --allow-unfinished --no-pictures");
  ASSERT_EQ(partial.exitCode, 0) << partial.output;
  EXPECT_NE(partial.output.find("unfinished.txt: warning: the run has not finished"),
            std::string::npos)
      << partial.output;
  EXPECT_NE(fileBytes(tmp.path() / "partial" / "report.md")
                .find("**Unfinished: run \"b\" has not finished"),
            std::string::npos);
  EXPECT_NE(fileBytes(tmp.path() / "partial" / "report.html")
                .find("<p><strong>Unfinished: run &quot;b&quot; has not finished"),
            std::string::npos);
  const auto resumed = visgrab::test::runVisgrab(common + " --threads 2 --resume --out " +
                                                 visgrab::test::shellQuoted(killedOut));
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resumed"), std::string::npos) << resumed.output;
  EXPECT_FALSE(fs::exists(killedOut / "unfinished.txt"));
  EXPECT_FALSE(fs::exists(tmp.path() / "a" / "unfinished.txt"));
  EXPECT_EQ(fileBytes(killedOut / "trials.csv"), fileBytes(tmp.path() / "a" / "trials.csv"));
  EXPECT_EQ(fileBytes(killedOut / "run.csv"), fileBytes(tmp.path() / "a" / "run.csv"));
  // The analyses of the two runs side by side.
  const auto report =
      visgrab::test::runVisgrab("analyze " + visgrab::test::shellQuoted(tmp.path() / "a") + " " +
                                visgrab::test::shellQuoted(killedOut) + " --out " +
                                visgrab::test::shellQuoted(tmp.path() / "report"));
  ASSERT_EQ(report.exitCode, 0) << report.output;
  const std::string html = fileBytes(tmp.path() / "report" / "report.html");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("known"), std::string::npos);
  EXPECT_TRUE(fs::exists(tmp.path() / "report" / "report.md"));
  // Without --resume an existing result folder is refused.
  const auto again =
      visgrab::test::runVisgrab(common + " --out " + visgrab::test::shellQuoted(killedOut));
  EXPECT_EQ(again.exitCode, 1) << again.output;
  EXPECT_NE(again.output.find("--resume"), std::string::npos) << again.output;
  // Resuming with another scene selection is refused (it would change the run the analyses
  // read), and the folder is left as it was.
  const auto narrowed = visgrab::test::runVisgrab(common + " --resume --scenes textured --out " +
                                                  visgrab::test::shellQuoted(killedOut));
  EXPECT_EQ(narrowed.exitCode, 1) << narrowed.output;
  EXPECT_NE(narrowed.output.find(" holds a run of " + std::to_string(database().list().size()) +
                                 " scenes; this run selects "),
            std::string::npos)
      << narrowed.output;
  EXPECT_NE(narrowed.output.find("(--scenes textured): resume it with the --scenes it was "
                                 "started with"),
            std::string::npos)
      << narrowed.output;
  EXPECT_EQ(fileBytes(killedOut / "trials.csv"), fileBytes(tmp.path() / "a" / "trials.csv"));
  EXPECT_EQ(fileBytes(killedOut / "run.csv"), fileBytes(tmp.path() / "a" / "run.csv"));
}

}  // namespace
