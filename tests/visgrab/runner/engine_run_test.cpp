// A run's physics engine: recorded in run.csv with its settings; a resumed folder of another
// engine or other settings is refused; `visgrab run --engine` refuses an engine it does not know
// (or this build lacks) as a command-line error.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "rw/math/rpy.hpp"
#include "rwsim/engines/engine_registry.hpp"
#include "rwsim/trial/grasp_outcome.hpp"
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
using rw::math::Vector3D;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;

std::string readFile(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeFile(const fs::path& f, const std::string& text) {
  std::ofstream out(f, std::ios::binary);
  out << text;
}

// Two grasps on the saltbox scene of the shared test database: one around it, one beside it.
class EngineRun : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto& database = visgrab::test::testDatabase();
    const auto scene = db::SceneConditions::single(db::Texture::kPlain, 13, 1);
    Vector3D base = Vector3D::Zero();
    for (const auto& pose : database.groundTruth(db::sceneIdOf(scene))) {
      if (pose.object == 13) base = pose.X_WO.translation();
    }
    std::vector<GraspRequest> grasps;
    for (const auto& [id, offset] : {std::pair{"around", Vector3D(0, 0, 0.07)},
                                     std::pair{"beside", Vector3D(0.25, 0, 0.07)}}) {
      GraspRequest r;
      r.sceneId = db::sceneIdOf(scene);
      r.id = id;
      r.method = "known";
      r.kind = GraspKind::kPreshape;
      r.preshape = "SDH_CYL";
      r.X_W_tcp = rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0), base + offset);
      grasps.push_back(r);
    }
    visgrab::taskio::writeGraspList(grasps, tmp_.path() / "grasps.txt");
    options_.database = database.root();
    options_.grasps = {tmp_.path() / "grasps.txt"};
    options_.out = tmp_.path() / "results";
    options_.hand = visgrab::test::sourceDir() / "scenes/hands/sdh/sdh.grasp.xml";
  }

  visgrab::test::TempDir tmp_;
  visgrab::runner::RunOptions options_;
};

TEST_F(EngineRun, RunCsvRecordsTheEngineAndItsSettings) {
  visgrab::runner::runBenchmark(options_);
  const auto run = visgrab::results::readResults(options_.out);
  EXPECT_EQ(run.sources.engine, "ode");
  // The settings name ODE's version and the step the dwc's PhysicsEngine gives (5 ms).
  EXPECT_EQ(run.sources.engineSettings.rfind("ODE ", 0), 0u) << run.sources.engineSettings;
  EXPECT_NE(run.sources.engineSettings.find("step 0.005 s WorldStep"), std::string::npos)
      << run.sources.engineSettings;
  const std::string text = readFile(options_.out / "run.csv");
  EXPECT_NE(text.find("\nengine,ode,,,,,,\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nengine_settings,\"ODE "), std::string::npos) << text;
}

TEST_F(EngineRun, ResumingAnotherEnginesFolderIsRefused) {
  visgrab::runner::runBenchmark(options_);
  const fs::path runFile = options_.out / "run.csv";
  const std::string original = readFile(runFile);
  std::string other = original;
  other.replace(other.find("\nengine,ode,"), 12, "\nengine,mujoco,");
  writeFile(runFile, other);
  options_.resume = true;
  try {
    visgrab::runner::runBenchmark(options_);
    FAIL() << "a folder of MuJoCo's trials resumed on ODE";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(options_.out.string()), std::string::npos) << m;
    EXPECT_NE(m.find("engine 'mujoco'"), std::string::npos) << m;
    EXPECT_NE(m.find("engine 'ode'"), std::string::npos) << m;
  }
  // Other settings of the same engine (another time step, say) are refused too.
  std::string settings = original;
  const auto at = settings.find("step 0.005 s");
  ASSERT_NE(at, std::string::npos);
  settings.replace(at, 12, "step 0.002 s");
  writeFile(runFile, settings);
  try {
    visgrab::runner::runBenchmark(options_);
    FAIL() << "a folder of other ODE settings resumed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("step 0.002 s"), std::string::npos) << e.what();
  }
  // A run.csv older than the engine record is ODE's: it resumes (nothing left to run) and
  // gains the record.
  std::string older = original;
  older.erase(older.find("engine,ode,"), std::string("engine,ode,,,,,,\n").size());
  older.erase(older.find("engine_settings,"));
  writeFile(runFile, older);
  const auto summary = visgrab::runner::runBenchmark(options_);
  EXPECT_EQ(summary.trials, 0);
  EXPECT_EQ(summary.resumed, 2);
  EXPECT_EQ(visgrab::results::readResults(options_.out).sources.engine, "ode");
}

