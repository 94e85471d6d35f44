// Semantics of the workcell loader on small workcells written in the tests: attachment rules,
// units, DH joints, Include/Define/Use, setups, properties, warnings and diagnostics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "rw/loaders/workcell_writer.hpp"
#include "rw/math/dh.hpp"
#include "rw/math/rpy.hpp"
#include "support/test_support.hpp"

namespace {

using rw::common::Diagnostic;
using rw::common::LoadError;
using rw::kinematics::FKTable;
using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::math::Transform3D;
using rw::models::WorkCell;
using visgrab::test::TempDir;
using visgrab::test::writeFile;

constexpr double kDeg = std::numbers::pi / 180.0;

// A closed tetrahedron as ASCII STL (4 triangles, outward normals).
std::string tetrahedronStl() {
  return "solid tet\n"
         "facet normal 0 0 -1\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n  vertex 1 0 0\n"
         " endloop\nendfacet\n"
         "facet normal 0 -1 0\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 0 1\n"
         " endloop\nendfacet\n"
         "facet normal -1 0 0\n outer loop\n  vertex 0 0 0\n  vertex 0 0 1\n  vertex 0 1 0\n"
         " endloop\nendfacet\n"
         "facet normal 1 1 1\n outer loop\n  vertex 1 0 0\n  vertex 0 1 0\n  vertex 0 0 1\n"
         " endloop\nendfacet\n"
         "endsolid tet\n";
}

// One triangle as AC3D.
std::string triangleAc3d() {
  return "AC3Db\n"
         "MATERIAL \"\" rgb 1 1 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0.5 0.5 0.5  shi 10  trans 0\n"
         "OBJECT world\nkids 1\nOBJECT poly\nname \"tri\"\nnumvert 3\n0 0 0\n1 0 0\n0 1 0\n"
         "numsurf 1\nSURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n";
}

// Loads `xml` as if it were dir/main.wc.xml; fails the test with the messages on LoadError.
std::unique_ptr<WorkCell> loadText(const TempDir& dir, const std::string& xml,
                                   std::vector<Diagnostic>* warnings = nullptr) {
  try {
    return rw::loaders::loadWorkCellFromString(xml, dir.path() / "main.wc.xml", warnings);
  } catch (const LoadError& e) {
    ADD_FAILURE() << e.what();
    return nullptr;
  }
}

FrameId parentOf(const WorkCell& wc, const std::string& name) {
  const FrameId id = wc.findFrame(name);
  EXPECT_TRUE(id.valid()) << name;
  return id.valid() ? wc.frames().frame(id).parent() : FrameId{};
}

bool mentions(const std::vector<Diagnostic>& diagnostics, const std::string& text) {
  return std::any_of(diagnostics.begin(), diagnostics.end(), [&](const Diagnostic& d) {
    return d.message.find(text) != std::string::npos;
  });
}

std::set<std::pair<std::string, std::string>> unordered(
    const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::set<std::pair<std::string, std::string>> out;
  for (const auto& [a, b] : pairs) out.insert(a < b ? std::make_pair(a, b) : std::make_pair(b, a));
  return out;
}

TEST(WorkCellLoader, DefaultCollisionSetupExcludesParentChildAndGrandparentPairs) {
  // WORLD { A { B { D }, C }, E }
  TempDir dir;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Frame name="A"/>
    <Frame name="B" refframe="A"/>
    <Frame name="C" refframe="A"/>
    <Frame name="D" refframe="B"/>
    <Frame name="E" refframe="WORLD"/>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  // By hand (reference §1.5.6, WORLD itself never listed): parent-child pairs A-B, A-C, B-D;
  // pairs whose grandparent is the other's parent: D (grandparent A) with B and C; B and C
  // (grandparent WORLD) with A and E.
  const std::set<std::pair<std::string, std::string>> expected = {
      {"A", "B"}, {"A", "C"}, {"B", "D"}, {"C", "D"}, {"B", "E"}, {"C", "E"}};
  EXPECT_EQ(unordered(wc->collisionSetup().excludePairs), expected);
  EXPECT_EQ(wc->collisionSetup().excludePairs.size(), 6u);
  const auto& proximity = wc->proximitySetup();
  EXPECT_TRUE(proximity.useIncludeAll);
  EXPECT_FALSE(proximity.useExcludeStaticPairs);
  ASSERT_EQ(proximity.rules.size(), 6u);
  std::vector<std::pair<std::string, std::string>> ruled;
  for (const auto& r : proximity.rules) {
    EXPECT_FALSE(r.include);
    ruled.emplace_back(r.patternA, r.patternB);
  }
  EXPECT_EQ(unordered(ruled), expected);
}

TEST(WorkCellLoader, ProximitySetupFileReplacesTheDefaultAndIsScoped) {
  TempDir dir;
  writeFile(dir.path() / "dev.prox.xml", R"(<ProximitySetup>
    <Exclude PatternA="Base" PatternB="*"/>
    <Include PatternA="Left?" PatternB="REGEX.*Right"/>
  </ProximitySetup>)");
  writeFile(dir.path() / "dev.cs.xml", R"(<CollisionSetup>
    <Exclude><FramePair first="Base" second="Left1"/></Exclude>
    <Volatile>Left1</Volatile>
    <ExcludeStaticPairs/>
  </CollisionSetup>)");
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <TreeDevice name="Dev">
      <Frame name="Base"/>
      <Frame name="Left1"/>
      <ProximitySetup file="dev.prox.xml"/>
      <CollisionSetup file="dev.cs.xml"/>
    </TreeDevice>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  const auto& cs = wc->collisionSetup();
  ASSERT_EQ(cs.excludePairs.size(), 1u);
  EXPECT_EQ(cs.excludePairs[0], std::make_pair(std::string("Dev.Base"), std::string("Dev.Left1")));
  EXPECT_EQ(cs.volatileFrames, std::vector<std::string>{"Dev.Left1"});
  EXPECT_TRUE(cs.excludeStaticPairs);
  const auto& ps = wc->proximitySetup();
  EXPECT_TRUE(ps.useIncludeAll);
  EXPECT_TRUE(ps.useExcludeStaticPairs);
  ASSERT_EQ(ps.rules.size(), 3u);
  EXPECT_EQ(ps.rules[0].patternA, "Dev.Base");
  EXPECT_EQ(ps.rules[0].patternB, "Dev.Left1");
  EXPECT_FALSE(ps.rules[0].include);
  EXPECT_EQ(ps.rules[1].patternA, "Dev.Base");
  EXPECT_EQ(ps.rules[1].patternB, "Dev.*");
  EXPECT_FALSE(ps.rules[1].include);
  EXPECT_EQ(ps.rules[2].patternA, "Dev.Left?");
  EXPECT_EQ(ps.rules[2].patternB, "REGEXDev\\..*Right");
  EXPECT_TRUE(ps.rules[2].include);
}

TEST(WorkCellLoader, AttachmentRulesFollowRobWork) {
  TempDir dir;
  std::vector<Diagnostic> warnings;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Frame name="Mount" refframe="Other"><Pos>0 0 1</Pos><RPY>90 0 0</RPY></Frame>
    <Frame name="Other"/>
    <Frame name="Tool" refframe="Arm.End"/>
    <Frame name="Shelf" refframe="Mount"/>
    <TreeDevice name="Arm">
      <Frame name="Base" refframe="Mount"/>
      <Joint name="J1" type="Revolute"><RPY>0 0 0</RPY><Pos>0 0 0.1</Pos></Joint>
      <Frame name="End" type="EndEffector"/>
      <Frame name="Side" refframe="Base"/>
    </TreeDevice>
    <SerialDevice name="S">
      <Frame name="B"/>
      <Joint name="q1" type="Prismatic" refframe="B"/>
      <Joint name="q2" type="Revolute" refframe="Nowhere"/>
    </SerialDevice>
  </WorkCell>)",
                           &warnings);
  ASSERT_NE(wc, nullptr);
  const FrameId world = FrameTree::kWorld;
  EXPECT_EQ(parentOf(*wc, "Mount"), world);  // the first frame always hangs on WORLD
  EXPECT_EQ(parentOf(*wc, "Other"), world);  // no refframe: WORLD
  EXPECT_EQ(parentOf(*wc, "Tool"), wc->findFrame("Arm.End"));  // forward reference
  EXPECT_EQ(parentOf(*wc, "Shelf"), wc->findFrame("Mount"));
  EXPECT_EQ(parentOf(*wc, "Arm.Base"), wc->findFrame("Shelf"));   // last wc frame before it
  EXPECT_EQ(parentOf(*wc, "Arm.J1"), wc->findFrame("Arm.Base"));  // previous frame
  EXPECT_EQ(parentOf(*wc, "Arm.End"), wc->findFrame("Arm.J1"));
  EXPECT_EQ(parentOf(*wc, "Arm.Side"), wc->findFrame("Arm.Base"));  // scoped refframe
  EXPECT_EQ(parentOf(*wc, "S.B"), wc->findFrame("Shelf"));
  EXPECT_EQ(parentOf(*wc, "S.q1"), wc->findFrame("S.B"));
  EXPECT_EQ(parentOf(*wc, "S.q2"), wc->findFrame("S.q1"));  // serial: refframe ignored
  // Frames are stored parent-first even with the forward reference.
  for (const auto& f : wc->frames().frames()) {
    if (f.id() != world) {
      EXPECT_LT(f.parent().index, f.id().index) << f.name();
    }
  }
  EXPECT_EQ(warnings.size(), 3u);
  EXPECT_TRUE(mentions(warnings, "first frame of a workcell is always attached to WORLD"));
  EXPECT_TRUE(mentions(warnings, "base frame of a device"));
  EXPECT_TRUE(mentions(warnings, "refframe \"Nowhere\" is ignored"));
  for (const Diagnostic& w : warnings) EXPECT_EQ(w.severity, Diagnostic::Severity::kWarning);

  // Pos before RPY is fine; RPY is Rz Ry Rx in degrees.
  const FrameId mount = wc->findFrame("Mount");
  EXPECT_TRANSFORM_NEAR(
      wc->frames().frame(mount).fixedTransform(),
      rw::math::rpyTransform(Eigen::Vector3d(90 * kDeg, 0, 0), Eigen::Vector3d(0, 0, 1)), 1e-15);
  const auto* arm = wc->findDevice("Arm");
  ASSERT_NE(arm, nullptr);
  ASSERT_EQ(arm->ends().size(), 1u);
  EXPECT_EQ(arm->ends()[0], wc->findFrame("Arm.End"));
  const auto* serial = wc->findDevice("S");
  ASSERT_NE(serial, nullptr);
  EXPECT_EQ(serial->kind(), rw::models::Device::Kind::kSerial);
  EXPECT_EQ(serial->dof(), 2);
  EXPECT_EQ(serial->ends()[0], wc->findFrame("S.q2"));
}

