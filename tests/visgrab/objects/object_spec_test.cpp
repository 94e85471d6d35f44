#include <gtest/gtest.h>

#include <set>
#include <string>

#include "objects_test_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace {

using rw::common::Diagnostic;
using rw::common::LoadError;
using visgrab::objects::loadObjectSpecsFromString;
using visgrab::objects::PatternKind;
using visgrab::objects::ShapeKind;
using visgrab::test::objects::projectSpec;

TEST(ObjectSpec, ProjectFileHasThe18ObjectsOfThePaper) {
  const auto& spec = projectSpec();
  const std::vector<std::string> names = {
      "amicelli", "breadbox",     "burti",     "cleaningbottle", "cocacola", "corny",
      "denkmit",  "greencup",     "icecoffee", "marmelade",      "peachcan", "pure",
      "saltbox",  "saltcylinder", "sucker",    "tomato",         "waterjug", "whitecup"};
  ASSERT_EQ(spec.objects.size(), 18u);
  for (int id = 1; id <= 18; ++id) {
    const auto* o = spec.findObject(id);
    ASSERT_NE(o, nullptr) << id;
    EXPECT_EQ(o->name, names[id - 1]) << id;
    EXPECT_GT(o->mass, 0.0);
  }
  // The paper's pairs a..i.
  const std::vector<std::pair<int, int>> pairs = {{1, 18}, {2, 11}, {3, 7},   {4, 15}, {5, 14},
                                                  {6, 8},  {9, 13}, {10, 12}, {16, 17}};
  std::set<int> inPairs;
  for (const auto& [a, b] : pairs) {
    EXPECT_NE(spec.findObject(a), nullptr) << a;
    EXPECT_NE(spec.findObject(b), nullptr) << b;
    inPairs.insert(a);
    inPairs.insert(b);
  }
  EXPECT_EQ(inPairs.size(), 18u);  // every object is in exactly one pair
  ASSERT_NE(spec.findTable("plain"), nullptr);
  ASSERT_NE(spec.findTable("textured"), nullptr);
  EXPECT_NEAR(spec.findTable("plain")->x, 1.2, 1e-12);
  EXPECT_NEAR(spec.findTable("plain")->y, 0.8, 1e-12);
}

TEST(ObjectSpec, ProjectObjectsFitTheSdh) {
  // The SDH opens about 0.14 m between opposing fingertips: every object must offer a
  // horizontal width below that when standing.
  for (const auto& o : projectSpec().objects) {
    const double width =
        o.kind == ShapeKind::kBox ? std::min(o.boxSize.x(), o.boxSize.y()) : 2.0 * o.maxRadius();
    EXPECT_LE(width, 0.14) << o.name;
    EXPECT_GE(o.height(), 0.05) << o.name;
    EXPECT_LE(o.height(), 0.25) << o.name;
  }
}

