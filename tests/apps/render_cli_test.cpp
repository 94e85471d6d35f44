// `visgrab render` on a scene of the shared test database: the scene alone, a grasp's three
// moments taken from a run's results (which record the database, grasps and hand), the montage,
// the overlay on the left image, and the command-line mistakes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "rwsim/trial/trial_protocol.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#include "visgrab/render/png_io.hpp"
#include "visgrab/results/results_file.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::test::RunResult;
using visgrab::test::runVisgrab;
using visgrab::test::shellQuoted;

constexpr const char* kScene = "plain/single/cocacola/01";

std::string db() { return shellQuoted(visgrab::test::testDatabasePath()); }

// A results folder of two grasps on the can, from two grasp files: SDH_CYL pointing down (RPY 0
// 180 0, quaternion 0 0 1 0) around its middle (stable) and with the palm 2 cm above the table
// (in collision).
class RenderCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new visgrab::test::TempDir;
    const auto base = visgrab::test::testDatabase().groundTruth(kScene).front().X_WO.translation();
    // One grasp per file, both given to `visgrab run` (--grasps repeated).
    char good[256], through[256];
    std::snprintf(good, sizeof good,
                  "%s, known, good, preshape, %.6f,%.6f,%.6f, 0,0,1,0, SDH_CYL\n", kScene, base.x(),
                  base.y(), base.z() + 0.06);
    std::snprintf(through, sizeof through,
                  "%s, known, through, preshape, %.6f,%.6f,%.6f, 0,0,1,0, SDH_CYL\n", kScene,
                  base.x(), base.y(), base.z() + 0.02);
    visgrab::test::writeFile(dir_->path() / "good.csv", good);
    visgrab::test::writeFile(dir_->path() / "through.csv", through);
    const RunResult r =
        runVisgrab("run --db " + db() + " --grasps " + shellQuoted(dir_->path() / "good.csv") +
                   " --grasps " + shellQuoted(dir_->path() / "through.csv") + " --out " +
                   shellQuoted(dir_->path() / "results") + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static fs::path path(const std::string& name) { return dir_->path() / name; }
  static std::string results() { return " --results " + shellQuoted(dir_->path() / "results"); }

  static visgrab::test::TempDir* dir_;
};

visgrab::test::TempDir* RenderCli::dir_ = nullptr;