TEST(WorkCellLoader, UnitsFollowRobWorkConventions) {
  TempDir dir;
  std::vector<Diagnostic> warnings;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <TreeDevice name="D">
      <Frame name="Base" type="Movable"><Transform>0 -1 0 0.1  1 0 0 0.2  0 0 1 0.3</Transform></Frame>
      <Joint name="R" type="Revolute">
        <PosLimit min="-45" max="30"/><VelLimit max="90"/><AccLimit max="180"/>
      </Joint>
      <Joint name="P" type="Prismatic"><PosLimit min="-0.1" max="0.2"/><VelLimit max="0.5"/></Joint>
      <Joint name="Dep" type="Revolute">
        <Depend on="R" gain="2" offset="0.25"/>
        <PosLimit min="-1" max="1"/>
      </Joint>
      <PosLimit refjoint="Dep" min="-60" max="60"/>
      <VelLimit refjoint="P" max="0.25"/>
      <Q name="Home">0.5 0.05</Q>
      <Q name="Other">1 2</Q>
    </TreeDevice>
  </WorkCell>)",
                           &warnings);
  ASSERT_NE(wc, nullptr);
  const auto& R = wc->frames().frame(wc->findFrame("D.R"));
  EXPECT_DOUBLE_EQ(R.limits().lower, -45 * kDeg);
  EXPECT_DOUBLE_EQ(R.limits().upper, 30 * kDeg);
  EXPECT_DOUBLE_EQ(R.limits().velocity, 90 * kDeg);
  EXPECT_DOUBLE_EQ(R.limits().acceleration, 180 * kDeg);
  const auto& P = wc->frames().frame(wc->findFrame("D.P"));
  EXPECT_DOUBLE_EQ(P.limits().lower, -0.1);
  EXPECT_DOUBLE_EQ(P.limits().upper, 0.2);
  EXPECT_DOUBLE_EQ(P.limits().velocity, 0.25);  // the device-level limit comes last
  // Dependent joint: inner limits ignored (warned), device-level limits unconverted (§1.9).
  const auto& dep = wc->frames().frame(wc->findFrame("D.Dep"));
  EXPECT_DOUBLE_EQ(dep.limits().lower, -60.0);
  EXPECT_DOUBLE_EQ(dep.limits().upper, 60.0);
  EXPECT_TRUE(mentions(warnings, "limits inside a dependent joint are ignored"));
  // Q values are raw; Home is the default state; Depend offset is raw.
  const auto& device = *wc->findDevice("D");
  const auto state = wc->defaultState();
  EXPECT_VECTOR_NEAR(device.getQ(state), Eigen::Vector2d(0.5, 0.05), 0.0);
  EXPECT_DOUBLE_EQ(dep.jointValue(state), 2 * 0.5 + 0.25);
  EXPECT_EQ(device.configurations().size(), 2u);
  EXPECT_VECTOR_NEAR(device.configurations().at("Other"), Eigen::Vector2d(1, 2), 0.0);
  // Transform: 12 numbers, row-major, no conversion; a Movable frame starts there.
  Transform3D expected = Transform3D::Identity();
  expected.linear() << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  expected.translation() << 0.1, 0.2, 0.3;
  const FrameId base = wc->findFrame("D.Base");
  EXPECT_TRANSFORM_NEAR(wc->frames().frame(base).movableTransform(state), expected, 1e-12);
}

