#include "visgrab/database/original_manifest.hpp"

#include <gtest/gtest.h>

#include <string>

#include "visgrab/database/database.hpp"

namespace visgrab::database {
namespace {

using rw::common::LoadError;
namespace fs = std::filesystem;

const fs::path kManifest = "/data/visgrab/benchmark.xml";

std::string scene(const std::string& id, const std::string& locator, const std::string& set,
                  const std::string& texture, const std::string& prefix = "") {
  const std::string p = prefix;
  return "    <" + p + "scene id=\"" + id + "\">\n" + "      <" + p + "info><" + p +
         "sceneLocator>" + locator + "</" + p + "sceneLocator><" + p + "sceneSet>" + set + "</" +
         p + "sceneSet><" + p + "sceneSetID>7</" + p + "sceneSetID><" + p + "textureCondition>" +
         texture + "</" + p + "textureCondition></" + p + "info>\n" + "      <" + p + "input><" +
         p + "leftImg>img/" + id + "_L.png</" + p + "leftImg><" + p + "rightImg>img/" + id +
         "_R.png</" + p + "rightImg><" + p + "disp>d.png</" + p + "disp><" + p +
         "pointCloud>pc.pcd</" + p + "pointCloud></" + p + "input>\n" + "      <" + p +
         "simulator><" + p + "wc>sim/" + id + ".wc.xml</" + p + "wc><" + p + "dwc>sim/" + id +
         ".dwc.xml</" + p + "dwc><" + p + "collision>c.stl</" + p + "collision></" + p +
         "simulator>\n" + "    </" + p + "scene>\n";
}

std::string manifest(const std::string& scenes, const std::string& type = "GraspUnknownObject") {
  return "<?xml version=\"1.0\"?>\n<visgrab>\n  <benchmark type=\"" + type + "\">\n" + scenes +
         "  </benchmark>\n</visgrab>\n";
}

std::string errorOf(const std::string& text) {
  try {
    parseOriginalManifest(text, kManifest);
  } catch (const LoadError& e) {
    EXPECT_EQ(e.diagnostics().size(), 1u) << e.what();
    return e.diagnostics()[0].format();
  }
  return "no error";
}

TEST(OriginalManifestTest, ReadsScenesAndResolvesPathsAgainstTheManifestFolder) {
  const auto m = parseOriginalManifest(
      manifest(scene("cocacola_03", "textured/cocacola/img_03", "single", "textured")), kManifest);
  ASSERT_EQ(m.scenes.size(), 1u);
  const OriginalScene& s = m.scenes[0];
  EXPECT_EQ(m.directory, "/data/visgrab");
  EXPECT_EQ(s.id, "cocacola_03");
  EXPECT_EQ(s.line, 4);
  EXPECT_EQ(s.sceneSetId, "7");
  EXPECT_EQ(s.leftImage, "/data/visgrab/img/cocacola_03_L.png");
  EXPECT_EQ(s.rightImage, "/data/visgrab/img/cocacola_03_R.png");
  EXPECT_EQ(s.workcell, "/data/visgrab/sim/cocacola_03.wc.xml");
  EXPECT_EQ(s.dynamicWorkcell, "/data/visgrab/sim/cocacola_03.dwc.xml");
  EXPECT_EQ(s.collision, "/data/visgrab/c.stl");
  EXPECT_EQ(deriveConditions(s), SceneConditions::single(Texture::kTextured, 5, 3));
  EXPECT_TRUE(m.warnings.empty());
}

TEST(OriginalManifestTest, NamespacePrefixesAreIgnored) {
  // Declared prefix on every element, undeclared prefix on the root, prefixed attribute.
  const std::string declared =
      "<x:visgrab xmlns:vg=\"urn:a\">\n  <vg:benchmark vg:type=\"GraspUnknownObject\">\n" +
      scene("a", "textured/pure/img_01", "single", "textured", "vg:") +
      "  </vg:benchmark>\n</x:visgrab>\n";
  const auto m = parseOriginalManifest(declared, kManifest);
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].leftImage, "/data/visgrab/img/a_L.png");
  const std::string attribute = manifest("    <scene foo:id=\"b\">" +
                                         scene("x", "textured/pure/img_01", "single", "textured")
                                             .substr(std::string("    <scene id=\"x\">").size()));
  EXPECT_EQ(parseOriginalManifest(attribute, kManifest).scenes.at(0).id, "b");
}

