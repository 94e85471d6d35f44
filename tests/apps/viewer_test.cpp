// `visgrab-viewer` under Xvfb on the shared test database: a scene and a replayed grasp saved with
// --screenshot (a real picture with the objects in the middle), replays of runs made with another
// protocol than the lift, and the command-line mistakes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_set>

#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/render/png_io.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/taskio/grasp_list.hpp"
#include "visgrab/view/cameras.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::test::RunResult;
using visgrab::test::shellQuoted;

// A standing red can on the plain table: it stands out from the table and the background.
constexpr const char* kScene = "plain/single/cocacola/01";
constexpr int kWidth = 640;
constexpr int kHeight = 480;

RunResult viewer(const std::string& args) {
  return visgrab::test::runProgram(VISGRAB_VIEWER_BINARY, args);
}

// xvfb-run on the PATH, if any.
std::optional<fs::path> xvfbRun() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && fs::exists(fs::path(dir) / "xvfb-run")) return fs::path(dir) / "xvfb-run";
  }
  return std::nullopt;
}

// The viewer with `args` on a virtual X screen of its own. Test processes that run side by side
// start their search for a free display number at different places (xvfb-run -a can race), and
// a server that failed to start is tried once more.
RunResult viewerUnderXvfb(const fs::path& xvfb, const std::string& args) {
  RunResult r;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int display = 100 + static_cast<int>(getpid() % 500) * 2 + attempt * 1000;
    r = visgrab::test::runProgram(xvfb, "-a -n " + std::to_string(display) +
                                            " -s '-screen 0 1280x1024x24' " +
                                            shellQuoted(VISGRAB_VIEWER_BINARY) + " " + args);
    if (r.output.find("Xvfb failed to start") == std::string::npos) break;
  }
  return r;
}

#define REQUIRE_XVFB(var)                                               \
  const auto var##_opt = xvfbRun();                                     \
  if (!var##_opt)                                                       \
    GTEST_SKIP() << "xvfb-run is not installed: the viewer needs an X " \
                    "display (Debian package xvfb)";                    \
  const fs::path& var = *var##_opt

std::string viewerArgs(const fs::path& shot, const std::string& more) {
  return "--db " + shellQuoted(visgrab::test::testDatabasePath()) + " --scene " + kScene +
         " --screenshot " + shellQuoted(shot) + " --size " + std::to_string(kWidth) + "x" +
         std::to_string(kHeight) + " " + more;
}

using Rgb = Eigen::Vector3d;

Rgb pixel(const visgrab::visual::RgbImage& image, int x, int y) {
  const auto* p = &image.pixels[3 * (static_cast<std::size_t>(y) * image.width + x)];
  return Rgb(p[0], p[1], p[2]);
}

// Mean colour of the w x h block at (x, y).
Rgb meanColour(const visgrab::visual::RgbImage& image, int x, int y, int w, int h) {
  Rgb sum = Rgb::Zero();
  for (int j = y; j < y + h; ++j) {
    for (int i = x; i < x + w; ++i) sum += pixel(image, i, j);
  }
  return sum / (w * h);
}

// The pictures' background colour as the renderer writes it (sRGB of view::studioBackground).
Rgb backgroundColour() {
  const Eigen::Vector3f linear = visgrab::view::studioBackground();
  Rgb rgb;
  for (int c = 0; c < 3; ++c) {
    const double v = linear[c];
    rgb[c] = 255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055);
  }
  return rgb;
}

// The screenshot is a real picture: many colours, most pixels not the cleared background.
void expectNotBlank(const visgrab::visual::RgbImage& image) {
  std::unordered_set<std::uint32_t> colours;
  const Rgb background = backgroundColour();
  std::size_t drawn = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Rgb p = pixel(image, x, y);
      colours.insert(static_cast<std::uint32_t>(p[0]) << 16 |
                     static_cast<std::uint32_t>(p[1]) << 8 | static_cast<std::uint32_t>(p[2]));
      if ((p - background).cwiseAbs().maxCoeff() > 4.0) ++drawn;
    }
  }
  const double total = static_cast<double>(image.width) * image.height;
  EXPECT_GT(colours.size(), 500u);
  EXPECT_GT(static_cast<double>(drawn) / total, 0.25) << "mostly background";
}

visgrab::visual::RgbImage readShot(const fs::path& shot) {
  EXPECT_TRUE(fs::is_regular_file(shot)) << shot;
  const auto image = visgrab::render::readPng(shot);
  // The view's size times the device pixel ratio (1 under Xvfb; any whole ratio is fine).
  EXPECT_EQ(image.width % kWidth, 0) << image.width;
  EXPECT_EQ(image.width / kWidth, image.height / kHeight) << image.width << "x" << image.height;
  EXPECT_EQ(image.height % kHeight, 0) << image.height;
  return image;
}

