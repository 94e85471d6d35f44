#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <string>

#include "rw/common/text_file.hpp"
#include "support/test_support.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/generator/scene_model.hpp"
#include "visgrab/objects/object_model.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::database::SceneConditions;
using visgrab::database::Texture;

// Lowest point of the model's collision geometry at pose X_WO, m.
double lowestPoint(const visgrab::objects::ObjectModel& model, const rw::math::Transform3D& X_WO) {
  double lowest = 1e9;
  for (const auto& piece : model.collision) {
    for (const auto& v : piece.triangles->vertices) lowest = std::min(lowest, (X_WO * v).z());
  }
  return lowest;
}

// RobWork's green cup (an STL with two small holes: fillHoles) and jam jar (both with their axis
// along y: rpy turns them up), read where RW_COMPAT_DATA points, never copied: a 4-scene database
// of them, standing and lying, on both tables, through generateDatabase.
TEST(MeshObjectDatabase, RobWorkMeshesGenerateSettledScenes) {
  REQUIRE_COMPAT_DATA(data);
  const fs::path cup = data / "objects" / "GreenCup_5k_tex.stl";
  const fs::path jam = data / "objects" / "OrangeMarmelade.stl";
  if (!fs::exists(cup) || !fs::exists(jam)) GTEST_SKIP() << "RobWork's object meshes are missing";
  visgrab::test::TempDir dir;
  const fs::path specFile = visgrab::test::writeFile(
      dir.path() / "spec" / "objects.xml",
      "<ObjectDatabase>\n"
      "  <Object id=\"101\" name=\"rwcup\" mass=\"0.09\">\n"
      "    <Mesh file=\"" +
          cup.string() +
          "\" rpy=\"0 0 90\" fillHoles=\"true\"/>\n"
          "    <Appearance pattern=\"plain-plastic\" seed=\"7\" body=\"0.1 0.45 0.12\"/>\n"
          "  </Object>\n"
          "  <Object id=\"102\" name=\"rwjam\" density=\"900\">\n"
          "    <Mesh file=\"" +
          jam.string() +
          "\" rpy=\"0 0 90\"/>\n"
          "    <Appearance pattern=\"label-band\" seed=\"8\" body=\"0.9 0.5 0.1\">\n"
          "      <Colour rgb=\"0.9 0.5 0.1\"/><Colour rgb=\"0.15 0.2 0.6\"/>\n"
          "    </Appearance>\n"
          "  </Object>\n"
          "  <Pair a=\"rwcup\" b=\"rwjam\"/>\n"
          "</ObjectDatabase>\n");
  const auto spec = visgrab::objects::loadObjectSpecs(specFile);
  visgrab::generator::GeneratorOptions options;
  options.out = dir.path() / "db";
  options.objectSpec = specFile;
  options.tableSpec = visgrab::test::sourceDir() / "scenes/objects/objects.xml";
  options.handFolder = visgrab::test::sourceDir() / "scenes/hands/sdh";
  options.materials = visgrab::test::sourceDir() / "scenes/materials.xml";
  options.catalog = visgrab::generator::objectCatalog(spec);
  options.seed = 5;
  options.threads = 2;
  const std::vector<SceneConditions> scenes{SceneConditions::single(Texture::kPlain, 101, 1),
                                            SceneConditions::single(Texture::kTextured, 101, 5),
                                            SceneConditions::single(Texture::kTextured, 102, 2),
                                            SceneConditions::single(Texture::kPlain, 102, 6)};
  const auto report = visgrab::generator::generateDatabase(scenes, options);
  ASSERT_TRUE(report.failures.empty()) << report.failures.front();
  EXPECT_EQ(report.generated, 4);

  // The index names the objects; the Database reads it with its own catalog.
  std::string index;
  ASSERT_TRUE(rw::common::readTextFile(options.out / "index.xml", index).empty());
  EXPECT_NE(index.find("<Object id=\"101\" name=\"rwcup\">"), std::string::npos);
  const auto db = visgrab::database::Database::open(options.out);
  ASSERT_EQ(db.list().size(), 4u);
  EXPECT_FALSE(db.catalog().isBenchmark());
  EXPECT_EQ(db.catalog().name(102), "rwjam");
  EXPECT_EQ(db.list()[0].id, "plain/single/rwcup/01");
  EXPECT_EQ(db.filter(visgrab::database::SceneFilter::parse("*/rwjam/*")).size(), 2u);
  EXPECT_NE(visgrab::database::Database::summaryLine(db.list()[0], db.catalog())
                .find("object 101 rwcup, pose 1"),
            std::string::npos);

  // Settled: on the table (lowest point within 2 mm of its top), standing upright or lying.
  std::map<int, visgrab::objects::ObjectModel> models;
  for (const int id : {101, 102}) {
    models.emplace(id, visgrab::objects::generateObject(*spec.findObject(id)));
  }
  for (const auto& entry : db.list()) {
    const auto& model = models.at(entry.conditions->objects[0]);
    const auto& X = entry.groundTruth.at(0).X_WO;
    EXPECT_NEAR(lowestPoint(model, X), 0.0, 0.002) << entry.id;
    const double zUp = X.linear()(2, 2);  // the object's z axis, vertical component
    if (entry.conditions->arrangement() == visgrab::database::Arrangement::kStanding) {
      EXPECT_GT(zUp, 0.95) << entry.id;
    } else {
      EXPECT_LT(std::abs(zUp), 0.5) << entry.id;
    }
    EXPECT_TRUE(fs::exists(entry.leftImage)) << entry.id;
  }
  // The object files of the mesh objects, with what was done to the meshes noted.
  std::string example;
  ASSERT_TRUE(rw::common::readTextFile(options.out / "objects" / "rwcup" / "rwcup.wc.xml", example)
                  .empty());
  EXPECT_NE(example.find("filled 2 holes bounded by 6 open edges"), std::string::npos) << example;
  EXPECT_NE(example.find("automatic convex decomposition"), std::string::npos) << example;
}

}  // namespace