TEST(WorkCellLoader, DrawableColoursFromRgb) {
  // RobWork's <RGB>r g b [a]</RGB> in a Drawable; the alpha is read and reported as not drawn; a
  // CollisionModel is not drawn, so its colour is ignored with a warning.
  TempDir dir;
  std::vector<Diagnostic> warnings;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Frame name="F">
      <Drawable name="Red"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><RGB>1 0 0.25</RGB>
        <Box x="1" y="1" z="1"/></Drawable>
      <Drawable name="Plain"><Sphere radius="0.1"/></Drawable>
      <Drawable name="Glass" colmodel="Disabled"><RGB>0 0.5 1 0.3</RGB><Sphere radius="0.1"/>
      </Drawable>
      <CollisionModel name="Hull"><RGB>0 1 0</RGB><Sphere radius="0.2"/></CollisionModel>
    </Frame>
  </WorkCell>)",
                           &warnings);
  ASSERT_NE(wc, nullptr);
  const auto* object = wc->findObject(wc->findFrame("F"));
  ASSERT_NE(object, nullptr);
  ASSERT_EQ(object->visual.size(), 3u);
  EXPECT_EQ(object->visual[0].color, (std::array<float, 3>{1.0f, 0.0f, 0.25f}));
  EXPECT_EQ(object->visual[1].color, rw::models::GeometryInstance{}.color);
  EXPECT_EQ(object->visual[2].color, (std::array<float, 3>{0.0f, 0.5f, 1.0f}));
  EXPECT_TRUE(mentions(warnings, "transparency (alpha 0.3"));
  EXPECT_TRUE(mentions(warnings, "a CollisionModel is not drawn"));
  // The writer keeps the colours: written and read again, the same.
  const auto written = dir.path() / "written.wc.xml";
  rw::loaders::saveWorkCell(*wc, written);
  const auto again = rw::loaders::loadWorkCell(written);
  const auto* o2 = again->findObject(again->findFrame("F"));
  ASSERT_NE(o2, nullptr);
  ASSERT_EQ(o2->visual.size(), 3u);
  EXPECT_EQ(o2->visual[0].color, object->visual[0].color);
  EXPECT_EQ(o2->visual[1].color, object->visual[1].color);
  EXPECT_EQ(o2->visual[2].color, object->visual[2].color);
}

