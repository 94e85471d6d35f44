#include "visgrab/database/database_index.hpp"

#include <gtest/gtest.h>

#include <string>

#include "rw/common/diagnostic.hpp"
#include "rw/math/rpy.hpp"
#include "support/test_support.hpp"

namespace visgrab::database {
namespace {

using rw::common::LoadError;

DatabaseIndex sampleIndex() {
  DatabaseIndex index;
  index.seed = 18446744073709551615ull;
  index.generator = "visgrab test <&>";
  const auto single = SceneConditions::single(Texture::kTextured, 5, 3);
  const auto pair = SceneConditions::pairScene(Texture::kPlain, 'e', 6);
  SceneRecord b{sceneIdOf(single), single, defaultSceneFiles(sceneIdOf(single)), {}};
  b.objects.push_back({5, rw::math::rpyTransform(Eigen::Vector3d(0.3, -0.2, 1.1),
                                                 Eigen::Vector3d(0.1, -0.02, 0.06))});
  SceneRecord a{sceneIdOf(pair), pair, defaultSceneFiles(sceneIdOf(pair)), {}};
  a.objects.push_back({5, rw::math::rpyTransform(Eigen::Vector3d(0.1, 1.5707, 0),
                                                 Eigen::Vector3d(-0.1, 0.05, 0.0333333333333))});
  a.objects.push_back({14, rw::math::rpyTransform(Eigen::Vector3d(-2.5, 0, 0.01),
                                                  Eigen::Vector3d(0.1 / 3, 1e-17, 0.04))});
  // Out of order on purpose: the writer sorts into enumerateScenes() order.
  index.scenes = {b, a};
  return index;
}

std::string errorOf(const std::string& text) {
  try {
    parseIndex(text, "db/index.xml");
  } catch (const LoadError& e) {
    EXPECT_EQ(e.diagnostics().size(), 1u) << e.what();
    return e.diagnostics().empty() ? "" : e.diagnostics()[0].format();
  }
  return "no error";
}

// A valid index with one scene; `scene` replaces the scene's attributes/children when given.
std::string indexText(const std::string& sceneAttributes, const std::string& body,
                      const std::string& rootAttributes = "formatVersion=\"1\" seed=\"7\"") {
  return "<?xml version=\"1.0\"?>\n"
         "<VisGraBDatabase " +
         rootAttributes +
         ">\n"
         "  <Scene " +
         sceneAttributes + ">\n" + body +
         "  </Scene>\n"
         "</VisGraBDatabase>\n";
}

const std::string kScene =
    "id=\"textured/single/cocacola/03\" texture=\"textured\" kind=\"single\" "
    "arrangement=\"standing\" pose=\"3\"";
const std::string kFiles =
    "    <Files left=\"l.png\" right=\"r.png\" calibration=\"c.yml\" workcell=\"s.wc.xml\" "
    "dynamicWorkcell=\"s.dwc.xml\"/>\n";
const std::string kObject =
    "    <Object id=\"5\" name=\"cocacola\">\n"
    "      <Pos>0 0 0.06</Pos>\n"
    "      <RPY>90 0 0</RPY>\n"
    "    </Object>\n";

TEST(DatabaseIndexTest, WriteReadRoundTrip) {
  const DatabaseIndex original = sampleIndex();
  const std::string text = indexToXml(original);
  const DatabaseIndex read = parseIndex(text, "index.xml");
  EXPECT_EQ(read.formatVersion, kIndexFormatVersion);
  EXPECT_EQ(read.seed, original.seed);
  EXPECT_EQ(read.generator, original.generator);
  ASSERT_EQ(read.scenes.size(), 2u);
  // Sorted: plain before textured.
  EXPECT_EQ(read.scenes[0].id, "plain/double/cocacola_saltcylinder/06");
  EXPECT_EQ(read.scenes[1].id, "textured/single/cocacola/03");
  for (const SceneRecord& r : read.scenes) {
    const SceneRecord& o = r.id == original.scenes[0].id ? original.scenes[0] : original.scenes[1];
    EXPECT_EQ(r.conditions, o.conditions);
    EXPECT_EQ(r.files, o.files);
    ASSERT_EQ(r.objects.size(), o.objects.size());
    for (std::size_t i = 0; i < r.objects.size(); ++i) {
      EXPECT_EQ(r.objects[i].object, o.objects[i].object);
      // Written at 1 nm and 1e-9 degree.
      EXPECT_TRANSFORM_NEAR(r.objects[i].X_WO, o.objects[i].X_WO, 1e-9);
    }
  }
  // Writing what was read gives the same text again (a resumed generation rewrites the index).
  EXPECT_EQ(indexToXml(read), indexToXml(parseIndex(indexToXml(read), "index.xml")));
  EXPECT_EQ(indexToXml(read), indexToXml(original));
}

TEST(DatabaseIndexTest, FileRoundTripIsAtomic) {
  test::TempDir dir;
  const auto file = dir.path() / "index.xml";
  writeIndex(file, sampleIndex());
  const DatabaseIndex read = readIndex(file);
  EXPECT_EQ(read.scenes.size(), 2u);
  // No temporary file is left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(DatabaseIndexTest, AcceptsAHandWrittenIndex) {
  const auto index = parseIndex(indexText(kScene, kFiles + kObject), "i.xml");
  ASSERT_EQ(index.scenes.size(), 1u);
  EXPECT_EQ(index.seed, 7u);
  EXPECT_EQ(index.scenes[0].files.calibration, "c.yml");
  EXPECT_TRANSFORM_NEAR(index.scenes[0].objects[0].X_WO,
                        rw::math::rpyTransform(Eigen::Vector3d(std::numbers::pi / 2, 0, 0),
                                               Eigen::Vector3d(0, 0, 0.06)),
                        1e-12);
}

TEST(DatabaseIndexTest, Version1IsReadWithoutTheNewFilesAndRewrittenAsVersion2) {
  const auto index = parseIndex(indexText(kScene, kFiles + kObject), "i.xml");
  EXPECT_EQ(index.formatVersion, 1);
  ASSERT_EQ(index.scenes.size(), 1u);
  const SceneFiles& f = index.scenes[0].files;
  EXPECT_EQ(f.left, "l.png");
  EXPECT_EQ(f.dynamicWorkcell, "s.dwc.xml");
  for (const std::string* empty :
       {&f.rawLeft, &f.rawRight, &f.disparity, &f.pointCloud, &f.depth, &f.mask, &f.poses}) {
    EXPECT_EQ(*empty, "");
  }
  const std::string rewritten = indexToXml(index);
  EXPECT_NE(rewritten.find("formatVersion=\"2\""), std::string::npos) << rewritten;
  EXPECT_EQ(rewritten.find("rawLeft"), std::string::npos) << rewritten;
  EXPECT_EQ(parseIndex(rewritten, "i.xml").scenes[0].files, f);
}

TEST(DatabaseIndexTest, Version2NamesEveryFileAndMayLeaveTheNewOnesOut) {
  const std::string files =
      "    <Files left=\"l.png\" right=\"r.png\" calibration=\"c.yml\" workcell=\"s.wc.xml\" "
      "dynamicWorkcell=\"s.dwc.xml\" disparity=\"d.png\" pointCloud=\"p.ply\" depth=\"z.png\" "
      "mask=\"m.png\" poses=\"o.yml\"/>\n";
  const auto index =
      parseIndex(indexText(kScene, files + kObject, "formatVersion=\"2\" seed=\"7\""), "i.xml");
  ASSERT_EQ(index.scenes.size(), 1u);
  const SceneFiles& f = index.scenes[0].files;
  EXPECT_EQ(f.rawLeft, "");  // no raw pair
  EXPECT_EQ(f.rawRight, "");
  EXPECT_EQ(f.disparity, "d.png");
  EXPECT_EQ(f.pointCloud, "p.ply");
  EXPECT_EQ(f.depth, "z.png");
  EXPECT_EQ(f.mask, "m.png");
  EXPECT_EQ(f.poses, "o.yml");
  // Round trip: the absent ones stay absent, the others keep their paths.
  const std::string text = indexToXml(index);
  EXPECT_EQ(text.find("rawLeft"), std::string::npos) << text;
  EXPECT_EQ(parseIndex(text, "i.xml").scenes[0].files, f);
  // defaultSceneFiles names all twelve in the scene's folder.
  const SceneFiles d = defaultSceneFiles("plain/single/corny/07");
  EXPECT_EQ(d.rawLeft, "scenes/plain/single/corny/07/raw_left.png");
  EXPECT_EQ(d.rawRight, "scenes/plain/single/corny/07/raw_right.png");
  EXPECT_EQ(d.disparity, "scenes/plain/single/corny/07/disparity.png");
  EXPECT_EQ(d.pointCloud, "scenes/plain/single/corny/07/cloud.ply");
  EXPECT_EQ(d.depth, "scenes/plain/single/corny/07/depth.png");
  EXPECT_EQ(d.mask, "scenes/plain/single/corny/07/mask.png");
  EXPECT_EQ(d.poses, "scenes/plain/single/corny/07/poses.yml");
  EXPECT_EQ(sceneFileFields().size(), 12u);
}

TEST(DatabaseIndexTest, NewFilesAreCheckedAndBelongToVersion2) {
  const std::string v1WithDepth =
      "    <Files left=\"l.png\" right=\"r.png\" calibration=\"c.yml\" workcell=\"s.wc.xml\" "
      "dynamicWorkcell=\"s.dwc.xml\" depth=\"z.png\"/>\n";
  EXPECT_EQ(errorOf(indexText(kScene, v1WithDepth + kObject)),
            "db/index.xml:4:5: error: <Files>: depth needs index format version 2 (this index "
            "says version 1)");
  const std::string badCloud =
      "    <Files left=\"l.png\" right=\"r.png\" calibration=\"c.yml\" workcell=\"s.wc.xml\" "
      "dynamicWorkcell=\"s.dwc.xml\" pointCloud=\"../p.ply\"/>\n";
  EXPECT_EQ(errorOf(indexText(kScene, badCloud + kObject, "formatVersion=\"2\" seed=\"7\"")),
            "db/index.xml:4:5: error: <Files>: pointCloud=\"../p.ply\": the path must not contain "
            "\"..\"");
  DatabaseIndex index = sampleIndex();
  index.scenes[0].files.mask = "/abs/mask.png";
  EXPECT_THROW(indexToXml(index), std::invalid_argument);
}

TEST(DatabaseIndexTest, MalformedIndexesGiveOneErrorWithFileAndLine) {
  EXPECT_EQ(errorOf(""),
            "db/index.xml: error: no <VisGraBDatabase> element: not a VisGraB "
            "database index");
  EXPECT_EQ(errorOf("<VisGraBDatabase formatVersion=\"1\" seed=\"1\">\n  <Scene>\n"),
            "db/index.xml:2:3: error: <Scene>: missing required attribute \"id\"");
  EXPECT_EQ(errorOf("<VisGraBDatabase formatVersion=\"1\" seed=\"1\">\n</Scenes>\n"),
            "db/index.xml:2:3: error: not well-formed XML: expected end of tag 'VisGraBDatabase' "
            "(opened at line 1)");
  // Schema: unknown element, missing attribute, bad enumeration, pose out of range.
  EXPECT_EQ(errorOf(indexText(kScene, kFiles + kObject + "    <Extra/>\n")),
            "db/index.xml:9:5: error: unknown element <Extra> in <Scene id=\"textured/single/"
            "cocacola/03\">");
  EXPECT_EQ(errorOf(indexText(kScene, kFiles + kObject, "seed=\"7\"")),
            "db/index.xml:2:1: error: <VisGraBDatabase>: missing required attribute "
            "\"formatVersion\"");
  EXPECT_NE(errorOf(indexText(kScene + " ", kFiles + kObject, "formatVersion=\"1\" seed=\"-1\""))
                .find("db/index.xml:2:1: error: <VisGraBDatabase>"),
            std::string::npos);
  // Meaning: version, id, conditions, duplicates, objects, numbers, paths.
  EXPECT_EQ(errorOf(indexText(kScene, kFiles + kObject, "formatVersion=\"3\" seed=\"7\"")),
            "db/index.xml:2:1: error: index format version 3 is not supported (this program "
            "reads versions 1 to 2)");
  EXPECT_EQ(
      errorOf(indexText("id=\"textured/single/pepsi/03\" texture=\"textured\" kind=\"single\" "
                        "arrangement=\"standing\" pose=\"3\"",
                        kFiles + kObject)),
      "db/index.xml:3:3: error: <Scene id=\"textured/single/pepsi/03\">: \"textured/single/pepsi/"
      "03\" is not a scene id (expected <plain|textured>/<single|double>/<object or pair>/"
      "<01..08>, e.g. textured/single/cocacola/03)");
  EXPECT_EQ(
      errorOf(indexText("id=\"textured/single/cocacola/03\" texture=\"textured\" kind=\"single\" "
                        "arrangement=\"lying\" pose=\"3\"",
                        kFiles + kObject)),
      "db/index.xml:3:3: error: <Scene id=\"textured/single/cocacola/03\">: arrangement=\"lying\" "
      "contradicts the id, which means arrangement=\"standing\"");
  EXPECT_EQ(errorOf("<VisGraBDatabase formatVersion=\"1\" seed=\"7\">\n  <Scene " + kScene + ">\n" +
                    kFiles + kObject + "  </Scene>\n  <Scene " + kScene + ">\n" + kFiles + kObject +
                    "  </Scene>\n</VisGraBDatabase>\n"),
            "db/index.xml:9:3: error: duplicate scene id \"textured/single/cocacola/03\" (first at "
            "line 2)");
  EXPECT_EQ(
      errorOf(indexText(kScene, kFiles + "    <Object id=\"6\" name=\"corny\">\n      <Pos>0 0 "
                                         "0</Pos>\n      <RPY>0 0 0</RPY>\n    </Object>\n")),
      "db/index.xml:3:3: error: <Scene id=\"textured/single/cocacola/03\">: the <Object> ids "
      "must be 5 (in this order) for this scene");
  EXPECT_EQ(
      errorOf(indexText(kScene, kFiles + "    <Object id=\"5\" name=\"pepsi\">\n      <Pos>0 0 "
                                         "0</Pos>\n      <RPY>0 0 0</RPY>\n    </Object>\n")),
      "db/index.xml:5:5: error: <Object name=\"pepsi\">: object 5 is called \"cocacola\", not "
      "\"pepsi\"");
  EXPECT_EQ(
      errorOf(indexText(kScene, kFiles + "    <Object id=\"5\" name=\"cocacola\">\n      <Pos>0 "
                                         "NaN 0</Pos>\n      <RPY>0 0 0</RPY>\n    </Object>\n")),
      "db/index.xml:6:7: error: <Pos>: \"NaN\" is not a finite number");
  EXPECT_EQ(errorOf(indexText(kScene,
                              "    <Files left=\"../l.png\" right=\"r.png\" calibration=\"c.yml\" "
                              "workcell=\"s.wc.xml\" dynamicWorkcell=\"s.dwc.xml\"/>\n" +
                                  kObject)),
            "db/index.xml:4:5: error: <Files>: left=\"../l.png\": the path must not contain "
            "\"..\"");
  EXPECT_EQ(
      errorOf(indexText(kScene,
                        "    <Files left=\"l.png\" right=\"/abs/r.png\" calibration=\"c.yml\" "
                        "workcell=\"s.wc.xml\" dynamicWorkcell=\"s.dwc.xml\"/>\n" +
                            kObject)),
      "db/index.xml:4:5: error: <Files>: right=\"/abs/r.png\": the path must be relative to "
      "the database folder");
}

// Schema errors say what is wrong (issue 20): missing, out of order, given twice, misspelt.
TEST(DatabaseIndexTest, SchemaErrorsSayWhatIsWrong) {
  EXPECT_EQ(errorOf(indexText(kScene, kFiles + "    <Object id=\"5\" name=\"cocacola\">\n"
                                               "      <RPY>90 0 0</RPY>\n    </Object>\n")),
            "db/index.xml:6:7: error: missing <Pos> (required before <RPY>)");
  EXPECT_EQ(errorOf(indexText(kScene, kFiles + "    <Object id=\"5\" name=\"cocacola\">\n"
                                               "      <RPY>90 0 0</RPY>\n      <Pos>0 0 "
                                               "0.06</Pos>\n    </Object>\n")),
            "db/index.xml:6:7: error: <RPY> is out of order: it must come after <Pos>");
  EXPECT_EQ(errorOf(indexText(kScene, kObject + kFiles)),
            "db/index.xml:4:5: error: <Object> is out of order: it must come after <Files>");
  EXPECT_EQ(errorOf(indexText(kScene, kObject)),
            "db/index.xml:4:5: error: missing <Files> (required before <Object>)");
  EXPECT_EQ(errorOf(indexText(kScene, kFiles + kFiles + kObject)),
            "db/index.xml:5:5: error: <Files> is given twice; <Scene "
            "id=\"textured/single/cocacola/03\"> allows only one (the first is at line 4)");
  EXPECT_EQ(errorOf(indexText(kScene, kFiles)),
            "db/index.xml:3:3: error: missing <Object> (required after <Files>)");
  std::string misspelt = kObject;
  misspelt.replace(misspelt.find("<Pos>"), 5, "<Poss>");
  misspelt.replace(misspelt.find("</Pos>"), 6, "</Poss>");
  EXPECT_EQ(errorOf(indexText(kScene, kFiles + misspelt)),
            "db/index.xml:6:7: error: unknown element <Poss> in <Object name=\"cocacola\">; did "
            "you mean <Pos>?");
}

TEST(DatabaseIndexTest, MissingFileIsAnError) {
  test::TempDir dir;
  try {
    readIndex(dir.path() / "index.xml");
    FAIL() << "no error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("index.xml: error: cannot read the database index: "),
              std::string::npos)
        << e.what();
  }
}

TEST(DatabaseIndexTest, WriterRejectsInvalidRecords) {
  DatabaseIndex index = sampleIndex();
  index.scenes[0].id = "textured/single/cocacola/04";
  EXPECT_THROW(indexToXml(index), std::invalid_argument);
  index = sampleIndex();
  index.scenes[0].files.left = "../x.png";
  EXPECT_THROW(indexToXml(index), std::invalid_argument);
  index = sampleIndex();
  index.scenes[0].objects.clear();
  EXPECT_THROW(indexToXml(index), std::invalid_argument);
}

}  // namespace
}  // namespace visgrab::database