TEST(OriginalManifestTest, FirstChildWinsAndUnknownElementsAreIgnoredWithWarnings) {
  std::string text = manifest("    <notes>ignored</notes>\n" +
                              scene("s", "textured/pure/img_01", "single", "textured"));
  // A second <leftImg> in <input>: the first one is used.
  const std::string first = "<leftImg>img/s_L.png</leftImg>";
  text.replace(text.find(first), first.size(), first + "<leftImg>other.png</leftImg><extra/>");
  const auto m = parseOriginalManifest(text, kManifest);
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].leftImage, "/data/visgrab/img/s_L.png");
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_EQ(m.warnings[0].format(),
            "/data/visgrab/benchmark.xml:4:5: warning: <notes> in <benchmark> ignored");
  EXPECT_EQ(m.warnings[1].format(),
            "/data/visgrab/benchmark.xml:7:72: warning: <extra> in <input> ignored");
}

TEST(OriginalManifestTest, OnlyTheFirstBenchmarkIsUsed) {
  const std::string text = "<visgrab>\n  <benchmark type=\"GraspUnknownObject\">\n" +
                           scene("one", "textured/pure/img_01", "single", "textured") +
                           "  </benchmark>\n  <benchmark type=\"Other\">\n" +
                           scene("two", "textured/pure/img_02", "single", "textured") +
                           "  </benchmark>\n</visgrab>\n";
  const auto m = parseOriginalManifest(text, kManifest);
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].id, "one");
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0].format(),
            "/data/visgrab/benchmark.xml:9:3: warning: second <benchmark> ignored (only the first "
            "is used)");
}

TEST(OriginalManifestTest, DuplicateIdsLastWins) {
  const std::string text = manifest(scene("dup", "textured/pure/img_01", "single", "textured") +
                                    scene("other", "textured/pure/img_02", "single", "textured") +
                                    scene("dup", "textured/pure/img_05", "single", "textured"));
  const auto m = parseOriginalManifest(text, kManifest);
  EXPECT_EQ(m.scenes.size(), 3u);  // both are stored, as in the original
  ASSERT_NE(m.find("dup"), nullptr);
  EXPECT_EQ(m.find("dup")->line, 14);
  EXPECT_EQ(m.find("nope"), nullptr);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0].format(),
            "/data/visgrab/benchmark.xml:14:5: warning: duplicate scene id \"dup\" (also at line "
            "4); this later one is used");
  const Database db = Database::openOriginalManifestText(text, kManifest);
  ASSERT_EQ(db.list().size(), 2u);
  EXPECT_EQ(db.list()[0].id, "other");
  EXPECT_EQ(db.scene("dup").conditions->pose, 5);
}

TEST(OriginalManifestTest, WhitespaceIsTrimmed) {
  std::string text = manifest(scene("s", "textured/pure/img_01", "single", "textured"));
  text.replace(text.find("<wc>"), 4, "<wc>\n   ");
  text.replace(text.find("id=\"s\""), 6, "id=\" s \"");
  const auto m = parseOriginalManifest(text, kManifest);
  EXPECT_EQ(m.scenes.at(0).id, "s");
  EXPECT_EQ(m.scenes.at(0).workcell, "/data/visgrab/sim/s.wc.xml");
}

TEST(OriginalManifestTest, CollisionIsOptional) {
  std::string text = manifest(scene("s", "textured/pure/img_01", "single", "textured"));
  const std::string collision = "<collision>c.stl</collision>";
  text.erase(text.find(collision), collision.size());
  EXPECT_TRUE(parseOriginalManifest(text, kManifest).scenes.at(0).collision.empty());
}