TEST(WorkCellLoader, DhJointsUseTheirOwnTypeEachTime) {
  TempDir dir;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <SerialDevice name="UR">
      <Frame name="Base"/>
      <DHJoint name="J1" alpha="90" a="0.1" d="0.2" offset="30" type="schilling"/>
      <DHJoint name="J2" alpha="-90" a="0.3" d="0.05" offset="10"/>
      <DHJoint name="J3" alpha="5" a="0.4" theta="20" offset="0.02"/>
      <DHJoint name="J4" alpha="1" a="0.6" b="0.01" offset="-2" type="HGP"/>
      <DHJoint name="J5" alpha="2" a="0.7" beta="3" offset="0.03"/>
    </SerialDevice>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  auto frame = [&](const char* name) -> const rw::kinematics::Frame& {
    return wc->frames().frame(wc->findFrame(std::string("UR.") + name));
  };
  EXPECT_EQ(frame("J1").type(), FrameType::kRevolute);
  EXPECT_TRANSFORM_NEAR(frame("J1").fixedTransform(),
                        rw::math::schillingDH(90 * kDeg, 0.1, 0.2, 30 * kDeg), 1e-15);
  // No type: craig, not the schilling of the previous joint (RobWork's carry-over bug, A.16).
  EXPECT_TRANSFORM_NEAR(frame("J2").fixedTransform(),
                        rw::math::craigDH(-90 * kDeg, 0.3, 0.05, 10 * kDeg), 1e-15);
  EXPECT_EQ(frame("J3").type(), FrameType::kPrismatic);
  EXPECT_TRANSFORM_NEAR(frame("J3").fixedTransform(),
                        rw::math::craigDH(5 * kDeg, 0.4, 0.02, 20 * kDeg), 1e-15);
  EXPECT_EQ(frame("J4").type(), FrameType::kRevolute);
  EXPECT_TRANSFORM_NEAR(frame("J4").fixedTransform(),
                        rw::math::hgpDH(1 * kDeg, 0.6, -2 * kDeg, 0.01), 1e-15);
  EXPECT_EQ(frame("J5").type(), FrameType::kPrismatic);
  EXPECT_TRANSFORM_NEAR(frame("J5").fixedTransform(),
                        rw::math::hgpDH(2 * kDeg, 0.7, 3 * kDeg, 0.03), 1e-15);
  EXPECT_EQ(wc->findDevice("UR")->dof(), 5);
}

