// generateAcronymDatabase (`visgrab db from-acronym`) on a box written by the test, whose
// object frame, mass properties and friction are worked by hand below.
#include "visgrab/generator/acronym_database.hpp"

#include <gtest/gtest.h>

#include <string>

#include "rw/common/text_file.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "support/test_support.hpp"
#include "visgrab/database/database.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::generator::AcronymObjectSource;

// A closed box from (100, 50, 10) to (104, 53, 16) in file units, triangles wound outwards.
std::string boxObj() {
  std::string text;
  for (int i = 0; i < 8; ++i) {
    text += "v " + std::to_string((i & 1) != 0 ? 104 : 100) + " " +
            std::to_string((i & 2) != 0 ? 53 : 50) + " " + std::to_string((i & 4) != 0 ? 16 : 10) +
            "\n";
  }
  // Vertex k (1-based) = i + 1 with x bit 1, y bit 2, z bit 4.
  text +=
      "f 1 3 4\nf 1 4 2\n"   // z = 10, normal -z
      "f 5 6 8\nf 5 8 7\n"   // z = 16, normal +z
      "f 1 2 6\nf 1 6 5\n"   // y = 50, normal -y
      "f 3 7 8\nf 3 8 4\n"   // y = 53, normal +y
      "f 1 5 7\nf 1 7 3\n"   // x = 100, normal -x
      "f 2 4 8\nf 2 8 6\n";  // x = 104, normal +x
  return text;
}

AcronymObjectSource boxSource(const fs::path& dir) {
  AcronymObjectSource s;
  s.file = "Box_abc123_0.01.h5";
  s.mesh = visgrab::test::writeFile(dir / "meshes/Box/abc123.obj", boxObj());
  s.scale = 0.01;
  s.mass = 0.2;
  s.friction = 0.7;
  // Not the uniform solid's centre (1.02, 0.515, 0.13): the file's values must win.
  s.com = {1.021, 0.516, 0.12};
  s.inertia = Eigen::Vector3d(3e-4, 2e-4, 1e-4).asDiagonal();
  return s;
}

visgrab::generator::AcronymDatabaseOptions projectFiles() {
  visgrab::generator::AcronymDatabaseOptions options;
  options.handFolder = visgrab::test::sourceDir() / "scenes/hands/sdh";
  options.materials = visgrab::test::sourceDir() / "scenes/materials.xml";
  return options;
}

TEST(AcronymDatabase, NamesObjectsAfterTheFileWithoutTheScale) {
  using visgrab::generator::acronymObjectName;
  EXPECT_EQ(acronymObjectName("Table_99cf659ae2fe4b87b72437fd995483b_0.009700376721042367.h5"),
            "table_99cf659ae2fe4b87b72437fd995483b");
  EXPECT_EQ(acronymObjectName("Mug-Large_1a2b.h5"), "mug_large_1a2b");
  EXPECT_EQ(acronymObjectName("7up_can.h5"), "object_7up_can");
}

TEST(AcronymDatabase, TheObjectFloatsWhereItsScaledMeshSaysWithTheFilesMassAndFriction) {
  visgrab::test::TempDir dir;
  const fs::path db = dir.path() / "db";
  const auto report =
      visgrab::generator::generateAcronymDatabase({boxSource(dir.path())}, db, projectFiles());
  ASSERT_EQ(report.scenes.size(), 1u);
  const std::string id = "plain/single/box_abc123/01";
  EXPECT_EQ(report.scenes[0], id);

  const auto database = visgrab::database::Database::open(db);
  const auto& scene = database.scene(id);
  EXPECT_TRUE(scene.leftImage.empty());
  EXPECT_TRUE(scene.calibration.empty());
  ASSERT_TRUE(scene.source.has_value());
  EXPECT_EQ(scene.source->file, "Box_abc123_0.01.h5");
  EXPECT_TRUE(scene.source->X_W_source.isApprox(rw::math::Transform3D::Identity()));
  // The scaled box spans x 1.00..1.04, y 0.50..0.53, z 0.10..0.16 m in the world (the mesh
  // frame). The object frame has the lowest point at z = 0 and the uniform solid's centroid
  // (1.02, 0.515, 0.13) on its z axis, so it sits at (1.02, 0.515, 0.10), unrotated.
  ASSERT_EQ(scene.groundTruth.size(), 1u);
  const rw::math::Transform3D& X_WO = scene.groundTruth[0].X_WO;
  EXPECT_NEAR((X_WO.translation() - rw::math::Vector3D(1.02, 0.515, 0.10)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((X_WO.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);

  const auto dwc = rwsim::loaders::loadDynamicWorkCell(scene.dynamicWorkcell);
  const auto body = dwc->findBody("box_abc123");
  ASSERT_TRUE(body.valid());
  const auto& b = dwc->body(body);
  EXPECT_DOUBLE_EQ(b.mass.mass, 0.2);
  // The file's centre of mass in the object frame: (1.021, 0.516, 0.12) - (1.02, 0.515, 0.10).
  EXPECT_NEAR((b.mass.cog - rw::math::Vector3D(0.001, 0.001, 0.02)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(b.mass.inertia(0, 0), 3e-4, 1e-12);
  EXPECT_NEAR(b.mass.inertia(2, 2), 1e-4, 1e-12);
  EXPECT_EQ(b.material, "Object_box_abc123");
  EXPECT_DOUBLE_EQ(dwc->materials().mu("Finger", b.material), 0.7);
  // The project's pairs are kept.
  EXPECT_DOUBLE_EQ(dwc->materials().mu("Finger", "Object"), 0.6);
  // No table in the scene.
  EXPECT_FALSE(dwc->findBody("Table").valid());
  // The collision geometry is the mesh itself (the default): one piece, the box's 8 corners
  // joined by position and its 12 triangles, at the scaled box's place in the object frame.
  const std::string hull = rw::common::readTextFileOrThrow(db / "scenes" / id / "scene.wc.xml");
  EXPECT_NE(hull.find("box_abc123_hull0.stl"), std::string::npos) << hull;
  EXPECT_EQ(hull.find("box_abc123_hull1.stl"), std::string::npos) << hull;

  // Again: the scene is complete, nothing is redone; the index keeps its bytes.
  const std::string before = rw::common::readTextFileOrThrow(db / "index.xml");
  visgrab::generator::generateAcronymDatabase({boxSource(dir.path())}, db, projectFiles());
  EXPECT_EQ(rw::common::readTextFileOrThrow(db / "index.xml"), before);
}

TEST(AcronymDatabase, RefusesBadSources) {
  visgrab::test::TempDir dir;
  auto s = boxSource(dir.path());
  const auto expectError = [&](const AcronymObjectSource& bad, const std::string& what) {
    try {
      visgrab::generator::generateAcronymDatabase({bad}, dir.path() / "db", projectFiles());
      ADD_FAILURE() << "no error for " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("Box_abc123_0.01.h5"), std::string::npos) << e.what();
    }
  };
  auto bad = s;
  bad.mass = 0.0;
  expectError(bad, "object/mass");
  bad = s;
  bad.inertia(0, 1) = 1e-3;
  expectError(bad, "object/inertia");
  bad = s;
  bad.friction = -1.0;
  expectError(bad, "object/friction");
  EXPECT_THROW(
      visgrab::generator::generateAcronymDatabase({s, s}, dir.path() / "db2", projectFiles()),
      std::invalid_argument);
}

}  // namespace
