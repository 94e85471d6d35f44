#include "support/test_database.hpp"

#include <sys/file.h>
#include <unistd.h>

#include <fcntl.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/render/mesh_loader.hpp"
#include "visgrab/render/offscreen_renderer.hpp"

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

render::RenderResult renderLeftViewTruth(const database::Database& database,
                                         const database::SceneEntry& entry) {
  static render::OffscreenRenderer renderer;
  static std::map<std::string, std::vector<render::MeshHandle>> uploaded;
  auto meshes = [&](const std::filesystem::path& obj) -> const std::vector<render::MeshHandle>& {
    auto it = uploaded.find(obj.string());
    if (it == uploaded.end()) {
      std::vector<render::MeshHandle> handles;
      for (auto& m : render::loadVisualMeshes(obj)) {
        handles.push_back(renderer.add(std::make_shared<const visual::VisualMesh>(m)));
      }
      it = uploaded.emplace(obj.string(), handles).first;
    }
    return it->second;
  };
  const std::string texture(database::toString(entry.conditions->texture));
  render::Scene scene;
  for (const auto h : meshes(database.root() / "tables" / texture / (texture + ".obj"))) {
    scene.items.push_back({h, rw::math::Transform3D::Identity(), 1});
  }
  for (const auto& pose : database.groundTruth(entry.id)) {
    const std::string name(database::objectName(pose.object));
    for (const auto h : meshes(database.root() / "objects" / name / (name + ".obj"))) {
      scene.items.push_back({h, pose.X_WO, static_cast<std::uint16_t>(10 + pose.object)});
    }
  }
  const auto k = database.calibration(entry.id);
  render::PinholeCamera camera;
  camera.fx = k.P1(0, 0);
  camera.fy = k.P1(1, 1);
  camera.cx = k.P1(0, 2);
  camera.cy = k.P1(1, 2);
  camera.width = k.width;
  camera.height = k.height;
  // The rectified left camera: the raw left camera turned by R1.
  camera.X_WC = k.X_TL;
  camera.X_WC.linear() = k.X_TL.linear() * k.R1.transpose();
  return renderer.render(scene, camera);
}

const database::Database& idealTestDatabase() {
  static const database::Database database = database::Database::open(idealTestDatabasePath());
  return database;
}

}  // namespace visgrab::test