TEST(WorkCellLoader, IncludeDefineAndUseExpandPerFile) {
  TempDir dir;
  writeFile(dir.path() / "parts/meshes/tet.stl", tetrahedronStl());
  // A fragment with several top-level elements; its Define is its own.
  writeFile(dir.path() / "parts/fingers.xml", R"(<?xml version="1.0" encoding="UTF-8"?>
<Define id="finger">
  <Joint name="J" type="Revolute"><RPY>0 0 0</RPY><Pos>0 0 0.05</Pos></Joint>
  <Frame name="Tip" type="EndEffector"><RPY>0 0 0</RPY><Pos>0 0 0.03</Pos></Frame>
  <Drawable name="TipGeo" refframe="Tip"><Polytope file="meshes/tet"/></Drawable>
  <PosLimit refjoint="J" min="-10" max="20"/>
</Define>
<SerialChain name="a"><Use id="finger"/></SerialChain>
<Frame name="Mid" refframe="Base"/>
<SerialChain name="b"><Use id="finger"/></SerialChain>
)");
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <TreeDevice name="Hand">
      <Frame name="Base"/>
      <Include file="parts/fingers.xml"/>
    </TreeDevice>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  const auto& hand = *wc->findDevice("Hand");
  std::vector<std::string> joints;
  for (const FrameId j : hand.activeJoints()) joints.push_back(wc->frames().frame(j).name());
  EXPECT_EQ(joints, (std::vector<std::string>{"Hand.a.J", "Hand.b.J"}));
  EXPECT_EQ(parentOf(*wc, "Hand.a.J"), wc->findFrame("Hand.Base"));
  EXPECT_EQ(parentOf(*wc, "Hand.b.J"), wc->findFrame("Hand.Mid"));
  EXPECT_DOUBLE_EQ(wc->frames().frame(wc->findFrame("Hand.b.J")).limits().upper, 20 * kDeg);
  const auto* a = wc->findObject(wc->findFrame("Hand.a.Tip"));
  const auto* b = wc->findObject(wc->findFrame("Hand.b.Tip"));
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  ASSERT_EQ(a->collision.size(), 1u);
  EXPECT_EQ(a->collision[0].geometry, b->collision[0].geometry);  // one mesh per file and load
  EXPECT_EQ(std::filesystem::path(a->collision[0].geometry->sourceFile()).filename(), "tet.stl");
  EXPECT_EQ(a->collision[0].geometry->triangles().triangles.size(), 4u);
}

// ${NAME} in an Include's file is the environment variable NAME (this project's extension, for
// files that lie outside the project, such as RobWork's own devices): anywhere in the name, more
// than once.
TEST(WorkCellLoader, AnIncludeNamesAnEnvironmentVariable) {
  TempDir dir;
  writeFile(dir.path() / "data/parts/frames.xml", "<Frame name=\"A\"/>\n<Frame name=\"B\"/>\n");
  ASSERT_EQ(setenv("VISGRAB_TEST_DATA", (dir.path() / "data").c_str(), 1), 0);
  ASSERT_EQ(setenv("VISGRAB_TEST_PART", "frames", 1), 0);
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Include file="${VISGRAB_TEST_DATA}/parts/${VISGRAB_TEST_PART}.xml"/>
  </WorkCell>)");
  unsetenv("VISGRAB_TEST_DATA");
  unsetenv("VISGRAB_TEST_PART");
  ASSERT_NE(wc, nullptr);
  EXPECT_TRUE(wc->findFrame("A").valid());
  EXPECT_TRUE(wc->findFrame("B").valid());
}

TEST(WorkCellLoader, AnIncludeRedirectPutsAnotherHandInTheScene) {
  TempDir dir;
  writeFile(dir.path() / "hands/a/hand_a.wc.xml",
            "<TreeDevice name=\"HandA\">\n <Frame name=\"Base\" refframe=\"Mount\"/>\n"
            "</TreeDevice>\n");
  // Hand B's Include is relative to its own folder: the redirect keeps that.
  writeFile(dir.path() / "other/b/hand_b.wc.xml",
            "<TreeDevice name=\"HandB\">\n <Frame name=\"Base\" refframe=\"Mount\"/>\n"
            " <Include file=\"tip.xml\"/>\n</TreeDevice>\n");
  writeFile(dir.path() / "other/b/tip.xml", "<Frame name=\"Tip\" refframe=\"Base\"/>\n");
  const auto scene = writeFile(dir.path() / "scenes/s1/scene.wc.xml",
                               "<WorkCell name=\"w\">\n <Frame name=\"Mount\"/>\n"
                               " <Include file=\"../../hands/a/hand_a.wc.xml\"/>\n</WorkCell>\n");
  const auto asWritten = rw::loaders::loadWorkCell(scene);
  EXPECT_NE(asWritten->findDevice("HandA"), nullptr);
  EXPECT_EQ(asWritten->findDevice("HandB"), nullptr);

  // The key names the file differently from the Include; it still matches.
  rw::loaders::WorkCellLoadOptions options;
  options.includeRedirects[dir.path() / "hands/x/../a/hand_a.wc.xml"] =
      dir.path() / "other/b/hand_b.wc.xml";
  const auto swapped = rw::loaders::loadWorkCell(scene, options);
  EXPECT_EQ(swapped->findDevice("HandA"), nullptr);
  EXPECT_NE(swapped->findDevice("HandB"), nullptr);
  EXPECT_TRUE(swapped->findFrame("HandB.Tip").valid());
  EXPECT_EQ(parentOf(*swapped, "HandB.Base"), swapped->findFrame("Mount"));

  // A redirect of a file the scene does not include changes nothing.
  rw::loaders::WorkCellLoadOptions unused;
  unused.includeRedirects[dir.path() / "hands/a/other.wc.xml"] =
      dir.path() / "other/b/hand_b.wc.xml";
  EXPECT_NE(rw::loaders::loadWorkCell(scene, unused)->findDevice("HandA"), nullptr);
}