TEST_F(RenderCli, SceneAloneIsFramedOnTheObjects) {
  const RunResult r = runVisgrab("render --db " + db() + " --scene " + kScene + " --out " +
                                 shellQuoted(path("scene.png")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto image = visgrab::render::readPng(path("scene.png"));
  ASSERT_EQ(image.width, 800);
  ASSERT_EQ(image.height, 600);
  // The can fills the middle: the centre pixels are neither the background (top-left corner)
  // nor all one colour.
  auto px = [&](int row, int col) {
    const std::size_t i = 3 * (static_cast<std::size_t>(row) * 800 + col);
    return std::array<int, 3>{image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
  };
  EXPECT_NE(px(300, 400), px(2, 2));
  int differing = 0;
  for (int row = 250; row < 350; ++row) {
    for (int col = 350; col < 450; ++col) differing += px(row, col) != px(300, 400) ? 1 : 0;
  }
  EXPECT_GT(differing, 1000);
}

TEST_F(RenderCli, GraspStripFromTheRunsResults) {
  RunResult r = runVisgrab("render" + results() + " --scene " + kScene +
                           " --grasp good --size 240x180 --out " + shellQuoted(path("good.png")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("stable"), std::string::npos) << r.output;
  auto image = visgrab::render::readPng(path("good.png"));
  EXPECT_EQ(image.width, 3 * (240 + 2));
  EXPECT_EQ(image.height, 36 + 180 + 30 + 2);
  // The second grasp by number: in collision, one panel.
  r = runVisgrab("render" + results() + " --scene " + kScene + " --grasp 2 --size 240x180 --out " +
                 shellQuoted(path("through.png")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("in_collision"), std::string::npos) << r.output;
  image = visgrab::render::readPng(path("through.png"));
  EXPECT_EQ(image.width, 240 + 2);
}

TEST_F(RenderCli, MontageAndOverlay) {
  RunResult r =
      runVisgrab("render" + results() + " --scene " + kScene +
                 " --montage --size 160x120 --columns 3 --out " + shellQuoted(path("montage.png")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("2 grasps"), std::string::npos) << r.output;
  auto image = visgrab::render::readPng(path("montage.png"));
  EXPECT_EQ(image.width, 3 * (160 + 2));
  EXPECT_EQ(image.height, 36 + (120 + 30 + 2) + 30);

  r = runVisgrab("render" + results() + " --scene " + kScene + " --grasp good --overlay --out " +
                 shellQuoted(path("overlay.png")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  image = visgrab::render::readPng(path("overlay.png"));
  const auto left =
      visgrab::render::readImage(visgrab::test::testDatabase().scene(kScene).leftImage);
  ASSERT_EQ(image.width, left.width);
  ASSERT_EQ(image.height, left.height + 36);
  // The hand is drawn over the image: many pixels below the title differ from the left image.
  int changed = 0;
  for (int row = 0; row < left.height; ++row) {
    for (int col = 0; col < left.width; ++col) {
      const std::size_t a = 3 * (static_cast<std::size_t>(row) * left.width + col);
      const std::size_t b = 3 * (static_cast<std::size_t>(row + 36) * left.width + col);
      int d = 0;
      for (int k = 0; k < 3; ++k) d += std::abs(left.pixels[a + k] - image.pixels[b + k]);
      changed += d > 30 ? 1 : 0;
    }
  }
  EXPECT_GT(changed, 2000);
  EXPECT_LT(changed, left.width * left.height / 2);
}

// The report's pictures of a run over two scenes (one per table): each scene is drawn with a
// renderer of its own, and every showcase gets its picture.
TEST_F(RenderCli, ReportPicturesOfSeveralScenes) {
  std::string plan;
  for (const char* scene : {"plain/single/cocacola/01", "textured/single/cocacola/01"}) {
    const auto base = visgrab::test::testDatabase().groundTruth(scene).front().X_WO.translation();
    char line[256];
    std::snprintf(line, sizeof line,
                  "%s, known, good, preshape, %.6f,%.6f,%.6f, 0,0,1,0, SDH_CYL\n", scene, base.x(),
                  base.y(), base.z() + 0.06);
    plan += line;
  }
  visgrab::test::writeFile(path("two.csv"), plan);
  RunResult r = runVisgrab("run --db " + db() + " --grasps " + shellQuoted(path("two.csv")) +
                           " --out " + shellQuoted(path("two")) + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runVisgrab("analyze " + shellQuoted(path("two")) + " --out " +
                 shellQuoted(path("two-report")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("not drawn"), std::string::npos) << r.output;
  // Both held grasps are their group's best: one picture per table.
  for (const char* table : {"plain", "textured"}) {
    const fs::path image =
        path("two-report") / "images" / (std::string("column1-") + table + "-single-all-best.png");
    ASSERT_TRUE(fs::exists(image)) << image;
    EXPECT_GT(visgrab::render::readPng(image).width, 100);
  }
}

// `--grasp N` is the scene's N-th row of trials.csv. The grasp file names the method "first" in
// another scene before "second" and "first" in this one: the run writes this scene's trials
// "first" then "second" (methods as first seen over the run); counting the methods within the
// scene alone would put "second" first.
TEST_F(RenderCli, GraspNIsTheScenesNthRowOfTrialsCsv) {
  std::string plan;
  const auto line = [&](const char* scene, const char* method, const char* id, double above) {
    const auto base = visgrab::test::testDatabase().groundTruth(scene).front().X_WO.translation();
    char text[256];
    std::snprintf(text, sizeof text, "%s, %s, %s, preshape, %.6f,%.6f,%.6f, 0,0,1,0, SDH_CYL\n",
                  scene, method, id, base.x(), base.y(), base.z() + above);
    plan += text;
  };
  line("textured/single/cocacola/01", "first", "elsewhere", 0.06);
  line(kScene, "second", "through", 0.02);
  line(kScene, "first", "good", 0.06);
  visgrab::test::writeFile(path("mixed.csv"), plan);
  RunResult r = runVisgrab("run --db " + db() + " --grasps " + shellQuoted(path("mixed.csv")) +
                           " --out " + shellQuoted(path("mixed")) + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::vector<visgrab::results::TrialRecord> rows;
  for (const auto& t : visgrab::results::readResults(path("mixed")).trials) {
    if (t.sceneId == kScene) rows.push_back(t);
  }
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].graspId, "good");
  ASSERT_NE(rows[0].outcome, rows[1].outcome);
  for (const std::string& inputs : {" --db " + db() + " --grasps " + shellQuoted(path("mixed.csv")),
                                    " --results " + shellQuoted(path("mixed"))}) {
    for (std::size_t n = 1; n <= rows.size(); ++n) {
      SCOPED_TRACE(inputs + " --grasp " + std::to_string(n));
      r = runVisgrab("render" + inputs + " --scene " + kScene + " --grasp " + std::to_string(n) +
                     " --size 120x90 --out " + shellQuoted(path("mixed.png")));
      ASSERT_EQ(r.exitCode, 0) << r.output;
      const std::string outcome(rwsim::trial::outcomeName(rows[n - 1].outcome));
      EXPECT_NE(r.output.find(", " + outcome + ", hand"), std::string::npos) << r.output;
    }
  }
}

// --- Runs made with another protocol than the lift ---------------------------------------------

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// `text` with its first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Three runs of the can's two grasps (render's "good" and "through"): one with the project's
// shake (--protocol shake); two with a protocol file of their own outside the data folder
// ("myshake": the shake 3 cm instead of 2), "custom" whose file stays where it was and "moved"
// whose file is moved away after the run; and a fourth protocol file, the shake with one value
// changed.
class RenderProtocolCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new visgrab::test::TempDir;
    const auto base = visgrab::test::testDatabase().groundTruth(kScene).front().X_WO.translation();
    std::string plan;
    for (const auto& [id, above] : {std::pair{"good", 0.06}, std::pair{"high", 0.10}}) {
      char line[256];
      std::snprintf(line, sizeof line,
                    "%s, known, %s, preshape, %.6f,%.6f,%.6f, 0,0,1,0, SDH_CYL\n", kScene, id,
                    base.x(), base.y(), base.z() + above);
      plan += line;
    }
    visgrab::test::writeFile(path("grasps.csv"), plan);
    const std::string shake = readText(visgrab::test::sourceDir() / "scenes/protocols/shake.xml");
    visgrab::test::writeFile(path("mine/myshake.xml"),
                             replaced(replaced(shake, "name=\"shake\"", "name=\"myshake\""),
                                      "amplitude=\"0.02\"", "amplitude=\"0.03\""));
    visgrab::test::writeFile(path("changed.xml"), replaced(shake, "cycles=\"2\"", "cycles=\"3\""));
    fs::copy_file(path("mine/myshake.xml"), path("mine/moved.xml"));
    for (const auto& [out, protocol] : {std::pair{"shake", std::string("shake")},
                                        std::pair{"custom", shellQuoted(path("mine/myshake.xml"))},
                                        std::pair{"moved", shellQuoted(path("mine/moved.xml"))}}) {
      const RunResult r =
          runVisgrab("run --db " + db() + " --grasps " + shellQuoted(path("grasps.csv")) +
                     " --protocol " + protocol + " --out " + shellQuoted(path(out)) + " --quiet");
      ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    fs::create_directories(path("elsewhere"));
    fs::rename(path("mine/moved.xml"), path("elsewhere/moved.xml"));
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static fs::path path(const std::string& name) { return dir_->path() / name; }
  static std::string results(const std::string& run) {
    return " --results " + shellQuoted(path(run));
  }
  static std::string hashOf(const fs::path& protocol) {
    return rwsim::trial::protocolHash(rwsim::trial::loadTrialProtocol(protocol));
  }
  // trials.csv's outcome of grasp `id` of `run`.
  static std::string outcomeOf(const std::string& run, const std::string& id) {
    for (const auto& t : visgrab::results::readResults(path(run)).trials) {
      if (t.graspId == id) return std::string(rwsim::trial::outcomeName(t.outcome));
    }
    ADD_FAILURE() << "no grasp " << id << " in " << run;
    return {};
  }
  // Renders `grasp` of `run` with `more` options; the picture is `out`.
  static RunResult render(const std::string& run, const std::string& grasp, const std::string& more,
                          const std::string& out) {
    return runVisgrab("render" + results(run) + " --scene " + kScene + " --grasp " + grasp +
                      " --size 120x90 " + more + " --out " + shellQuoted(path(out)));
  }

  static visgrab::test::TempDir* dir_;
};

visgrab::test::TempDir* RenderProtocolCli::dir_ = nullptr;

// The shake run's grasps replay with the data folder's shake: the replay ends as trials.csv says
// (its outcome in the closing line; a replay that differed in outcome or simulated time would say
// "replayed as ... but the results say ...").
TEST_F(RenderProtocolCli, AShakeRunReplaysWithTheShake) {
  const auto run = visgrab::results::readResults(path("shake"));
  ASSERT_EQ(run.sources.protocol, "shake");
  for (const std::string id : {"good", "high"}) {
    for (const std::string& given : {std::string(), std::string("--protocol shake")}) {
      SCOPED_TRACE(id + " " + given);
      const RunResult r = render("shake", id, given, "shake.png");
      ASSERT_EQ(r.exitCode, 0) << r.output;
      EXPECT_NE(r.output.find(", " + outcomeOf("shake", id) + ", hand"), std::string::npos)
          << r.output;
      EXPECT_EQ(r.output.find("replayed as"), std::string::npos) << r.output;
      EXPECT_GT(visgrab::render::readPng(path("shake.png")).width, 120);
    }
  }
  // The montage simulates nothing it has a record of, but replays with the shake all the same.
  const RunResult montage =
      runVisgrab("render" + results("shake") + " --scene " + kScene +
                 " --montage --size 120x90 --out " + shellQuoted(path("montage.png")));
  ASSERT_EQ(montage.exitCode, 0) << montage.output;
  EXPECT_NE(montage.output.find("2 grasps"), std::string::npos) << montage.output;
}

// A protocol file whose hash is not the run's is refused: exit 1, the file and both hashes
// named, no picture. So is the lift for a shake run, and the shake for a lift run.
TEST_F(RenderProtocolCli, AProtocolWithAnotherHashIsRefused) {
  const std::string shakeHash = hashOf(visgrab::test::sourceDir() / "scenes/protocols/shake.xml");
  struct Case {
    std::string run;
    std::string given;
    std::string givenHash;
    std::string runs;
  };
  const Case cases[] = {
      {"shake", path("changed.xml").string(), hashOf(path("changed.xml")),
       "the protocol \"shake\" (hash " + shakeHash + ")"},
      {"shake", "lift", hashOf(visgrab::test::sourceDir() / "scenes/protocols/lift.xml"),
       "the protocol \"shake\" (hash " + shakeHash + ")"},
      {"custom", "shake", shakeHash,
       "the protocol \"myshake\" (hash " + hashOf(path("mine/myshake.xml")) + ")"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.run + " --protocol " + c.given);
    fs::remove(path("refused.png"));
    const RunResult r = render(c.run, "good", "--protocol " + shellQuoted(c.given), "refused.png");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("cannot replay the trials of " + path(c.run).string()),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("has hash " + c.givenHash), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.runs), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("refused.png")));
  }
}

// A run made with a protocol file outside the data folder replays with the file it recorded
// (run.csv's protocol_file). Once that file is moved away: refused (naming the protocol, its hash
// and the missing file, asking for --protocol FILE), and replayed with the file given.
TEST_F(RenderProtocolCli, ACustomProtocolRunReplaysWithItsFile) {
  for (const std::string id : {"good", "high"}) {
    SCOPED_TRACE(id);
    const RunResult r = render("custom", id, "", "custom.png");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(", " + outcomeOf("custom", id) + ", hand"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("replayed as"), std::string::npos) << r.output;
  }

  const std::string hash = hashOf(path("elsewhere/moved.xml"));
  fs::remove(path("moved.png"));
  RunResult r = render("moved", "good", "", "moved.png");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("the protocol \"myshake\" (hash " + hash + "), which cannot be found"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("the run's protocol file " + path("mine/moved.xml").string() +
                          " does not exist"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("pass --protocol FILE"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("moved.png")));
  // The scene alone replays nothing: drawn.
  r = runVisgrab("render" + results("moved") + " --scene " + kScene + " --size 120x90 --out " +
                 shellQuoted(path("moved-scene.png")));
  EXPECT_EQ(r.exitCode, 0) << r.output;

  for (const std::string id : {"good", "high"}) {
    SCOPED_TRACE(id);
    r = render("moved", id, "--protocol " + shellQuoted(path("elsewhere/moved.xml")), "moved.png");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(", " + outcomeOf("moved", id) + ", hand"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("replayed as"), std::string::npos) << r.output;
  }
}

// The report draws the shake run's pictures with the data folder's shake and the custom run's
// with its file, and leaves out the pictures of the run whose file was moved, saying why.
TEST_F(RenderProtocolCli, ReportPicturesUseTheRunsProtocol) {
  for (const std::string run : {"shake", "custom"}) {
    SCOPED_TRACE(run);
    const RunResult r = runVisgrab("analyze " + shellQuoted(path(run)) + " --bootstrap 0 --out " +
                                   shellQuoted(path(run + "-report")));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("not drawn"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::is_empty(path(run + "-report") / "images"));
  }

  const RunResult r = runVisgrab("analyze " + shellQuoted(path("moved")) + " --bootstrap 0 --out " +
                                 shellQuoted(path("moved-report")));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("not drawn: the run's trials ran the protocol \"myshake\""),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("which cannot be found"), std::string::npos) << r.output;
}

TEST_F(RenderCli, MistakesAreUsageErrors) {
  const std::string out = " --out " + shellQuoted(path("x.png"));
  struct Case {
    std::string args;
    int exitCode;
    std::string message;
  };
  const Case cases[] = {
      {"render --db " + db() + out, 2, "--scene ID is required"},
      {"render --db " + db() + " --scene " + kScene, 2, "--out FILE.png is required"},
      {"render --db " + db() + " --scene " + kScene + " --out x.jpg", 2, "ending in .png"},
      {"render --db " + db() + " --scene " + kScene + " --size 10x" + out, 2, "--size"},
      {"render --db " + db() + " --scene " + kScene + " --view iso" + out, 2, "--view"},
      {"render --db " + db() + " --scene " + kScene + " --overlay" + out, 2, "--overlay needs"},
      {"render --db " + db() + " --scene " + kScene + " --grasp 1" + out, 2, "needs the grasps"},
      {"render" + results() + " --scene " + kScene + " --grasp 9" + out, 2, "out of range"},
      {"render" + results() + " --scene " + kScene + " --grasp bad" + out, 2, "no grasp 'bad'"},
      {"render" + results() + " --scene " + kScene + " --montage --grasp 1" + out, 2, "--montage"},
      {"render --db " + db() + " --scene plain/single/cocacola/09" + out, 1,
       "closest known ids: plain/single/cocacola/01"},
      {"render --db " + shellQuoted(path("nowhere")) + " --scene " + kScene + out, 1, "nowhere"},
  };
  for (const Case& c : cases) {
    const RunResult r = runVisgrab(c.args);
    EXPECT_EQ(r.exitCode, c.exitCode) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(path("x.png")));
}

}  // namespace
