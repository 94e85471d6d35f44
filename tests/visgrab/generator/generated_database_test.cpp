// The shared generated test database (tests/support/test_database.hpp) checked against
// independent truth: the simulator (the settled objects stay put and do not penetrate), the
// renderer's ground-truth depth (OpenCV's StereoSGBM on the rectified pair, reprojected with Q)
// and the collision geometry projected with P1 (silhouettes); and small generations of their own
// for byte equality (determinism across thread counts, resume) and unusable inputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "rw/loaders/workcell_loader.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/render/mesh_loader.hpp"
#include "visgrab/render/offscreen_renderer.hpp"

namespace {

namespace fs = std::filesystem;
namespace db = visgrab::database;
namespace gen = visgrab::generator;
using rw::math::Transform3D;
using rw::math::Vector3D;

gen::GeneratorOptions optionsFor(const fs::path& out, int threads) {
  gen::GeneratorOptions options;
  options.out = out;
  options.objectSpec = visgrab::test::sourceDir() / "scenes/objects/objects.xml";
  options.handFolder = visgrab::test::sourceDir() / "scenes/hands/sdh";
  options.materials = visgrab::test::sourceDir() / "scenes/materials.xml";
  options.seed = 5;
  options.threads = threads;
  return options;
}

// The shared test database (tests/support/test_database.hpp): standing, lying, apart and
// close, on both tables.
const db::Database& sampleDatabase() { return visgrab::test::testDatabase(); }

TEST(GeneratedDatabase, ListsTheGeneratedScenesWithTheirConditions) {
  const auto& database = sampleDatabase();
  ASSERT_EQ(database.list().size(), visgrab::test::kTestSceneIds.size());
  EXPECT_EQ(database.seed(), visgrab::test::kTestDatabaseSeed);
  for (const auto& scene : visgrab::test::testDatabaseScenes()) {
    const auto& entry = database.scene(db::sceneIdOf(scene));
    ASSERT_TRUE(entry.conditions.has_value());
    EXPECT_EQ(*entry.conditions, scene);
    EXPECT_EQ(database.groundTruth(db::sceneIdOf(scene)).size(), scene.objects.size());
  }
}

TEST(GeneratedDatabase, SettledObjectsAreAtRestAndDoNotPenetrate) {
  const auto& database = sampleDatabase();
  for (const auto& entry : database.list()) {
    const auto dwc = rwsim::loaders::loadDynamicWorkCell(entry.dynamicWorkcell);
    rwsim::simulator::Simulator sim(*dwc);
    sim.reset(dwc->workcell().defaultState());
    const auto& truth = database.groundTruth(entry.id);
    std::vector<rwsim::dynamics::BodyId> bodies;
    for (const auto& pose : truth) {
      const auto body = dwc->findBody(db::objectName(pose.object));
      ASSERT_TRUE(body.valid());
      // The scene file puts the object where the index says.
      EXPECT_TRANSFORM_NEAR(sim.bodyPose(body), pose.X_WO, 1e-6);
      bodies.push_back(body);
    }
    double deepest = 0.0;
    for (int step = 0; step < 100; ++step) {  // 0.5 s more
      ASSERT_EQ(sim.step(), rwsim::simulator::StepStatus::kOk) << entry.id;
      for (const auto& pair : sim.contacts()) {
        for (const auto& c : pair.points) deepest = std::max(deepest, c.point.depth);
      }
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const Transform3D X = sim.bodyPose(bodies[i]);
      EXPECT_LT((X.translation() - truth[i].X_WO.translation()).norm(), 1e-3) << entry.id;
      EXPECT_LT(sim.bodyLinearVelocity(bodies[i]).norm(), 1e-3) << entry.id;
    }
    EXPECT_LT(deepest, 1e-3) << entry.id;
  }
}

// The truth of the rectified left view from the database's own files
// (test/support/test_database.hpp).
visgrab::render::RenderResult renderTruth(const db::Database& database,
                                          const db::SceneEntry& entry) {
  return visgrab::test::renderLeftViewTruth(database, entry);
}

// The matcher on clean images (the ideal-camera twin); on the realistic camera the share within
// 5 mm is lower by design (CameraRealism.*, docs/database-format.md "Realism").
TEST(GeneratedDatabase, StereoReconstructsTheObjectsWithinFiveMillimetres) {
  const auto& database = visgrab::test::idealTestDatabase();
  for (const auto& entry : database.list()) {
    const cv::Mat left = database.leftImage(entry.id);
    const cv::Mat right = database.rightImage(entry.id);
    const auto calibration = database.calibration(entry.id);
    // Disparities 48..240 px cover the table from 0.4 m to 2 m; 5x5 blocks on colour.
    const int blockSize = 5;
    auto sgbm = cv::StereoSGBM::create(48, 192, blockSize, 8 * 3 * blockSize * blockSize,
                                       32 * 3 * blockSize * blockSize, 1, 0, 10, 100, 2,
                                       cv::StereoSGBM::MODE_SGBM);
    cv::Mat disparity16, disparity;
    sgbm->compute(left, right, disparity16);
    disparity16.convertTo(disparity, CV_32F, 1.0 / 16.0);
    cv::Mat Q(4, 4, CV_64F);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) Q.at<double>(i, j) = calibration.Q(i, j);
    }
    cv::Mat points;
    cv::reprojectImageTo3D(disparity, points, Q, true);
    const auto truth = renderTruth(database, entry);
    int objectPixels = 0, withDisparity = 0, within = 0;
    for (int r = 0; r < truth.depth.height; ++r) {
      for (int c = 0; c < truth.depth.width; ++c) {
        if (truth.instanceIds.at(r, c) < 10) continue;
        ++objectPixels;
        if (disparity.at<float>(r, c) < 48.0f) continue;  // no disparity found
        ++withDisparity;
        const double z = points.at<cv::Vec3f>(r, c)[2];
        if (std::abs(z - truth.depth.at(r, c)) < 0.005) ++within;
      }
    }
    std::cout << entry.id << ": " << within << " of " << withDisparity
              << " object pixels with a disparity within 5 mm ("
              << 100.0 * within / std::max(1, withDisparity) << " %), " << objectPixels
              << " object pixels\n";
    ASSERT_GT(objectPixels, 2000) << entry.id;
    EXPECT_GT(withDisparity, objectPixels / 2) << entry.id;
    EXPECT_GE(within, 0.8 * withDisparity)
        << entry.id << ": " << within << " of " << withDisparity << " object pixels with a "
        << "disparity are within 5 mm (" << objectPixels << " object pixels)";
  }
}