TEST(OriginalManifestTest, ErrorsFailTheWholeFile) {
  EXPECT_EQ(errorOf("<visgrab/>"),
            "/data/visgrab/benchmark.xml:1:1: error: <visgrab> has no <benchmark> element");
  EXPECT_EQ(errorOf("<grasps/>"),
            "/data/visgrab/benchmark.xml:1:1: error: the root element is <grasps>; a VisGraB "
            "manifest starts with <visgrab>");
  EXPECT_EQ(errorOf(manifest("", "GraspKnownObject")),
            "/data/visgrab/benchmark.xml:3:3: error: <benchmark>: unknown benchmark type "
            "\"GraspKnownObject\" (expected GraspUnknownObject)");
  EXPECT_EQ(errorOf("<visgrab><benchmark/></visgrab>"),
            "/data/visgrab/benchmark.xml:1:10: error: <benchmark>: missing required attribute "
            "\"type\"");
  std::string noDwc = manifest(scene("a", "textured/pure/img_01", "single", "textured") +
                               scene("b", "textured/pure/img_02", "single", "textured"));
  const std::string dwc = "<dwc>sim/b.dwc.xml</dwc>";
  noDwc.erase(noDwc.find(dwc), dwc.size());
  EXPECT_EQ(errorOf(noDwc),
            "/data/visgrab/benchmark.xml:12:7: error: <scene id=\"b\">: missing "
            "<simulator>/<dwc>");
  EXPECT_EQ(errorOf(manifest("    <scene>\n    </scene>\n")),
            "/data/visgrab/benchmark.xml:4:5: error: <scene>: missing required attribute \"id\"");
  EXPECT_EQ(errorOf("<visgrab><benchmark type=\"GraspUnknownObject\">"),
            "/data/visgrab/benchmark.xml:1:47: error: not well-formed XML: expected end of tag "
            "'benchmark' (opened at line 1)");
}

TEST(OriginalManifestTest, ConditionsAreDerivedFromLocatorIdAndTexture) {
  OriginalScene s;
  s.sceneLocator = "/x/non-textured/cocacola_saltcylinder/img_06";
  EXPECT_EQ(deriveConditions(s), SceneConditions::pairScene(Texture::kPlain, 'e', 6));
  s = OriginalScene{};
  s.id = "bottle_flat_03";  // the formats document's invented example: no known object
  s.sceneLocator = "objects/bottle/flat/03";
  s.textureCondition = "textured";
  EXPECT_FALSE(deriveConditions(s));
  s.id = "cocacola_flat_03";
  s.sceneLocator = "objects/cocacola/flat/03";
  s.sceneSet = "single";
  EXPECT_EQ(deriveConditions(s), SceneConditions::single(Texture::kTextured, 5, 3));
  s.sceneSet = "double";  // disagrees
  EXPECT_FALSE(deriveConditions(s));
  s = OriginalScene{};
  s.id = "whitecup-amicelli-07";
  s.textureCondition = "non-textured";
  EXPECT_EQ(deriveConditions(s), SceneConditions::pairScene(Texture::kPlain, 'a', 7));
  s.textureCondition = "";  // texture unknown
  EXPECT_FALSE(deriveConditions(s));
  s = OriginalScene{};
  s.id = "textured/single/pure/02";  // one of our ids
  EXPECT_EQ(deriveConditions(s), SceneConditions::single(Texture::kTextured, 12, 2));
}

TEST(OriginalManifestTest, DatabaseOverTheManifest) {
  const std::string text =
      manifest(scene("cola3", "textured/cocacola/img_03", "single", "textured") +
               scene("bottle_flat_03", "objects/bottle/flat/03", "single", "textured"));
  const Database db = Database::openOriginalManifestText(text, kManifest);
  EXPECT_EQ(db.source(), Database::Source::kOriginalManifest);
  ASSERT_EQ(db.list().size(), 2u);
  EXPECT_FALSE(db.list()[1].conditions);
  EXPECT_EQ(db.filter(SceneFilter::parse("textured")).size(), 1u);
  EXPECT_EQ(db.filter(SceneFilter::parse("id=bottle*")).size(), 1u);
  // Our id finds the original scene too.
  EXPECT_EQ(db.scene("textured/single/cocacola/03").id, "cola3");
  EXPECT_EQ(db.scene("cola3").leftImage, "/data/visgrab/img/cola3_L.png");
  try {
    db.calibration("cola3");
    FAIL();
  } catch (const DatabaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene cola3: no calibration file is known (the original manifest names none)");
  }
  EXPECT_EQ(Database::summaryLine(db.list()[1]).substr(44), "  (conditions unknown)");
}

}  // namespace
}  // namespace visgrab::database