// 64-bit FNV-1a of a file's bytes, worked out here from the published constants (offset basis
// 14695981039346656037, prime 1099511628211), as 16 hex digits.
std::string fnv1aOfFile(const fs::path& f) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const char c : readFile(f)) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

// run.csv records the database's index hash; a resume, `render --results` and the report's
// pictures refuse a database that is not the run's any more (moved, generated again, replaced)
// with an error naming the path, instead of drawing another scene.
TEST_F(EngineRun, TheDatabasesIndexHashIsRecordedAndReplaysCheckIt) {
  visgrab::runner::runBenchmark(options_);
  const fs::path runFile = options_.out / "run.csv";
  const std::string original = readFile(runFile);
  const std::string hash = fnv1aOfFile(options_.database / "index.xml");
  EXPECT_EQ(visgrab::results::readResults(options_.out).sources.databaseHash, hash);
  EXPECT_NE(original.find("\ndatabase_hash," + hash + ",,,,,,\n"), std::string::npos) << original;

  const auto render = [&] {
    return visgrab::test::runVisgrab(
        "render --results " + visgrab::test::shellQuoted(options_.out) + " --scene " +
        db::sceneIdOf(db::SceneConditions::single(db::Texture::kPlain, 13, 1)) +
        " --method known --grasp around --size 64x48 --out " +
        visgrab::test::shellQuoted(tmp_.path() / "r.png"));
  };
  // Another database at the recorded path (here: another recorded hash).
  std::string replaced = original;
  replaced.replace(replaced.find(hash), hash.size(), "0123456789abcdef");
  writeFile(runFile, replaced);
  auto r = render();
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("the database at " + options_.database.string() +
                          " is not the one the run used: its index hash is " + hash +
                          ", the run recorded 0123456789abcdef"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(tmp_.path() / "r.png"));
  options_.resume = true;
  try {
    visgrab::runner::runBenchmark(options_);
    FAIL() << "a folder of another database's trials resumed";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(options_.out.string()), std::string::npos) << m;
    EXPECT_NE(m.find("0123456789abcdef"), std::string::npos) << m;
    EXPECT_NE(m.find("generated again or replaced"), std::string::npos) << m;
  }
  // The database moved away from the recorded path.
  std::string moved = original;
  const std::string gone = (tmp_.path() / "moved-away").string();
  moved.replace(moved.find("\ndatabase,") + 10, options_.database.string().size(), gone);
  writeFile(runFile, moved);
  r = render();
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("the database " + gone + " cannot be read (moved or deleted"),
            std::string::npos)
      << r.output;
  // The run's own database, unchanged: the picture is drawn.
  writeFile(runFile, original);
  r = render();
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(fs::exists(tmp_.path() / "r.png"));
}