TEST(GeneratedDatabase, SceneModelProjectedWithP1MatchesTheRenderedSilhouette) {
  const auto& database = sampleDatabase();
  for (const auto& entry : database.list()) {
    const auto calibration = database.calibration(entry.id);
    const auto wc = rw::loaders::loadWorkCell(entry.workcell);
    const auto state = wc->defaultState();
    // P1 projects points of the rectified left camera: X_TL turned by R1.
    Transform3D X_TR = calibration.X_TL;
    X_TR.linear() = calibration.X_TL.linear() * calibration.R1.transpose();
    const Transform3D X_LW = X_TR.inverse();
    const auto truth = renderTruth(database, entry);
    for (const auto& pose : database.groundTruth(entry.id)) {
      const auto frame = wc->frames().find(db::objectName(pose.object));
      ASSERT_TRUE(frame.valid());
      const auto* object = wc->findObject(frame);
      ASSERT_NE(object, nullptr);
      const Transform3D X_WF = rw::kinematics::worldTransform(wc->frames(), state, frame);
      cv::Mat model = cv::Mat::zeros(calibration.height, calibration.width, CV_8U);
      for (const auto& g : object->collision) {
        const auto& mesh = g.geometry->triangles();
        for (const auto& t : mesh.triangles) {
          std::vector<cv::Point> corners;
          for (const auto i : t) {
            const Eigen::Vector3d u =
                calibration.P1 *
                (X_LW * X_WF * g.X_frame_geometry * mesh.vertices[i]).homogeneous();
            // Fixed point with 8 fractional bits; pixel centres at integers as in OpenCV.
            corners.emplace_back(static_cast<int>(std::lround(u.x() / u.z() * 256.0)),
                                 static_cast<int>(std::lround(u.y() / u.z() * 256.0)));
          }
          cv::fillConvexPoly(model, corners, cv::Scalar(255), cv::LINE_8, 8);
        }
      }
      int both = 0, either = 0;
      for (int r = 0; r < model.rows; ++r) {
        for (int c = 0; c < model.cols; ++c) {
          // Pixels where the other object of a pair is in front say nothing about this one.
          const int id = truth.instanceIds.at(r, c);
          if (id >= 10 && id != 10 + pose.object) continue;
          const bool m = model.at<std::uint8_t>(r, c) != 0;
          const bool s = id == 10 + pose.object;
          both += m && s;
          either += m || s;
        }
      }
      ASSERT_GT(either, 0);
      EXPECT_GE(static_cast<double>(both) / either, 0.95) << entry.id << " object " << pose.object;
    }
  }
}

// Names of the files that differ between two folders' contents (or exist in one only).
std::vector<std::string> differences(const std::map<std::string, std::string>& a,
                                     const std::map<std::string, std::string>& b) {
  std::vector<std::string> out;
  for (const auto& [name, bytes] : a) {
    const auto it = b.find(name);
    if (it == b.end() || it->second != bytes) out.push_back(name);
  }
  for (const auto& [name, bytes] : b) {
    if (a.count(name) == 0) out.push_back(name + " (only in the second)");
  }
  return out;
}

