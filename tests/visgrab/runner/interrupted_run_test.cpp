// `visgrab run` stopped mid-run by a full disk (a small tmpfs as root; a file-size limit for any
// user), a deleted result folder, an unreadable scene file and SIGTERM: it exits with its
// documented code and a message naming the file and the system's reason, trials.csv ends in a
// complete line, and --resume then gives the same trials.csv and run.csv, byte for byte, as an
// uninterrupted run.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rw/math/rpy.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

namespace fs = std::filesystem;
namespace db = visgrab::database;
using rw::math::Vector3D;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;

std::string fileBytes(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::size_t lineCount(const fs::path& f) {
  const std::string text = fileBytes(f);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

fs::path handFile() { return visgrab::test::sourceDir() / "scenes/hands/sdh/sdh.grasp.xml"; }

// Six SDH cylinder grasps around the object of each of five scenes of the shared test database
// (30 trials, a few seconds each).
std::vector<GraspRequest> grasps() {
  const std::vector<db::SceneConditions> scenes{
      db::SceneConditions::single(db::Texture::kPlain, 5, 1),
      db::SceneConditions::single(db::Texture::kPlain, 13, 1),
      db::SceneConditions::pairScene(db::Texture::kPlain, 'e', 1),
      db::SceneConditions::single(db::Texture::kTextured, 11, 2),
      db::SceneConditions::single(db::Texture::kPlain, 10, 3),
  };
  std::vector<GraspRequest> out;
  for (const auto& scene : scenes) {
    Vector3D base = Vector3D::Zero();
    for (const auto& pose : visgrab::test::testDatabase().groundTruth(db::sceneIdOf(scene))) {
      if (pose.object == scene.objects[0]) base = pose.X_WO.translation();
    }
    for (int k = 0; k < 6; ++k) {
      const double a = k * std::numbers::pi / 3.0;
      GraspRequest r;
      r.sceneId = db::sceneIdOf(scene);
      r.id = "g" + std::to_string(k);
      r.method = "known";
      r.kind = GraspKind::kPreshape;
      r.preshape = "SDH_CYL";
      r.X_W_tcp =
          rw::math::rpyTransform(Vector3D(0.0, std::numbers::pi, 0.0),
                                 base + Vector3D(0.03 * std::cos(a), 0.03 * std::sin(a), 0.06));
      out.push_back(r);
    }
  }
  return out;
}

// How a child run ended, and what it printed.
struct ChildRun {
  int status = 0;
  std::string output;
  bool exited() const { return WIFEXITED(status); }
  int code() const { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }
};

class InterruptedRun : public ::testing::Test {
 protected:
  // One uninterrupted run (one thread) for every test to compare with.
  static void SetUpTestSuite() {
    shared_ = std::make_unique<visgrab::test::TempDir>();
    visgrab::taskio::writeGraspList(grasps(), shared_->path() / "grasps.txt");
    const auto whole =
        visgrab::test::runVisgrab(commonArgs() + " --threads 1 --out " +
                                  visgrab::test::shellQuoted(shared_->path() / "whole"));
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
  }
  static void TearDownTestSuite() { shared_.reset(); }

  static fs::path wholeDir() { return shared_->path() / "whole"; }

  static std::string commonArgs() {
    return "run --db " + visgrab::test::shellQuoted(visgrab::test::testDatabase().root()) +
           " --grasps " + visgrab::test::shellQuoted(shared_->path() / "grasps.txt") + " --hand " +
           visgrab::test::shellQuoted(handFile()) + " --quiet";
  }

  // Starts `visgrab run` (two threads) into `out` with its output in `log`; `fileLimit` sets
  // RLIMIT_FSIZE with SIGXFSZ ignored, so that a write past it fails with EFBIG.
  static pid_t start(const fs::path& out, const fs::path& log,
                     std::optional<rlim_t> fileLimit = std::nullopt) {
    const std::vector<std::string> args{VISGRAB_BINARY,
                                        "run",
                                        "--db",
                                        visgrab::test::testDatabase().root().string(),
                                        "--grasps",
                                        (shared_->path() / "grasps.txt").string(),
                                        "--hand",
                                        handFile().string(),
                                        "--quiet",
                                        "--threads",
                                        "2",
                                        "--out",
                                        out.string()};
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const std::string logFile = log.string();
    const pid_t pid = fork();
    if (pid == 0) {
      const int fd = ::open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) {
        ::dup2(fd, STDOUT_FILENO);
        ::dup2(fd, STDERR_FILENO);
        ::close(fd);
      }
      if (fileLimit) {
        const rlimit limit{*fileLimit, *fileLimit};
        ::setrlimit(RLIMIT_FSIZE, &limit);
        ::signal(SIGXFSZ, SIG_IGN);
      }
      ::execv(VISGRAB_BINARY, argv.data());
      _exit(127);
    }
    return pid;
  }

  // Waits until `trials` holds the column line and `n` trials (true), or the child ended
  // (false; `status` set) or two minutes passed (false).
  static bool waitForTrials(pid_t pid, const fs::path& trials, std::size_t n, int& status) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
    while (std::chrono::steady_clock::now() < deadline) {
      if (lineCount(trials) >= 1 + n) return true;
      if (::waitpid(pid, &status, WNOHANG) == pid) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  static ChildRun finish(pid_t pid, const fs::path& log) {
    ChildRun r;
    ::waitpid(pid, &r.status, 0);
    r.output = fileBytes(log);
    return r;
  }

  // The stopped run's trials.csv ends in a complete line; --resume (one thread) completes it to
  // the uninterrupted run's bytes.
  static void expectResumesToTheWholeRun(const fs::path& out) {
    // A stopped run's folder (unless the folder itself was deleted) says it is unfinished until
    // the resume finishes it.
    if (fs::exists(out)) {
      EXPECT_TRUE(fs::exists(out / "unfinished.txt")) << "the stopped run looks finished";
    }
    const std::string partial = fileBytes(out / "trials.csv");
    if (!partial.empty()) {
      EXPECT_EQ(partial.back(), '\n') << "a torn line was left in trials.csv";
      EXPECT_LT(lineCount(out / "trials.csv"), lineCount(wholeDir() / "trials.csv"))
          << "the run was not stopped before its end";
    }
    const auto resumed = visgrab::test::runVisgrab(commonArgs() + " --threads 1 --resume --out " +
                                                   visgrab::test::shellQuoted(out));
    ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
    EXPECT_FALSE(fs::exists(out / "unfinished.txt"));
    EXPECT_EQ(fileBytes(out / "trials.csv"), fileBytes(wholeDir() / "trials.csv"));
    EXPECT_EQ(fileBytes(out / "run.csv"), fileBytes(wholeDir() / "run.csv"));
  }

  static std::unique_ptr<visgrab::test::TempDir> shared_;
};

std::unique_ptr<visgrab::test::TempDir> InterruptedRun::shared_;

// A tmpfs mounted for the test, unmounted at the end.
class Tmpfs {
 public:
  explicit Tmpfs(const fs::path& at) : at_(at) {
    fs::create_directories(at_);
    if (::mount("tmpfs", at_.c_str(), "tmpfs", 0, "size=256k") != 0) {
      error_ = std::strerror(errno);
    }
  }
  ~Tmpfs() {
    if (error_.empty()) ::umount2(at_.c_str(), MNT_DETACH);
  }
  Tmpfs(const Tmpfs&) = delete;
  Tmpfs& operator=(const Tmpfs&) = delete;
  const std::string& error() const { return error_; }

 private:
  fs::path at_;
  std::string error_;
};

// Fills the file system of `file`'s folder: writes `file` until the system says ENOSPC.
void fillDisk(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(fd, 0) << std::strerror(errno);
  const std::vector<char> block(4096, 'x');
  for (;;) {
    const ssize_t n = ::write(fd, block.data(), block.size());
    if (n > 0) continue;
    ASSERT_EQ(errno, ENOSPC) << std::strerror(errno);
    break;
  }
  ::close(fd);
}

TEST_F(InterruptedRun, AFullDiskStopsTheRunWithItsReasonAndResumeCompletesIt) {
  if (::geteuid() != 0) GTEST_SKIP() << "SKIPPED: mounting a small tmpfs needs root";
  visgrab::test::TempDir tmp;
  const fs::path mountPoint = tmp.path() / "disk";
  const Tmpfs disk(mountPoint);
  if (!disk.error().empty()) {
    GTEST_SKIP() << "SKIPPED: cannot mount a tmpfs here: " << disk.error();
  }
  const fs::path out = mountPoint / "results";
  const pid_t pid = start(out, tmp.path() / "log.txt");
  ASSERT_GT(pid, 0);
  int status = 0;
  ASSERT_TRUE(waitForTrials(pid, out / "trials.csv", 2, status))
      << "the run ended before it wrote 2 trials: " << fileBytes(tmp.path() / "log.txt");
  // The disk fills up mid-run.
  fillDisk(mountPoint / "filler");
  const ChildRun run = finish(pid, tmp.path() / "log.txt");
  ASSERT_TRUE(run.exited()) << run.output;
  EXPECT_EQ(run.code(), 1) << run.output;
  EXPECT_NE(run.output.find("cannot write " + out.string()), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(std::strerror(ENOSPC)), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("terminate called"), std::string::npos) << run.output;
  // Space again, then resume.
  fs::remove(mountPoint / "filler");
  expectResumesToTheWholeRun(out);
}

// Any user: a file-size limit makes writes past it fail (EFBIG) as a full disk would, in the
// middle of a line.
TEST_F(InterruptedRun, AWriteThatFailsInMidLineLeavesNoTornLineAndResumeCompletesIt) {
  visgrab::test::TempDir tmp;
  const fs::path out = tmp.path() / "results";
  // A limit run.csv stays below (its bytes do not depend on the run's progress) and trials.csv
  // passes after at least two trials, well before its end.
  const std::string whole = fileBytes(wholeDir() / "trials.csv");
  std::size_t header = 0, longest = 0;
  for (std::size_t at = 0, line = 0; at < whole.size(); ++line) {
    const std::size_t end = whole.find('\n', at) + 1;
    if (line < 1) header += end - at;
    if (line >= 1) longest = std::max(longest, end - at);
    at = end;
  }
  const rlim_t limit =
      std::max<std::size_t>(fs::file_size(wholeDir() / "run.csv"), header + 2 * longest) + 1;
  ASSERT_LT(limit + 2 * longest, whole.size()) << "too few trials for the test";
  const ChildRun run = finish(start(out, tmp.path() / "log.txt", limit), tmp.path() / "log.txt");
  ASSERT_TRUE(run.exited()) << run.output;
  EXPECT_EQ(run.code(), 1) << run.output;
  EXPECT_NE(run.output.find("cannot write " + (out / "trials.csv").string() + ": " +
                            std::strerror(EFBIG)),
            std::string::npos)
      << run.output;
  EXPECT_LE(fs::file_size(out / "trials.csv"), limit);
  EXPECT_GE(lineCount(out / "trials.csv"), 3u) << "fewer than two trials before the limit";
  expectResumesToTheWholeRun(out);
}

TEST_F(InterruptedRun, ADeletedResultFolderStopsTheRunAndResumeCompletesIt) {
  visgrab::test::TempDir tmp;
  const fs::path out = tmp.path() / "results";
  const pid_t pid = start(out, tmp.path() / "log.txt");
  ASSERT_GT(pid, 0);
  int status = 0;
  ASSERT_TRUE(waitForTrials(pid, out / "trials.csv", 2, status))
      << "the run ended before it wrote 2 trials: " << fileBytes(tmp.path() / "log.txt");
  fs::remove_all(out);
  const ChildRun run = finish(pid, tmp.path() / "log.txt");
  ASSERT_TRUE(run.exited()) << run.output;
  EXPECT_EQ(run.code(), 1) << run.output;
  EXPECT_NE(run.output.find("cannot write " + (out / "trials.csv").string() + ": " +
                            std::strerror(ENOENT)),
            std::string::npos)
      << run.output;
  expectResumesToTheWholeRun(out);
}

TEST_F(InterruptedRun, SigtermStopsTheRunCleanlyWithCode143AndResumeCompletesIt) {
  visgrab::test::TempDir tmp;
  const fs::path out = tmp.path() / "results";
  const pid_t pid = start(out, tmp.path() / "log.txt");
  ASSERT_GT(pid, 0);
  int status = 0;
  ASSERT_TRUE(waitForTrials(pid, out / "trials.csv", 3, status))
      << "the run ended before it wrote 3 trials: " << fileBytes(tmp.path() / "log.txt");
  ::kill(pid, SIGTERM);
  const ChildRun run = finish(pid, tmp.path() / "log.txt");
  ASSERT_TRUE(run.exited()) << "not a clean exit: " << run.output;
  EXPECT_EQ(run.code(), 128 + SIGTERM) << run.output;
  EXPECT_NE(run.output.find("SIGTERM"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("--resume"), std::string::npos) << run.output;
  expectResumesToTheWholeRun(out);
}

// A scene file that cannot be read when the run reaches its scene stops the run (exit 1, the file
// named); once it is back, --resume completes the run. The run uses a copy of the test database
// (its run.csv then names the copy: compared with the database line set aside).
TEST_F(InterruptedRun, AnUnreadableSceneFileStopsTheRunAndResumeCompletesIt) {
  visgrab::test::TempDir tmp;
  const fs::path copy = tmp.path() / "db";
  fs::copy(visgrab::test::testDatabase().root(), copy, fs::copy_options::recursive);
  // The last of the run's scenes in database order; the first one is loaded before the run.
  const fs::path missing = copy / "scenes/textured/single/peachcan/02/scene.dwc.xml";
  ASSERT_TRUE(fs::exists(missing));
  fs::rename(missing, tmp.path() / "saved.dwc.xml");
  const fs::path out = tmp.path() / "results";
  const std::string args = "run --db " + visgrab::test::shellQuoted(copy) + " --grasps " +
                           visgrab::test::shellQuoted(shared_->path() / "grasps.txt") + " --hand " +
                           visgrab::test::shellQuoted(handFile()) + " --quiet --out " +
                           visgrab::test::shellQuoted(out);
  const auto run = visgrab::test::runVisgrab(args + " --threads 2");
  EXPECT_EQ(run.exitCode, 1) << run.output;
  // The scene loader's diagnostic: the file, then the system's reason.
  EXPECT_NE(run.output.find(missing.string() + ": error: cannot read the file: no such file"),
            std::string::npos)
      << run.output;
  EXPECT_GE(lineCount(out / "trials.csv"), 1u + 6u) << "the scenes before it did not run";
  EXPECT_LT(lineCount(out / "trials.csv"), lineCount(wholeDir() / "trials.csv"));
  fs::rename(tmp.path() / "saved.dwc.xml", missing);
  const auto resumed = visgrab::test::runVisgrab(args + " --threads 1 --resume");
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  EXPECT_EQ(fileBytes(out / "trials.csv"), fileBytes(wholeDir() / "trials.csv"));
  auto withoutDatabase = [](std::string text) {
    const std::size_t at = text.find("\ndatabase,");
    if (at != std::string::npos) text.erase(at, text.find('\n', at + 1) - at);
    return text;
  };
  const std::string resumedRun = fileBytes(out / "run.csv");
  EXPECT_NE(resumedRun.find("\ndatabase," + copy.string() + ","), std::string::npos) << resumedRun;
  EXPECT_EQ(withoutDatabase(resumedRun), withoutDatabase(fileBytes(wholeDir() / "run.csv")));
}

}  // namespace
