#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rw/math/types.hpp"

/// Shared helpers for the project's tests.
namespace visgrab::test {

/// The project's source folder (for scenes/, xml/, tests/data/).
std::filesystem::path sourceDir();

/// `$RW_COMPAT_DATA` (RobWork's own files) if set and existing, else nullopt.
std::optional<std::filesystem::path> compatDataDir();

/// ACRONYM's example data (ACRONYM's NOTICE: tests only): `$VISGRAB_ACRONYM_DATA`, else
/// `$RW_COMPAT_DATA/../acronym`, if it holds franka_gripper_collision_mesh.stl; else nullopt.
std::optional<std::filesystem::path> acronymDataDir();

/// Checks two transforms agree: positions within `tol` metres, rotation matrices entrywise.
::testing::AssertionResult transformNear(const char* aExpr, const char* bExpr, const char* tolExpr,
                                         const rw::math::Transform3D& a,
                                         const rw::math::Transform3D& b, double tol);

/// Checks two vectors agree entrywise within `tol`.
::testing::AssertionResult vectorNear(const char* aExpr, const char* bExpr, const char* tolExpr,
                                      const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                      double tol);

/// A fresh empty temporary folder, removed when the object goes out of scope.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// The folder.
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Writes `text` to `file` (creating folders) and returns the path.
std::filesystem::path writeFile(const std::filesystem::path& file, const std::string& text);

/// Each input of fuzz/regressions/mesh written into `dir` as a mesh file whose extension the
/// input's first byte picks and whose bytes are the rest, as fuzz/mesh_fuzzer.cpp reads it.
std::vector<std::filesystem::path> meshFuzzRegressions(const std::filesystem::path& dir);

/// What a command printed and how it exited.
struct RunResult {
  /// Exit code (-1 if it did not exit normally).
  int exitCode = -1;
  /// Its stdout and stderr together.
  std::string output;
};

/// Runs `program` with `args` (already shell-quoted) through the shell and captures its output.
RunResult runProgram(const std::filesystem::path& program, const std::string& args);

/// `path` in single quotes for a shell command line.
std::string shellQuoted(const std::filesystem::path& path);

}  // namespace visgrab::test

/// Expects two Transform3D to agree within tol (positions in metres, rotation entries).
#define EXPECT_TRANSFORM_NEAR(a, b, tol) \
  EXPECT_PRED_FORMAT3(::visgrab::test::transformNear, a, b, tol)

/// Expects two Eigen vectors to agree entrywise within tol.
#define EXPECT_VECTOR_NEAR(a, b, tol) EXPECT_PRED_FORMAT3(::visgrab::test::vectorNear, a, b, tol)

/// Skips the current test with a reason unless RobWork's compatibility data is available;
/// otherwise declares `var` as its path.
#define REQUIRE_COMPAT_DATA(var)                                      \
  const auto var##_opt = ::visgrab::test::compatDataDir();            \
  if (!var##_opt)                                                     \
    GTEST_SKIP() << "RW_COMPAT_DATA is not set: RobWork's files are " \
                    "needed for this compatibility test";             \
  const std::filesystem::path& var = *var##_opt
