// The baseline's vision on the 20 scenes of the shared test database, against their ground
// truth (scene files, not the vision's own data): the table plane within 2 deg of the table
// frame, and every object found as a cluster whose estimated centre is within 2 cm of the
// centre of the object's collision geometry. Also: the grasps do not depend on the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "support/test_database.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/taskio/grasp_list.hpp"
#include "visgrab/vision/baseline.hpp"

namespace visgrab::vision {
namespace {

// Centre of the world-frame bounding box of an object's collision geometry.
Eigen::Vector3d trueCentre(const database::SceneEntry& scene, int objectId) {
  const auto wc = rw::loaders::loadWorkCell(scene.workcell);
  const auto state = wc->defaultState();
  const auto frame = wc->frames().find(std::string(database::objectName(objectId)));
  EXPECT_TRUE(frame.valid()) << scene.id << " object " << objectId;
  const auto* object = wc->findObject(frame);
  EXPECT_NE(object, nullptr);
  const rw::math::Transform3D X_WF = rw::kinematics::worldTransform(wc->frames(), state, frame);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (const auto& g : object->collision) {
    for (const auto& v : g.geometry->triangles().vertices) {
      const Eigen::Vector3d p = X_WF * g.X_frame_geometry * v;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  return 0.5 * (lo + hi);
}

// The segmentation's accuracy on clean images: the ideal-camera twin of the test database (on the
// realistic camera the baseline is measured by the benchmark, docs/baseline.md).
TEST(BaselineVision, TableAndObjectsMatchTheGroundTruthOnTwentyScenes) {
  const auto& db = test::idealTestDatabase();
  ASSERT_EQ(db.list().size(), 20u);
  const BaselineOptions options;
  double worstTilt = 0.0;
  int objects = 0, found = 0;
  for (const auto& scene : db.list()) {
    const SceneSegmentation s = analyzeScene(db, scene, options);
    const double tilt =
        std::acos(std::clamp(s.table.normal.dot(Eigen::Vector3d::UnitZ()), -1.0, 1.0)) * 180.0 /
        M_PI;
    EXPECT_LE(tilt, 2.0) << scene.id;
    EXPECT_NEAR(s.table.offset, 0.0, 0.005) << scene.id;
    worstTilt = std::max(worstTilt, tilt);
    for (const auto& truth : db.groundTruth(scene.id)) {
      const Eigen::Vector3d centre = trueCentre(scene, truth.object);
      double best = std::numeric_limits<double>::infinity();
      for (const auto& c : s.clusters) best = std::min(best, (c.centre - centre).norm());
      ++objects;
      found += best <= 0.02;
      EXPECT_LE(best, 0.02) << scene.id << ": " << database::objectName(truth.object) << " at "
                            << centre.transpose() << ", nearest cluster " << best << " m ("
                            << s.clusters.size() << " clusters)";
    }
  }
  EXPECT_EQ(objects, 28);
  std::cout << "worst table tilt " << worstTilt << " deg; " << found << " of " << objects
            << " objects found within 2 cm\n";
}

TEST(BaselineVision, GraspsAreTheSameWithOneAndTwoThreads) {
  const auto& db = test::testDatabase();
  std::vector<const database::SceneEntry*> scenes;
  for (const auto& s : db.list()) {
    if (scenes.size() < 4) scenes.push_back(&s);
  }
  BaselineOptions one, two;
  two.threads = 2;
  auto text = [&](const BaselineOptions& o) {
    std::vector<grasp::GraspRequest> all;
    for (const auto& r : baselineGrasps(db, scenes, o)) {
      EXPECT_TRUE(r.error.empty()) << r.sceneId << ": " << r.error;
      EXPECT_GT(r.clusters, 0) << r.sceneId;
      all.insert(all.end(), r.grasps.begin(), r.grasps.end());
    }
    return taskio::formatGraspList(all);
  };
  const std::string a = text(one);
  EXPECT_EQ(a, text(two));
  EXPECT_NE(a.find(",s3EGA1,s3EGA1-01,contacts,3,"), std::string::npos) << a.substr(0, 400);
}

TEST(BaselineVision, AnUnreadableSceneGetsAnErrorAndTheOthersGoOn) {
  const auto& db = test::testDatabase();
  database::SceneEntry broken = db.list().front();
  broken.id = "plain/single/nosuchobject/01";
  std::vector<const database::SceneEntry*> scenes = {&broken, &db.list()[1]};
  const auto results = baselineGrasps(db, scenes, BaselineOptions{});
  ASSERT_EQ(results.size(), 2u);
  EXPECT_TRUE(results[0].grasps.empty());
  EXPECT_NE(results[0].error.find("nosuchobject"), std::string::npos) << results[0].error;
  EXPECT_TRUE(results[1].error.empty()) << results[1].error;
  EXPECT_FALSE(results[1].grasps.empty());
}

}  // namespace
}  // namespace visgrab::vision
