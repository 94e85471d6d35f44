#include "support/test_support.hpp"

#include <sys/wait.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <vector>

namespace visgrab::test {

std::filesystem::path sourceDir() {
  if (const char* env = std::getenv("VISGRAB_SOURCE_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return VISGRAB_SOURCE_DIR;
}

std::optional<std::filesystem::path> compatDataDir() {
  const char* env = std::getenv("RW_COMPAT_DATA");
  if (env == nullptr || *env == '\0') return std::nullopt;
  std::filesystem::path dir(env);
  if (!std::filesystem::is_directory(dir)) return std::nullopt;
  return std::filesystem::absolute(dir);
}

std::optional<std::filesystem::path> acronymDataDir() {
  std::vector<std::filesystem::path> candidates;
  if (const char* d = std::getenv("VISGRAB_ACRONYM_DATA"); d != nullptr && *d != '\0') {
    candidates.emplace_back(d);
  }
  if (const auto compat = compatDataDir()) candidates.push_back(*compat / ".." / "acronym");
  for (const auto& c : candidates) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(c / "franka_gripper_collision_mesh.stl", ec)) {
      return std::filesystem::absolute(c).lexically_normal();
    }
  }
  return std::nullopt;
}

::testing::AssertionResult transformNear(const char* aExpr, const char* bExpr, const char*,
                                         const rw::math::Transform3D& a,
                                         const rw::math::Transform3D& b, double tol) {
  const double dp = (a.translation() - b.translation()).cwiseAbs().maxCoeff();
  const double dr = (a.linear() - b.linear()).cwiseAbs().maxCoeff();
  if (dp <= tol && dr <= tol) return ::testing::AssertionSuccess();
  std::ostringstream os;
  os << aExpr << " and " << bExpr << " differ by " << dp << " m in position and " << dr
     << " in rotation (tolerance " << tol << ")\n"
     << aExpr << " =\n"
     << a.matrix() << "\n"
     << bExpr << " =\n"
     << b.matrix();
  return ::testing::AssertionFailure() << os.str();
}

::testing::AssertionResult vectorNear(const char* aExpr, const char* bExpr, const char*,
                                      const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                      double tol) {
  if (a.size() != b.size()) {
    return ::testing::AssertionFailure()
           << aExpr << " has " << a.size() << " entries, " << bExpr << " has " << b.size();
  }
  const double d = a.size() == 0 ? 0.0 : (a - b).cwiseAbs().maxCoeff();
  if (d <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << aExpr << " = [" << a.transpose() << "] and " << bExpr << " = [" << b.transpose()
         << "] differ by " << d << " (tolerance " << tol << ")";
}

TempDir::TempDir() {
  static std::atomic<unsigned> counter{0};
  std::random_device rd;
  const auto base = std::filesystem::temp_directory_path();
  for (;;) {
    path_ = base / ("visgrab-test-" + std::to_string(rd()) + "-" + std::to_string(counter++));
    if (std::filesystem::create_directories(path_)) break;
  }
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::filesystem::path writeFile(const std::filesystem::path& file, const std::string& text) {
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
  return file;
}

std::vector<std::filesystem::path> meshFuzzRegressions(const std::filesystem::path& dir) {
  constexpr std::array<const char*, 8> kExtensions = {".stl", ".obj", ".ply", ".ac",
                                                      ".off", ".3ds", ".dae", ".stlb"};
  std::vector<std::filesystem::path> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(sourceDir() / "fuzz/regressions/mesh")) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.empty()) continue;
    const char* extension = kExtensions[static_cast<unsigned char>(bytes[0]) % kExtensions.size()];
    files.push_back(
        writeFile(dir / (entry.path().filename().string() + extension), bytes.substr(1)));
  }
  return files;
}

RunResult runProgram(const std::filesystem::path& program, const std::string& args) {
  const std::string command = shellQuoted(program) + " " + args + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), n);
  }
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string shellQuoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

}  // namespace visgrab::test