TEST(WorkCellLoader, AnIncludeRedirectToAMissingFileIsAnErrorAtTheInclude) {
  TempDir dir;
  writeFile(dir.path() / "hand_a.wc.xml", "<Frame name=\"Base\" refframe=\"WORLD\"/>\n");
  const auto scene =
      writeFile(dir.path() / "scene.wc.xml",
                "<WorkCell name=\"w\">\n <Include file=\"hand_a.wc.xml\"/>\n</WorkCell>\n");
  rw::loaders::WorkCellLoadOptions options;
  options.includeRedirects[dir.path() / "hand_a.wc.xml"] = dir.path() / "no_such_hand.wc.xml";
  try {
    rw::loaders::loadWorkCell(scene, options);
    FAIL() << "no LoadError";
  } catch (const LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    const Diagnostic& d = e.diagnostics()[0];
    EXPECT_EQ(d.file, scene.string());
    EXPECT_EQ(d.line, 2);
    EXPECT_NE(
        d.message.find("cannot read \"" + (dir.path() / "no_such_hand.wc.xml").string() +
                       "\" (redirected from \"" + (dir.path() / "hand_a.wc.xml").string() + "\")"),
        std::string::npos)
        << d.message;
    EXPECT_NE(std::string(e.what()).find(scene.string() + ":2:"), std::string::npos) << e.what();
  }
}

TEST(WorkCellLoader, CollisionPrefersStlAndDrawingPrefersAc3d) {
  TempDir dir;
  writeFile(dir.path() / "m.stl", tetrahedronStl());
  writeFile(dir.path() / "m.ac", triangleAc3d());
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Frame name="F"><Drawable name="G"><Polytope file="m"/></Drawable>
      <CollisionModel name="C"><Sphere radius="0.5"/></CollisionModel></Frame>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  const auto* object = wc->findObject(wc->findFrame("F"));
  ASSERT_NE(object, nullptr);
  ASSERT_EQ(object->collision.size(), 2u);
  ASSERT_EQ(object->visual.size(), 1u);
  EXPECT_EQ(std::filesystem::path(object->collision[0].geometry->sourceFile()).extension(), ".stl");
  EXPECT_EQ(std::filesystem::path(object->visual[0].geometry->sourceFile()).extension(), ".ac");
  EXPECT_EQ(object->collision[1].name, "C");
  EXPECT_EQ(object->collision[1].geometry->type(), rw::geometry::GeometryType::kSphere);
}

TEST(WorkCellLoader, PrimitivesAndModelOffsets) {
  TempDir dir;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Frame name="F"/>
    <Drawable name="Cyl" refframe="F"><RPY>0 90 0</RPY><Pos>1 2 3</Pos>
      <Cylinder radius="0.1" z="0.4"/><Cone radius="0.2" z="0.3"/>
      <Tube radius="0.1" thickness="0.02" z="0.5"/><Plane/>
    </Drawable>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  const auto* object = wc->findObject(wc->findFrame("F"));
  ASSERT_NE(object, nullptr);
  ASSERT_EQ(object->collision.size(), 4u);
  EXPECT_EQ(object->collision[0].geometry->parameters(), (std::vector<double>{0.1, 0.4}));
  EXPECT_EQ(object->collision[1].geometry->type(), rw::geometry::GeometryType::kCone);
  EXPECT_EQ(object->collision[2].geometry->parameters(), (std::vector<double>{0.1, 0.02, 0.5}));
  EXPECT_EQ(object->collision[3].geometry->type(), rw::geometry::GeometryType::kPlane);
  EXPECT_TRANSFORM_NEAR(
      object->collision[0].X_frame_geometry,
      rw::math::rpyTransform(Eigen::Vector3d(0, 90 * kDeg, 0), Eigen::Vector3d(1, 2, 3)), 1e-15);
}