TEST_F(EngineRun, TheCommandLineRefusesAnUnknownEngine) {
  const std::string args = "run --db " + visgrab::test::shellQuoted(options_.database) +
                           " --grasps " + visgrab::test::shellQuoted(options_.grasps[0]) +
                           " --out " + visgrab::test::shellQuoted(options_.out) + " --quiet";
  const auto bad = visgrab::test::runVisgrab(args + " --engine bullet");
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("--engine: unknown engine 'bullet' (expected one of ode, mujoco)"),
            std::string::npos)
      << bad.output;
  EXPECT_FALSE(fs::exists(options_.out / "trials.csv"));
  if (!rwsim::engines::isAvailable("mujoco")) {
    const auto absent = visgrab::test::runVisgrab(args + " --engine mujoco");
    EXPECT_EQ(absent.exitCode, 2) << absent.output;
    EXPECT_NE(absent.output.find("libmujoco-dev"), std::string::npos) << absent.output;
  }
}

// `visgrab run --engine mujoco` on every scene of the shared 20-scene test database: over each
// object (from the ground truth) a top-down SDH_CYL grasp and one 0.25 m beside it. Every trial
// must end with an outcome of the table, none a simulation failure or a timeout (either would be
// the MuJoCo adapter's: ODE runs the same grasps without one); the run records its engine; some
// grasps are held and the ones beside the objects close on nothing.
TEST(EngineRunMujoco, EveryTestDatabaseSceneRunsToAnOutcome) {
  if (!rwsim::engines::isAvailable("mujoco")) {
    GTEST_SKIP() << "this build has no MuJoCo engine (Debian's libmujoco-dev was not found at "
                    "configure time)";
  }
  const auto& database = visgrab::test::testDatabase();
  std::vector<GraspRequest> grasps;
  for (const auto& scene : visgrab::test::testDatabaseScenes()) {
    const std::string id = db::sceneIdOf(scene);
    for (const auto& pose : database.groundTruth(id)) {
      const Vector3D at = pose.X_WO.translation();
      for (const auto& [name, offset] : {std::pair{"over", Vector3D(0, 0, 0.07)},
                                         std::pair{"beside", Vector3D(0, 0.25, 0.07)}}) {
        GraspRequest r;
        r.sceneId = id;
        r.id = std::string(name) + "-" + std::to_string(pose.object);
        r.method = "known";
        r.kind = GraspKind::kPreshape;
        r.preshape = "SDH_CYL";
        r.X_W_tcp = rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0), at + offset);
        grasps.push_back(r);
      }
    }
  }
  visgrab::test::TempDir tmp;
  visgrab::taskio::writeGraspList(grasps, tmp.path() / "grasps.txt");
  const fs::path out = tmp.path() / "results";
  const auto run = visgrab::test::runVisgrab(
      "run --db " + visgrab::test::shellQuoted(database.root()) + " --grasps " +
      visgrab::test::shellQuoted(tmp.path() / "grasps.txt") + " --out " +
      visgrab::test::shellQuoted(out) + " --hand " +
      visgrab::test::shellQuoted(visgrab::test::sourceDir() / "scenes/hands/sdh/sdh.grasp.xml") +
      " --engine mujoco --threads 2 --quiet");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const auto results = visgrab::results::readResults(out);
  EXPECT_EQ(results.sources.engine, "mujoco");
  EXPECT_EQ(results.sources.engineSettings.rfind("MuJoCo ", 0), 0u)
      << results.sources.engineSettings;
  ASSERT_EQ(results.trials.size(), grasps.size());
  int simulated = 0;
  int held = 0;
  int besideMissed = 0;
  int beside = 0;
  int capped = 0;
  for (const auto& t : results.trials) {
    using rwsim::trial::GraspOutcome;
    EXPECT_NE(t.outcome, GraspOutcome::kSimulationFailure)
        << t.sceneId << " " << t.graspId << ": " << t.detail;
    EXPECT_NE(t.outcome, GraspOutcome::kTimeout) << t.sceneId << " " << t.graspId;
    if (rwsim::trial::isDecidedBeforeSimulation(t.outcome)) continue;
    ++simulated;
    held += rwsim::trial::isHeld(t.outcome) ? 1 : 0;
    capped += t.closingCapped ? 1 : 0;
    if (t.graspId.starts_with("beside")) {
      ++beside;
      besideMissed += t.outcome == GraspOutcome::kMissed ? 1 : 0;
    }
  }
  // 20 scenes, 30 objects: most grasps are simulated (some over lying objects collide).
  EXPECT_GE(simulated, 30) << "of " << results.trials.size();
  EXPECT_GE(held, 5);
  EXPECT_GE(beside, 10);
  EXPECT_GE(besideMissed * 10, beside * 8) << besideMissed << " of " << beside;
  // The fingers come to rest on what they grasp. (These hand-made grasps did not hit the cap
  // without the motors' armature either; MujocoEngine.AFingerPressedOnABlockComesToRest is the
  // test that fails without it.)
  EXPECT_LE(capped * 10, simulated) << capped << " capped closings of " << simulated;
  std::printf("%d of %d simulated trials held, %d closings capped\n", held, simulated, capped);
}