std::map<std::string, std::string> filesOf(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    files[fs::relative(e.path(), dir).generic_string()] =
        std::string(std::istreambuf_iterator<char>(in), {});
  }
  return files;
}

TEST(GeneratedDatabase, SameSeedSameBytesWhateverTheThreadsAndAResumeRedoesOnlyWhatIsMissing) {
  visgrab::test::TempDir tmp;
  const std::vector<db::SceneConditions> scenes{
      db::SceneConditions::single(db::Texture::kTextured, 18, 2),
      db::SceneConditions::pairScene(db::Texture::kPlain, 'e', 6)};
  const auto one = gen::generateDatabase(scenes, optionsFor(tmp.path() / "one", 1));
  const auto two = gen::generateDatabase(scenes, optionsFor(tmp.path() / "two", 2));
  EXPECT_EQ(one.generated, 2);
  EXPECT_EQ(two.generated, 2);
  const auto a = filesOf(tmp.path() / "one");
  EXPECT_EQ(differences(a, filesOf(tmp.path() / "two")), std::vector<std::string>{});
  EXPECT_GT(a.size(), 10u);
  // Interrupted after a scene lost its right image: only that scene is made again, identically.
  const std::string right = "scenes/" + db::sceneIdOf(scenes[1]) + "/right.png";
  ASSERT_EQ(a.count(right), 1u);
  fs::remove(tmp.path() / "one" / right);
  const auto resumed = gen::generateDatabase(scenes, optionsFor(tmp.path() / "one", 1));
  EXPECT_EQ(resumed.generated, 1);
  EXPECT_EQ(resumed.skipped, 1);
  EXPECT_EQ(differences(filesOf(tmp.path() / "one"), a), std::vector<std::string>{});
  // Another seed in the same folder is refused.
  auto other = optionsFor(tmp.path() / "one", 1);
  other.seed = 6;
  EXPECT_THROW(gen::generateDatabase(scenes, other), std::runtime_error);
}

// The canister (object 12) lies on its lid, 4 mm wider than its body: on true cylinders it rolls
// in a circle (a neutral equilibrium) and never comes to rest in an undamped settle. The second,
// damped settle (rolling resistance) brings it to rest on the table; without it the scene fails.
TEST(GeneratedDatabase, ALyingCanisterThatRollsSettlesWithRollingDamping) {
  visgrab::test::TempDir tmp;
  const std::vector<db::SceneConditions> scenes{
      db::SceneConditions::single(db::Texture::kPlain, 12, 7)};
  auto undamped = optionsFor(tmp.path() / "undamped", 1);
  undamped.seed = 1;
  undamped.maxAttempts = 1;
  undamped.rollingDamping = 0.0;
  const auto failed = gen::generateDatabase(scenes, undamped);
  ASSERT_EQ(failed.generated, 0);
  ASSERT_EQ(failed.failures.size(), 1u);
  EXPECT_NE(failed.failures[0].find("not at rest"), std::string::npos) << failed.failures[0];

  auto damped = undamped;
  damped.out = tmp.path() / "damped";
  damped.rollingDamping = gen::GeneratorOptions{}.rollingDamping;
  const auto made = gen::generateDatabase(scenes, damped);
  ASSERT_EQ(made.generated, 1) << (made.failures.empty() ? "" : made.failures[0]);
  // Lying: the canister's axis is horizontal, its lowest point on the table.
  const db::Database database = db::Database::open(damped.out);
  const auto& entry = database.list().front();
  ASSERT_EQ(entry.groundTruth.size(), 1u);
  const Transform3D& X = entry.groundTruth[0].X_WO;
  EXPECT_LT(std::abs(X.linear().col(2).z()), 0.1);
  // The scene file keeps no damping: trials run without it.
  std::ifstream dwc(entry.dynamicWorkcell);
  const std::string text((std::istreambuf_iterator<char>(dwc)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("Damping"), std::string::npos);
}

TEST(GeneratedDatabase, UnusableInputsAreClearErrors) {
  visgrab::test::TempDir tmp;
  const std::vector<db::SceneConditions> scenes{
      db::SceneConditions::single(db::Texture::kPlain, 5, 1)};
  auto options = optionsFor(tmp.path() / "db", 1);
  options.objectSpec = tmp.path() / "missing.xml";
  try {
    gen::generateDatabase(scenes, options);
    ADD_FAILURE() << "a missing object spec must throw";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("missing.xml"), std::string::npos) << e.what();
  }
  options = optionsFor(tmp.path() / "db2", 1);
  options.handFolder = tmp.path() / "nohand";
  try {
    gen::generateDatabase(scenes, options);
    ADD_FAILURE() << "a missing hand folder must throw";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("nohand"), std::string::npos) << e.what();
  }
}

}  // namespace