TEST(ObjectSpec, ReadsShapesAndAppearance) {
  const auto spec = loadObjectSpecsFromString(R"(<ObjectDatabase>
  <Table name="t" x="1" y="0.5" pattern="cluttered" rgb="0.1 0.2 0.3" seed="7"/>
  <Object id="3" name="jar" mass="0.5" product="a jar">
    <Lathe><Point z="0" r="0.03"/><Point z="0.1" r="0.035"/><Point z="0.12" r="0.03"/></Lathe>
    <Handle z="0.05" span="0.04" reach="0.03" thickness="0.01"/>
    <Appearance pattern="label-band" seed="9" body="0.5 0.4 0.3" bodyMaterial="glass"
                labelBottom="0.02" labelTop="0.08" lidBottom="0.1" lid="0.2 0.2 0.2"
                lidMaterial="metal" specular="0.3">
      <Colour rgb="1 0 0"/><Colour rgb="0 0 1"/>
    </Appearance>
  </Object>
</ObjectDatabase>)",
                                              "inline.xml");
  ASSERT_EQ(spec.objects.size(), 1u);
  const auto& o = spec.objects[0];
  EXPECT_EQ(o.kind, ShapeKind::kLathe);
  EXPECT_EQ(o.line, 3);
  ASSERT_EQ(o.profile.size(), 3u);
  EXPECT_DOUBLE_EQ(o.profile[1].r, 0.035);
  ASSERT_TRUE(o.handle.has_value());
  EXPECT_DOUBLE_EQ(o.handle->reach, 0.03);
  EXPECT_EQ(o.appearance.pattern, PatternKind::kLabelBand);
  EXPECT_EQ(o.appearance.seed, 9u);
  EXPECT_EQ(o.appearance.palette.size(), 2u);
  ASSERT_TRUE(o.appearance.label.has_value());
  EXPECT_DOUBLE_EQ((*o.appearance.label)[1], 0.08);
  EXPECT_DOUBLE_EQ(*o.appearance.lidBottom, 0.1);
  EXPECT_EQ(o.appearance.lidMaterial, visgrab::objects::SurfaceMaterial::kMetal);
  EXPECT_EQ(o.appearance.bodyMaterial, visgrab::objects::SurfaceMaterial::kGlass);
  EXPECT_NEAR(o.radiusAt(0.05), 0.0325, 1e-12);
  ASSERT_EQ(spec.tables.size(), 1u);
  EXPECT_EQ(spec.tables[0].pattern, visgrab::objects::TablePattern::kCluttered);
  EXPECT_EQ(spec.tables[0].seed, 7u);
}

TEST(ObjectSpec, PatternNamesRoundTrip) {
  for (auto k : {PatternKind::kPrintedBox, PatternKind::kLabelBand, PatternKind::kMetalCan,
                 PatternKind::kPlainPlastic}) {
    EXPECT_EQ(visgrab::objects::patternKindFromName(visgrab::objects::patternKindName(k)), k);
  }
  EXPECT_FALSE(visgrab::objects::patternKindFromName("zebra").has_value());
}

// One malformed document: the line the error must name and a part of its message.
struct BadSpec {
  const char* what;
  std::string xml;
  int line;
  std::string message;
};

const std::string kAppearance =
    R"(<Appearance pattern="printed-box" seed="1" body="0.5 0.5 0.5"><Colour rgb="1 0 0"/><Colour rgb="0 1 0"/></Appearance>)";

std::string box(const std::string& boxElement, const std::string& appearance = kAppearance) {
  return "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n" + boxElement + "\n" +
         appearance + "\n</Object>\n</ObjectDatabase>\n";
}

std::string lathe(const std::string& points, const std::string& extra = "") {
  return "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n<Lathe>\n" + points +
         "</Lathe>\n" + extra +
         "<Appearance pattern=\"plain-plastic\" seed=\"1\" body=\"0.5 0.5 0.5\"/>\n"
         "</Object>\n</ObjectDatabase>\n";
}

class MalformedSpec : public ::testing::TestWithParam<BadSpec> {};