// --- The trial protocol's record --------------------------------------------------------------

TEST_F(EngineRun, TheLiftLeavesNoProtocolRecordAndAnotherProtocolIsRecordedAndChecked) {
  // The default and --protocol lift: no record (run.csv as before protocols existed).
  visgrab::runner::runBenchmark(options_);
  const std::string plain = readFile(options_.out / "run.csv");
  EXPECT_EQ(plain.find("protocol"), std::string::npos) << plain;
  const std::string plainTrials = readFile(options_.out / "trials.csv");
  auto lift = options_;
  lift.out = tmp_.path() / "lift";
  lift.protocol = visgrab::test::sourceDir() / "scenes/protocols/lift.xml";
  visgrab::runner::runBenchmark(lift);
  EXPECT_EQ(readFile(lift.out / "run.csv"), plain);
  EXPECT_EQ(readFile(lift.out / "trials.csv"), plainTrials);

  // The shake: its name and hash (16 hex digits) in run.csv.
  auto shake = options_;
  shake.out = tmp_.path() / "shake";
  // Given through a detour (sub/../protos/shake.xml), the shake's file is recorded as the
  // plain path it names: tmp/protos/shake.xml.
  fs::create_directories(tmp_.path() / "sub");
  fs::create_directories(tmp_.path() / "protos");
  fs::copy_file(visgrab::test::sourceDir() / "scenes/protocols/shake.xml",
                tmp_.path() / "protos/shake.xml");
  shake.protocol = tmp_.path() / "sub/../protos/shake.xml";
  visgrab::runner::runBenchmark(shake);
  const auto run = visgrab::results::readResults(shake.out);
  EXPECT_EQ(run.sources.protocol, "shake");
  EXPECT_EQ(run.sources.protocolHash.size(), 16u);
  const std::string text = readFile(shake.out / "run.csv");
  EXPECT_NE(text.find("\nprotocol,shake,,,,,,\n"), std::string::npos) << text;
  // And the file it was given, absolute (the replays fall back on it).
  EXPECT_TRUE(run.sources.protocolFile.is_absolute()) << run.sources.protocolFile;
  EXPECT_EQ(run.sources.protocolFile.string(), tmp_.path().string() + "/protos/shake.xml");
  EXPECT_NE(text.find("\nprotocol_file," + run.sources.protocolFile.string() + ",,,,,,\n"),
            std::string::npos)
      << text;

  // Resuming the shake's folder with the lift (or the lift's with the shake) is refused.
  for (auto [dir, protocol] :
       {std::pair{shake.out, fs::path()}, std::pair{lift.out, shake.protocol}}) {
    auto resume = options_;
    resume.out = dir;
    resume.protocol = protocol;
    resume.resume = true;
    try {
      visgrab::runner::runBenchmark(resume);
      ADD_FAILURE() << dir << " was resumed with another protocol";
    } catch (const std::runtime_error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(dir.string()), std::string::npos) << m;
      EXPECT_NE(m.find("protocol 'shake'"), std::string::npos) << m;
      EXPECT_NE(m.find("the lift protocol"), std::string::npos) << m;
    }
  }
}

}  // namespace