TEST(ViewerApp, SavesAScreenshotOfASceneWithTheObjectsInTheMiddle) {
  REQUIRE_XVFB(xvfb);
  visgrab::test::TempDir dir;
  const fs::path shot = dir.path() / "shot.png";
  const RunResult r = viewerUnderXvfb(xvfb, viewerArgs(shot, ""));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto image = readShot(shot);
  ASSERT_GE(image.width, kWidth);
  expectNotBlank(image);
  // The can is framed in the middle: the central block is neither the background nor the table
  // seen in the corners.
  const int w = image.width / 10;
  const int h = image.height / 10;
  const Rgb middle = meanColour(image, (image.width - w) / 2, (image.height - h) / 2, w, h);
  EXPECT_GT((middle - backgroundColour()).norm(), 40.0) << middle.transpose();
  for (const auto& [x, y] :
       {std::pair{0, 0}, std::pair{image.width - w, 0}, std::pair{0, image.height - h},
        std::pair{image.width - w, image.height - h}}) {
    const Rgb corner = meanColour(image, x, y, w, h);
    EXPECT_GT((middle - corner).norm(), 40.0)
        << "middle " << middle.transpose() << " corner " << corner.transpose();
  }
}

TEST(ViewerApp, ReplaysAGraspAndSavesTheMomentAfterLifting) {
  REQUIRE_XVFB(xvfb);
  visgrab::test::TempDir dir;
  // The SDH's cylinder pre-shape pointing down (RPY 0 180 0: quaternion w x y z = 0 0 1 0), its
  // TCP 6 cm above the can's base (the can is about 12 cm high), from the ground truth.
  const auto& truth = visgrab::test::testDatabase().groundTruth(kScene);
  ASSERT_EQ(truth.size(), 1u);
  const rw::math::Vector3D tcp = truth[0].X_WO.translation() + rw::math::Vector3D(0, 0, 0.06);
  std::ostringstream line;
  line.precision(17);
  line << kScene << ", viewer_test, g1, preshape, " << tcp.x() << "," << tcp.y() << "," << tcp.z()
       << ", 0,0,1,0, SDH_CYL\n";
  const fs::path grasps = visgrab::test::writeFile(dir.path() / "grasps.csv", line.str());
  const fs::path shot = dir.path() / "grasp.png";
  const RunResult r =
      viewerUnderXvfb(xvfb, viewerArgs(shot, "--grasps " + shellQuoted(grasps) + " --grasp 1"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // The trial was replayed (the grasp holds the can).
  EXPECT_NE(r.output.find("grasp 1: stable"), std::string::npos) << r.output;
  const auto image = readShot(shot);
  ASSERT_GE(image.width, kWidth);
  expectNotBlank(image);
}

// --- Runs made with another protocol than the lift -----------------------------------------------

// Two runs of one grasp on the can (SDH_CYL pointing down, its TCP 6 cm above the can's base):
// one with the project's shake, one with a protocol file outside the data folder ("myshake": the
// shake 3 cm instead of 2), moved elsewhere after the run (so run.csv's protocol_file is gone).
class ViewerProtocol : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new visgrab::test::TempDir;
    const rw::math::Vector3D base =
        visgrab::test::testDatabase().groundTruth(kScene).front().X_WO.translation();
    visgrab::grasp::GraspRequest g;
    g.sceneId = kScene;
    g.id = "g1";
    g.method = "viewer_test";
    g.kind = visgrab::grasp::GraspKind::kPreshape;
    g.preshape = "SDH_CYL";
    g.X_W_tcp = rw::math::rpyTransform(rw::math::Vector3D(0.0, std::numbers::pi, 0.0),
                                       base + rw::math::Vector3D(0, 0, 0.06));
    visgrab::taskio::writeGraspList({g}, path("grasps.txt"));
    const fs::path shake = visgrab::test::sourceDir() / "scenes/protocols/shake.xml";
    std::ifstream in(shake, std::ios::binary);
    std::string text(std::istreambuf_iterator<char>(in), {});
    for (const auto& [from, to] : {std::pair{"name=\"shake\"", "name=\"myshake\""},
                                   std::pair{"amplitude=\"0.02\"", "amplitude=\"0.03\""}}) {
      text.replace(text.find(from), std::string(from).size(), to);
    }
    visgrab::test::writeFile(path("mine/myshake.xml"), text);
    for (const auto& [out, protocol] :
         {std::pair{"shake", shake}, std::pair{"custom", path("mine/myshake.xml")}}) {
      visgrab::runner::RunOptions options;
      options.database = visgrab::test::testDatabase().root();
      options.grasps = {path("grasps.txt")};
      options.out = path(out);
      options.hand = visgrab::test::sourceDir() / "scenes/hands/sdh/sdh.grasp.xml";
      options.protocol = protocol;
      visgrab::runner::runBenchmark(options);
    }
    fs::create_directories(path("elsewhere"));
    fs::rename(path("mine/myshake.xml"), path("elsewhere/myshake.xml"));
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static fs::path path(const std::string& name) { return dir_->path() / name; }
  // The viewer's arguments for grasp 1 of `run`, with a screenshot `shot`.
  static std::string replayArgs(const std::string& run, const std::string& more,
                                const std::string& shot) {
    return "--results " + shellQuoted(path(run)) + " --scene " + kScene + " --grasp 1 --size " +
           std::to_string(kWidth) + "x" + std::to_string(kHeight) + " --screenshot " +
           shellQuoted(path(shot)) + " " + more;
  }
  // trials.csv's outcome of the run's grasp.
  static std::string outcomeOf(const std::string& run) {
    const auto trials = visgrab::results::readResults(path(run)).trials;
    EXPECT_EQ(trials.size(), 1u);
    return trials.empty() ? std::string()
                          : std::string(rwsim::trial::outcomeName(trials[0].outcome));
  }

  static visgrab::test::TempDir* dir_;
};

visgrab::test::TempDir* ViewerProtocol::dir_ = nullptr;

// The shake run's grasp replays with the data folder's shake: its outcome and simulated time are
// trials.csv's (else the viewer says "the results say ...").
TEST_F(ViewerProtocol, ReplaysARunWithTheRunsProtocol) {
  REQUIRE_XVFB(xvfb);
  const RunResult r = viewerUnderXvfb(xvfb, replayArgs("shake", "", "shake.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("grasp 1: " + outcomeOf("shake")), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("the results say"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("not replayed"), std::string::npos) << r.output;
  expectNotBlank(readShot(path("shake.png")));

  // A run made with a protocol file of its own, since moved, replays with the file given.
  const RunResult custom = viewerUnderXvfb(
      xvfb, replayArgs("custom", "--protocol " + shellQuoted(path("elsewhere/myshake.xml")),
                       "custom.png"));
  ASSERT_EQ(custom.exitCode, 0) << custom.output;
  EXPECT_NE(custom.output.find("grasp 1: " + outcomeOf("custom")), std::string::npos)
      << custom.output;
  EXPECT_EQ(custom.output.find("the results say"), std::string::npos) << custom.output;
}

// Without the run's protocol nothing is replayed: --grasp is refused before any window opens
// (exit 1, naming the protocol and asking for its file), and so is a --protocol of another hash.
TEST_F(ViewerProtocol, RefusesToReplayWithoutTheRunsProtocol) {
  const RunResult missing = viewer(replayArgs("custom", "", "refused.png"));
  EXPECT_EQ(missing.exitCode, 1) << missing.output;
  EXPECT_NE(missing.output.find("cannot replay --grasp 1: the run's trials ran the protocol "
                                "\"myshake\""),
            std::string::npos)
      << missing.output;
  EXPECT_NE(missing.output.find("pass --protocol FILE"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(path("refused.png")));

  const RunResult other = viewer(replayArgs("shake", "--protocol lift", "refused.png"));
  EXPECT_EQ(other.exitCode, 1) << other.output;
  EXPECT_NE(other.output.find("lift.xml: the protocol \"lift\" has hash"), std::string::npos)
      << other.output;
  EXPECT_NE(other.output.find("the run's trials ran the protocol \"shake\""), std::string::npos)
      << other.output;
  EXPECT_FALSE(fs::exists(path("refused.png")));

  const RunResult unknown = viewer(replayArgs("shake", "--protocol hop", "refused.png"));
  EXPECT_EQ(unknown.exitCode, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--protocol: unknown protocol \"hop\""), std::string::npos)
      << unknown.output;
}

TEST(ViewerApp, CommandLineMistakesExitWith2AndNameTheOption) {
  // Checked before any window opens: no display needed.
  const RunResult unknown = viewer("--db somewhere --bogus-option 3");
  EXPECT_EQ(unknown.exitCode, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--bogus-option"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("usage: visgrab-viewer"), std::string::npos) << unknown.output;

  const RunResult size = viewer("--size 640by480");
  EXPECT_EQ(size.exitCode, 2) << size.output;
  EXPECT_NE(size.output.find("--size"), std::string::npos) << size.output;
  EXPECT_NE(size.output.find("640by480"), std::string::npos) << size.output;

  const RunResult missing = viewer("--scene " + std::string(kScene) + " --grasp");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("--grasp: expected"), std::string::npos) << missing.output;

  const RunResult help = viewer("--help");
  EXPECT_EQ(help.exitCode, 0) << help.output;
  EXPECT_NE(help.output.find("--screenshot"), std::string::npos) << help.output;
}

TEST(ViewerApp, UnreadableInputExitsWith1) {
  visgrab::test::TempDir dir;
  const RunResult noDb = viewer("--db " + shellQuoted(dir.path() / "nothing") + " --screenshot " +
                                shellQuoted(dir.path() / "x.png"));
  EXPECT_EQ(noDb.exitCode, 1) << noDb.output;
  EXPECT_NE(noDb.output.find("nothing"), std::string::npos) << noDb.output;
  EXPECT_FALSE(fs::exists(dir.path() / "x.png"));

  // An unknown scene is found out before any window opens; the message suggests the real one.
  const RunResult unknown =
      viewer("--db " + shellQuoted(visgrab::test::testDatabasePath()) +
             " --scene plain/single/cocacola/09 --screenshot " + shellQuoted(dir.path() / "x.png"));
  EXPECT_EQ(unknown.exitCode, 1) << unknown.output;
  EXPECT_NE(unknown.output.find(kScene), std::string::npos) << unknown.output;
}

}  // namespace