TEST(WorkCellLoader, FrustumIsACustomPrimitiveAndWritesBack) {
  TempDir dir;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Frame name="F"/>
    <Drawable name="Jar" refframe="F"><Custom type="Frustum" param="0.03 0.02 0.1"/></Drawable>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  const auto& geometry = *wc->findObject(wc->findFrame("F"))->collision.at(0).geometry;
  EXPECT_EQ(geometry.type(), rw::geometry::GeometryType::kFrustum);
  EXPECT_EQ(geometry.parameters(), (std::vector<double>{0.03, 0.02, 0.1}));
  EXPECT_VECTOR_NEAR(geometry.bounds().max, Eigen::Vector3d(0.03, 0.03, 0.05), 1e-15);
  const std::string xml = rw::loaders::writeWorkCell(*wc, dir.path());
  EXPECT_NE(xml.find(R"(<Custom type="Frustum" param="0.03 0.02 0.1"/>)"), std::string::npos)
      << xml;
  const auto copy = loadText(dir, xml);
  ASSERT_NE(copy, nullptr);
  EXPECT_EQ(copy->findObject(copy->findFrame("F"))->collision.at(0).geometry->parameters(),
            geometry.parameters());
}

TEST(WorkCellLoader, PropertiesKeepTheirTypes) {
  TempDir dir;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Property name="author" desc="who">Jane</Property>
    <TreeDevice name="D">
      <Frame name="Base">
        <Property name="mass" type="double"> 1.5 </Property>
        <Property name="home" type="Q">1 2 3</Property>
      </Frame>
      <Property name="vendor" type="string">ACME</Property>
    </TreeDevice>
  </WorkCell>)");
  ASSERT_NE(wc, nullptr);
  ASSERT_EQ(wc->properties().count("author"), 1u);
  EXPECT_EQ(std::get<std::string>(wc->properties().at("author").value), "Jane");
  EXPECT_EQ(wc->properties().at("author").description, "who");
  const auto& props = wc->frames().frame(wc->findFrame("D.Base")).properties();
  EXPECT_EQ(std::get<double>(props.at("mass").value), 1.5);
  EXPECT_VECTOR_NEAR(std::get<rw::math::Q>(props.at("home").value), Eigen::Vector3d(1, 2, 3), 0.0);
  EXPECT_EQ(std::get<std::string>(wc->findDevice("D")->properties().at("vendor").value), "ACME");
}

TEST(WorkCellLoader, PropertyOfUnknownTypeIsAWarningAndDropped) {
  TempDir dir;
  std::vector<Diagnostic> warnings;
  const auto wc = loadText(dir,
                           "<WorkCell name=\"w\">\n"
                           "  <Frame name=\"F\">\n"
                           "    <Property name=\"n\" type=\"int\">3</Property>\n"
                           "  </Frame>\n"
                           "</WorkCell>\n",
                           &warnings);
  ASSERT_NE(wc, nullptr);
  EXPECT_EQ(wc->frames().frame(wc->findFrame("F")).properties().count("n"), 0u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].severity, Diagnostic::Severity::kWarning);
  EXPECT_EQ(warnings[0].line, 3);
  EXPECT_EQ(warnings[0].column, 5);
  EXPECT_EQ(std::filesystem::path(warnings[0].file).filename(), "main.wc.xml");
  EXPECT_NE(warnings[0].message.find("type \"int\" is not supported"), std::string::npos);
  EXPECT_NE(warnings[0].format().find("main.wc.xml:3:5: warning: <Property name=\"n\">"),
            std::string::npos)
      << warnings[0].format();
}

TEST(WorkCellLoader, CameraAndCalibrationAreIgnoredWithWarnings) {
  TempDir dir;
  std::vector<Diagnostic> warnings;
  const auto wc = loadText(dir, R"(<WorkCell name="w">
    <Camera name="cam"><RPY>0 0 0</RPY><Pos>0 0 1</Pos></Camera>
    <Calibration file="calib.xml"/>
    <Frame name="F" daf="true"/>
  </WorkCell>)",
                           &warnings);
  ASSERT_NE(wc, nullptr);
  EXPECT_EQ(warnings.size(), 2u);
  EXPECT_TRUE(mentions(warnings, "<Camera name=\"cam\"> is read and ignored"));
  EXPECT_TRUE(mentions(warnings, "<Calibration file=\"calib.xml\"> is read and ignored"));
  EXPECT_TRUE(wc->frames().frame(wc->findFrame("F")).isDaf());
}

TEST(WorkCellLoader, WarningsAreReturnedAlsoWhenTheLoadFails) {
  TempDir dir;
  std::vector<Diagnostic> warnings;
  try {
    rw::loaders::loadWorkCellFromString(
        "<WorkCell name=\"w\">\n <Camera name=\"c\"/>\n <Frame name=\"A\"/>\n"
        " <Frame name=\"B\" refframe=\"C\"/>\n</WorkCell>\n",
        dir.path() / "w.wc.xml", &warnings);
    FAIL() << "no LoadError";
  } catch (const LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 2u);
    EXPECT_EQ(e.diagnostics()[0].severity, Diagnostic::Severity::kWarning);
    EXPECT_EQ(e.diagnostics()[1].severity, Diagnostic::Severity::kError);
    EXPECT_EQ(e.diagnostics()[1].line, 4);
    EXPECT_EQ(std::string(e.what()), e.diagnostics()[1].format());
  }
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].line, 2);
}

