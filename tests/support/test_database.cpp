#include "support/test_database.hpp"

#include <sys/file.h>
#include <unistd.h>

#include <fcntl.h>

#include <stdexcept>
#include <string>

#include "support/test_support.hpp"
#include "visgrab/generator/generator.hpp"

namespace visgrab::test {

namespace {

// Holds an exclusive flock on a file for its lifetime.
class FileLock {
 public:
  explicit FileLock(const std::filesystem::path& file)
      : fd_(::open(file.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0) {
      if (fd_ >= 0) ::close(fd_);
      throw std::runtime_error("cannot lock " + file.string());
    }
  }
  ~FileLock() {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

std::filesystem::path generateTestDatabase(const std::string& camera) {
  const std::filesystem::path dir =
      std::string(VISGRAB_TEST_DATABASE_DIR) + (camera == "realistic" ? "" : "-" + camera);
  std::filesystem::create_directories(dir.parent_path());
  const FileLock lock(dir.string() + ".lock");
  generator::GeneratorOptions options;
  options.out = dir;
  options.objectSpec = sourceDir() / "scenes/objects/objects.xml";
  options.handFolder = sourceDir() / "scenes/hands/sdh";
  options.materials = sourceDir() / "scenes/materials.xml";
  options.seed = kTestDatabaseSeed;
  options.threads = 2;
  options.camera = generator::findCameraProfile(camera, sourceDir() / "scenes/cameras");
  const auto report = generator::generateDatabase(testDatabaseScenes(), options);
  if (!report.failures.empty()) {
    throw std::runtime_error("shared test database " + dir.string() + ": " +
                             report.failures.front());
  }
  return dir;
}

}  // namespace

std::vector<database::SceneConditions> testDatabaseScenes() {
  std::vector<database::SceneConditions> scenes;
  for (const std::string_view id : kTestSceneIds) {
    const auto conditions = database::parseSceneId(id);
    if (!conditions) throw std::logic_error("kTestSceneIds: not a scene id: " + std::string(id));
    scenes.push_back(*conditions);
  }
  return scenes;
}

const std::filesystem::path& testDatabasePath() {
  static const std::filesystem::path dir = generateTestDatabase("realistic");
  return dir;
}

const std::filesystem::path& idealTestDatabasePath() {
  static const std::filesystem::path dir = generateTestDatabase("ideal");
  return dir;
}

const database::Database& testDatabase() {
  static const database::Database database = database::Database::open(testDatabasePath());
  return database;
}

const database::Database& idealTestDatabase() {
  static const database::Database database = database::Database::open(idealTestDatabasePath());
  return database;
}

}  // namespace visgrab::test