TEST_P(MalformedSpec, GivesExactlyOneErrorAtTheLine) {
  const BadSpec& bad = GetParam();
  try {
    loadObjectSpecsFromString(bad.xml, "specs/bad_objects.xml");
    FAIL() << bad.what << ": no error";
  } catch (const LoadError& e) {
    int errors = 0;
    for (const Diagnostic& d : e.diagnostics()) {
      if (d.severity != Diagnostic::Severity::kError) continue;
      ++errors;
      EXPECT_EQ(d.file, "specs/bad_objects.xml") << bad.what;
      EXPECT_EQ(d.line, bad.line) << bad.what << ": " << d.format();
      EXPECT_GT(d.column, 0) << bad.what;
      EXPECT_NE(d.message.find(bad.message), std::string::npos) << bad.what << ": " << d.format();
    }
    EXPECT_EQ(errors, 1) << bad.what << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find("specs/bad_objects.xml:" + std::to_string(bad.line) + ":"),
              std::string::npos)
        << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedSpec,
    ::testing::Values(
        BadSpec{"missing attribute", box(R"(<Box x="0.1" y="0.1"/>)"), 3,
                "<Box>: missing required attribute \"z\""},
        // Schema errors that say what is wrong (issue 20).
        BadSpec{"no shape", box(""), 4,
                "missing one of <Box>, <Cylinder>, <Lathe> or <Mesh> (required before "
                "<Appearance>)"},
        BadSpec{"appearance first",
                "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n" + kAppearance +
                    "\n<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n</Object>\n</ObjectDatabase>\n",
                3, "<Appearance> is out of order: it must come after <Box>"},
        BadSpec{"misspelt shape", box(R"(<Bx x="0.1" y="0.1" z="0.2"/>)"), 3,
                "unknown element <Bx> in <Object name=\"a\">; did you mean <Box>?"},
        BadSpec{"non-positive size", box(R"(<Box x="0.1" y="-0.1" z="0.2"/>)"), 3,
                "attribute y must be positive, got -0.1"},
        BadSpec{"not a number", box(R"(<Box x="0.1" y="wide" z="0.2"/>)"), 3,
                "attribute y: \"wide\" is not a number"},
        BadSpec{"corner radius", box(R"(<Box x="0.1" y="0.1" z="0.2" cornerRadius="0.01"/>)"), 3,
                "attribute cornerRadius must be in [0, 0.004]"},
        BadSpec{"non-monotonic profile",
                lathe("<Point z=\"0\" r=\"0.03\"/>\n<Point z=\"0.05\" r=\"0.03\"/>\n"
                      "<Point z=\"0.04\" r=\"0.03\"/>\n"),
                6, "profile not monotonic: z = 0.04 does not increase (previous point z = 0.05)"},
        BadSpec{"profile not from the bottom",
                lathe("<Point z=\"0.01\" r=\"0.03\"/>\n<Point z=\"0.05\" r=\"0.03\"/>\n"), 4,
                "the first profile point must be at z = 0"},
        BadSpec{"one profile point", lathe("<Point z=\"0\" r=\"0.03\"/>\n"), 3,
                "<Lathe>: a lathe needs at least two <Point> elements (bottom and top), got 1"},
        BadSpec{"zero radius", lathe("<Point z=\"0\" r=\"0.03\"/>\n<Point z=\"0.05\" r=\"0\"/>\n"),
                5, "attribute r must be positive, got 0"},
        BadSpec{"handle outside the body",
                lathe("<Point z=\"0\" r=\"0.03\"/>\n<Point z=\"0.1\" r=\"0.03\"/>\n",
                      "<Handle z=\"0.09\" span=\"0.04\" reach=\"0.03\" thickness=\"0.01\"/>\n"),
                7, "outside the body"},
        BadSpec{"handle without opening",
                lathe("<Point z=\"0\" r=\"0.03\"/>\n<Point z=\"0.1\" r=\"0.03\"/>\n",
                      "<Handle z=\"0.05\" span=\"0.04\" reach=\"0.01\" thickness=\"0.01\"/>\n"),
                7, "reach and span must exceed thickness"},
        BadSpec{"handle on a box",
                box("<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n"
                    "<Handle z=\"0.05\" span=\"0.04\" reach=\"0.03\" thickness=\"0.01\"/>"),
                4, "a handle needs a Cylinder or Lathe body"},
        BadSpec{"unknown pattern",
                box(R"(<Box x="0.1" y="0.1" z="0.2"/>)",
                    R"(<Appearance pattern="zebra" seed="1" body="0.5 0.5 0.5"/>)"),
                4, "unknown pattern \"zebra\"; expected printed-box, label-band"},
        BadSpec{
            "pattern for another shape",
            box(R"(<Box x="0.1" y="0.1" z="0.2"/>)",
                R"(<Appearance pattern="metal-can" seed="1" body="0.5 0.5 0.5"><Colour rgb="1 0 0"/><Colour rgb="0 1 0"/></Appearance>)"),
            4, "does not fit a Box"},
        BadSpec{
            "too few colours",
            box(R"(<Box x="0.1" y="0.1" z="0.2"/>)",
                R"(<Appearance pattern="printed-box" seed="1" body="0.5 0.5 0.5"><Colour rgb="1 0 0"/></Appearance>)"),
            4, "needs at least two <Colour> children, got 1"},
        BadSpec{
            "colour out of range",
            box(R"(<Box x="0.1" y="0.1" z="0.2"/>)",
                R"(<Appearance pattern="printed-box" seed="1" body="0.5 1.5 0.5"><Colour rgb="1 0 0"/><Colour rgb="0 1 0"/></Appearance>)"),
            4, "attribute body: colour components must be in [0, 1]"},
        BadSpec{
            "colour with two numbers",
            box(R"(<Box x="0.1" y="0.1" z="0.2"/>)",
                R"(<Appearance pattern="printed-box" seed="1" body="0.5 0.5"><Colour rgb="1 0 0"/><Colour rgb="0 1 0"/></Appearance>)"),
            4, "attribute body: expected 3 numbers (red green blue), got 2"},
        BadSpec{"unknown material",
                "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n"
                "<Cylinder radius=\"0.03\" height=\"0.1\"/>\n<Appearance pattern=\"plain-plastic\" "
                "seed=\"1\" body=\"0.5 0.5 0.5\" bodyMaterial=\"wood\"/>\n</Object>\n"
                "</ObjectDatabase>\n",
                4, "unknown bodyMaterial \"wood\"; expected plastic, metal, glass or cardboard"},
        BadSpec{"missing appearance",
                "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n"
                "<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n</Object>\n</ObjectDatabase>\n",
                2, "<Object name=\"a\">"},
        BadSpec{"unknown element", box(R"(<Sphere radius="0.1"/>)"), 3, "unknown element <Sphere>"},
        BadSpec{"duplicate id",
                "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n"
                "<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n" +
                    kAppearance +
                    "\n</Object>\n<Object id=\"1\" name=\"b\" mass=\"0.2\">\n"
                    "<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n" +
                    kAppearance + "\n</Object>\n</ObjectDatabase>\n",
                6, "duplicate id 1 (first at line 2)"},
        BadSpec{"duplicate name",
                "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n"
                "<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n" +
                    kAppearance +
                    "\n</Object>\n<Object id=\"2\" name=\"a\" mass=\"0.2\">\n"
                    "<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n" +
                    kAppearance + "\n</Object>\n</ObjectDatabase>\n",
                6, "duplicate name \"a\" (first at line 2)"},
        BadSpec{"zero mass",
                "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0\">\n"
                "<Box x=\"0.1\" y=\"0.1\" z=\"0.2\"/>\n" +
                    kAppearance + "\n</Object>\n</ObjectDatabase>\n",
                2, "attribute mass must be positive, got 0"},
        BadSpec{"unknown table pattern",
                "<ObjectDatabase>\n<Table name=\"t\" x=\"1\" y=\"1\" pattern=\"wood\" "
                "rgb=\"1 1 1\" seed=\"1\"/>\n</ObjectDatabase>\n",
                2, "unknown table pattern \"wood\"; expected \"plain\" or \"cluttered\""},
        BadSpec{"seed too large",
                "<ObjectDatabase>\n<Table name=\"t\" x=\"1\" y=\"1\" pattern=\"plain\" "
                "rgb=\"1 1 1\" seed=\"4294967296\"/>\n</ObjectDatabase>\n",
                2,
                "<Table name=\"t\">: attribute seed: expected an integer from 0 to 4294967295, "
                "got \"4294967296\""},
        BadSpec{"not well-formed",
                "<ObjectDatabase>\n<Object id=\"1\" name=\"a\" mass=\"0.2\">\n"
                "</ObjectDatabase>\n",
                3, "not well-formed XML"}),
    [](const auto& p) {
      std::string name = p.param.what;
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

}  // namespace