TEST(WorkCellLoader, LoadsFromDiskAndNamesTheFileAbsolutely) {
  TempDir dir;
  const auto file = writeFile(dir.path() / "scene.wc.xml",
                              "<WorkCell name=\"disk\"><Frame name=\"F\"/></WorkCell>");
  const auto wc = rw::loaders::loadWorkCell(file);
  ASSERT_NE(wc, nullptr);
  EXPECT_EQ(wc->name(), "disk");
  EXPECT_EQ(std::filesystem::path(wc->fileName()),
            std::filesystem::absolute(file).lexically_normal());
  EXPECT_TRUE(rw::loaders::checkWorkCell(file).empty());
}

TEST(WorkCellLoader, DiagnosticsFormatLikeACompiler) {
  Diagnostic d;
  d.file = "/a/hand.wc.xml";
  d.line = 42;
  d.column = 7;
  d.message = "<Joint name=\"j1\">: <PosLimit> min 90 > max 45";
  d.includedFrom = {"/a/scene.wc.xml:7", "/a/top.wc.xml:3"};
  EXPECT_EQ(d.format(),
            "in file included from /a/scene.wc.xml:7\n"
            "in file included from /a/top.wc.xml:3\n"
            "/a/hand.wc.xml:42:7: error: <Joint name=\"j1\">: <PosLimit> min 90 > max 45");
  d.column = 0;
  d.includedFrom.clear();
  d.severity = Diagnostic::Severity::kWarning;
  EXPECT_EQ(d.format(),
            "/a/hand.wc.xml:42: warning: <Joint name=\"j1\">: <PosLimit> min 90 > max 45");
  d.line = 0;
  EXPECT_EQ(d.format(), "/a/hand.wc.xml: warning: <Joint name=\"j1\">: <PosLimit> min 90 > max 45");

  Diagnostic e = d;
  e.severity = Diagnostic::Severity::kError;
  const LoadError error({d, e, e});
  EXPECT_EQ(error.diagnostics().size(), 3u);
  EXPECT_EQ(std::string(error.what()), e.format() + "\n" + e.format());
}

TEST(WorkCellLoader, ErrorsInIncludedFilesCarryTheChain) {
  TempDir dir;
  writeFile(dir.path() / "sub/inner.xml", "<Frame name=\"X\" refframe=\"Nowhere\"/>\n");
  writeFile(dir.path() / "sub/middle.xml", "\n<Include file=\"inner.xml\"/>\n");
  try {
    rw::loaders::loadWorkCellFromString(
        "<WorkCell name=\"w\">\n <Frame name=\"First\"/>\n <Include file=\"sub/middle.xml\"/>\n"
        "</WorkCell>\n",
        dir.path() / "virtual.wc.xml");
    FAIL() << "no LoadError";
  } catch (const LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    const Diagnostic& d = e.diagnostics()[0];
    EXPECT_EQ(d.file, (dir.path() / "sub/inner.xml").lexically_normal().string());
    EXPECT_EQ(d.line, 1);
    EXPECT_EQ(d.column, 1);
    ASSERT_EQ(d.includedFrom.size(), 2u);
    EXPECT_EQ(d.includedFrom[0],
              (dir.path() / "sub/middle.xml").lexically_normal().string() + ":2");
    EXPECT_EQ(d.includedFrom[1],
              (dir.path() / "virtual.wc.xml").lexically_normal().string() + ":3");
    EXPECT_NE(d.message.find("unknown refframe \"Nowhere\""), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("in file included from "), std::string::npos);
  }
}

TEST(WorkCellLoader, LoadsConcurrently) {
  TempDir dir;
  const std::string xml = R"(<WorkCell name="w">
    <TreeDevice name="D"><Frame name="Base"/><Joint name="J" type="Revolute"/>
      <Drawable name="G" refframe="J"><Box x="1" y="1" z="1"/></Drawable></TreeDevice>
  </WorkCell>)";
  std::vector<int> dofs(8, -1);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    threads.emplace_back([&, i] {
      try {
        const auto wc = rw::loaders::loadWorkCellFromString(xml, dir.path() / "t.wc.xml");
        dofs[i] = wc->findDevice("D")->dof();
      } catch (...) {
        dofs[i] = -2;
      }
    });
  }
  for (auto& t : threads) t.join();
  for (const int dof : dofs) EXPECT_EQ(dof, 1);
}

}  // namespace
