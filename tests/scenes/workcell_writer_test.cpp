// The workcell writer's text: RobWork's ordering and attachment rules, units, element choice,
// setup files and its refusals. Whether the text loads back to the same model is
// writer_roundtrip_test's job.

#include "rw/loaders/workcell_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "built_scene.hpp"
#include "support/test_support.hpp"

namespace {

using rw::kinematics::FrameSpec;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::loaders::renderWorkCell;
using rw::loaders::saveWorkCell;
using rw::loaders::writeWorkCell;
using rw::models::Device;
using rw::models::WorkCell;
using visgrab::test::TempDir;
using visgrab::test::scenes::buildScene;

// Position of `needle` in `text`, failing the test if it is absent.
std::size_t at(const std::string& text, const std::string& needle) {
  const std::size_t pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << "missing: " << needle << "\nin:\n" << text;
  return pos;
}

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

class WorkCellWriter : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = buildScene(dir_.path() / "meshes");
    files_ = renderWorkCell(*scene_.wc, dir_.path() / "out", "built");
    text_ = files_.workcell;
  }

  TempDir dir_;
  visgrab::test::scenes::BuiltScene scene_;
  rw::loaders::WorkCellFiles files_;
  std::string text_;
};

// RobWork mounts a device on the last workcell-level frame before it (WORLD if none) and puts
// the first workcell-level frame on WORLD whatever it names.
TEST_F(WorkCellWriter, OrdersDevicesAndFramesForRobWorksAttachmentRules) {
  const std::size_t arm = at(text_, "<SerialDevice name=\"Arm\">");
  const std::size_t table = at(text_, "<Frame name=\"Table\" refframe=\"WORLD\">");
  const std::size_t mount = at(text_, "<Frame name=\"Mount\" refframe=\"Arm.TCP\">");
  const std::size_t grip = at(text_, "<TreeDevice name=\"Grip\">");
  const std::size_t cup =
      at(text_, "<Frame name=\"Cup\" refframe=\"Table\" type=\"Movable\" daf=\"true\">");
  EXPECT_LT(arm, table);
  EXPECT_LT(table, mount);
  EXPECT_LT(mount, grip);
  EXPECT_LT(grip, cup);
  EXPECT_EQ(text_.find("<Frame", 0), text_.find("<Frame name=\"Base\"")) << text_;
  // Nothing at workcell level between Mount and the device mounted on it.
  EXPECT_EQ(text_.find("<", text_.find("</Frame>", mount) + 1), grip);
}

TEST_F(WorkCellWriter, WritesDeviceFramesRelativeToTheDevice) {
  // Serial device: no refframe at all (RobWork chains the frames); tree device: on every frame
  // but the base.
  at(text_, "<Frame name=\"Base\">");
  at(text_, "<Joint name=\"J1\" type=\"Revolute\">");
  at(text_, "<Joint name=\"J2\" type=\"Prismatic\">");
  at(text_, "<Joint name=\"J3\" type=\"Revolute\" state=\"Passive\">");
  at(text_, "<Frame name=\"TCP\">");
  at(text_, "<Frame name=\"Base\" type=\"Movable\">");
  at(text_, "<Joint name=\"R\" refframe=\"Base\" type=\"Prismatic\">");
  at(text_, "<Frame name=\"R.Tip\" refframe=\"R\" type=\"EndEffector\">");
  at(text_, "<Frame name=\"L.Tip\" refframe=\"L\" type=\"EndEffector\">");
}

TEST_F(WorkCellWriter, WritesAnglesInDegreesAndDependentLimitsRaw) {
  // J1: limits +-pi/2 rad, pi rad/s inside the joint, in degrees.
  const std::size_t j1 = at(text_, "<Joint name=\"J1\"");
  EXPECT_EQ(text_.find("<PosLimit min=\"-90\" max=\"90\"/>", j1), text_.find("<PosLimit", j1));
  EXPECT_EQ(text_.find("<VelLimit max=\"180\"/>", j1), text_.find("<VelLimit", j1));
  // J2's placement: RPY (0, pi/2, 0) rad.
  const std::size_t j2 = at(text_, "<Joint name=\"J2\"");
  EXPECT_EQ(text_.find("<RPY>0 90 0</RPY>", j2), text_.find("<RPY>", j2));
  EXPECT_EQ(text_.find("<Pos>0.3 0 0</Pos>", j2), text_.find("<Pos>", j2));
  // Full precision.
  at(text_, "<Pos>0 0 0.12345678901234</Pos>");
  // L depends on R; its limits go to device level, as written (RobWork ignores limits inside
  // a dependent joint).
  const std::size_t l = at(text_, "<Joint name=\"L\" refframe=\"Base\" type=\"Prismatic\">");
  const std::size_t lEnd = text_.find("</Joint>", l);
  const std::size_t depend = at(text_, "<Depend on=\"R\" gain=\"-1\" offset=\"0.001\"/>");
  EXPECT_LT(l, depend);
  EXPECT_LT(depend, lEnd);
  EXPECT_GT(at(text_, "<PosLimit refjoint=\"L\" min=\"-0.04\" max=\"0\"/>"), lEnd);
  EXPECT_GT(at(text_, "<VelLimit refjoint=\"L\" max=\"0.1\"/>"), lEnd);
  EXPECT_EQ(text_.substr(l, lEnd - l).find("Limit"), std::string::npos);
}

TEST_F(WorkCellWriter, PutsNamedConfigurationsLastInADevice) {
  const std::size_t arm = at(text_, "<SerialDevice name=\"Arm\">");
  const std::size_t end = text_.find("</SerialDevice>", arm);
  const std::size_t home = at(text_, "<Q name=\"Home\">0.1 0.2</Q>");
  const std::size_t ready = at(text_, "<Q name=\"Ready\">-0.5 0.25</Q>");
  EXPECT_LT(home, ready);
  EXPECT_LT(ready, end);
  EXPECT_EQ(text_.find('<', ready + 1), text_.find("</Q>", ready));
  EXPECT_EQ(text_.find('<', text_.find("</Q>", ready) + 1), end);
  EXPECT_LT(text_.rfind("</Frame>", end), home);
  EXPECT_LT(at(text_, "<Property name=\"payload\" type=\"double\" desc=\"kg\">2.5</Property>"),
            home);
  at(text_, "<Property name=\"gains\" type=\"Q\">1 2 3</Property>");
}

TEST_F(WorkCellWriter, WritesPropertiesWithTypesAndEscapes) {
  at(text_,
     "<Property name=\"maker\" type=\"string\" desc=\"who built it\">VisGraB &amp; co "
     "&lt;test&gt;</Property>");
  at(text_, "<Property name=\"height\" type=\"double\">0.7</Property>");
  at(text_,
     "<Property name=\"corners\" type=\"Q\" desc=\"corner heights\">1 2.5 -3 1e-07</Property>");
  at(text_, "<Property name=\"author\" type=\"string\">the writer tests</Property>");
}

TEST_F(WorkCellWriter, ChoosesDrawableOrCollisionModelAndWritesMeshesRelative) {
  at(text_, "<Drawable name=\"Floor\" refframe=\"WORLD\">");
  at(text_, "<Plane/>");
  at(text_, "<Drawable name=\"Body\">");
  at(text_, "<Cylinder radius=\"0.04\" z=\"0.1\"/>");
  at(text_, "<Sphere radius=\"0.02\"/>");
  at(text_, "<Tube radius=\"0.01\" thickness=\"0.005\" z=\"0.03\"/>");
  at(text_, "<Cone radius=\"0.03\" z=\"0.02\"/>");
  at(text_, "<Box x=\"1\" y=\"0.8\" z=\"0.04\"/>");
  at(text_, "<CollisionModel name=\"Lid\">");
  at(text_, "<Drawable name=\"Handle\" colmodel=\"Disabled\">");
  at(text_, "<CollisionModel name=\"Pad\">");
  at(text_, "<Drawable name=\"Logo\" colmodel=\"Disabled\">");
  at(text_, "<Polytope file=\"../meshes/tetra.stl\"/>");
  // Without a target folder the mesh keeps its absolute path.
  const std::string absolute = writeWorkCell(*scene_.wc, {});
  at(absolute,
     "<Polytope file=\"" + std::filesystem::absolute(scene_.meshFile).generic_string() + "\"/>");
}

TEST_F(WorkCellWriter, WritesTheSetupsToFilesOfTheirOwn) {
  ASSERT_EQ(files_.setupFiles.size(), 2u);
  EXPECT_EQ(files_.setupFiles[0].first, "built.collision.xml");
  EXPECT_EQ(files_.setupFiles[1].first, "built.proximity.xml");
  at(text_, "<CollisionSetup file=\"built.collision.xml\"/>");
  at(text_, "<ProximitySetup file=\"built.proximity.xml\"/>");
  const std::string& collision = files_.setupFiles[0].second;
  at(collision, "<FramePair first=\"Grip.Base\" second=\"Grip.R\"/>");
  at(collision, "<FramePair first=\"Table\" second=\"Cup\"/>");
  at(collision, "<Volatile>Cup</Volatile>");
  at(collision, "<ExcludeStaticPairs/>");
  // The proximity file holds only the rules beyond the collision setup's excludes.
  const std::string& proximity = files_.setupFiles[1].second;
  EXPECT_EQ(proximity.find("Grip.Base"), std::string::npos) << proximity;
  const std::size_t exclude = at(proximity, "<Exclude PatternA=\"Arm.*\" PatternB=\"Arm.*\"/>");
  EXPECT_LT(exclude, at(proximity, "<Include PatternA=\"Cup\" PatternB=\"Grip.?\"/>"));
  // The string form is self-contained: it names no setup file.
  const std::string alone = writeWorkCell(*scene_.wc, dir_.path() / "out");
  EXPECT_EQ(alone.find("Setup"), std::string::npos);
}

TEST_F(WorkCellWriter, SavesTheFilesNextToEachOtherDeterministically) {
  const auto out = dir_.path() / "out" / "built.wc.xml";
  std::filesystem::create_directories(out.parent_path());
  saveWorkCell(*scene_.wc, out);
  EXPECT_EQ(readText(out), text_);
  EXPECT_EQ(readText(dir_.path() / "out" / "built.collision.xml"), files_.setupFiles[0].second);
  EXPECT_EQ(readText(dir_.path() / "out" / "built.proximity.xml"), files_.setupFiles[1].second);
  EXPECT_EQ(renderWorkCell(*scene_.wc, dir_.path() / "out", "built").workcell, text_);
}

TEST(WorkCellWriterSetups, WritesNoProximityFileWithoutExtraRules) {
  WorkCell wc("Plain");
  FrameSpec box;
  box.name = "Box";
  box.parent = FrameTree::kWorld;
  wc.frames().add(box);
  const auto files = renderWorkCell(wc, {}, "plain");
  ASSERT_EQ(files.setupFiles.size(), 1u);
  EXPECT_EQ(files.setupFiles[0].first, "plain.collision.xml");
  EXPECT_EQ(files.workcell.find("ProximitySetup"), std::string::npos);
}

TEST(WorkCellWriterSetups, SaveThrowsNamingAFileItCannotWrite) {
  WorkCell wc("Plain");
  TempDir dir;
  const auto file = dir.path() / "missing-folder" / "x.wc.xml";
  try {
    saveWorkCell(wc, file);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------- models RobWork cannot express

FrameSpec spec(std::string name, rw::kinematics::FrameId parent,
               FrameType type = FrameType::kFixed) {
  FrameSpec s;
  s.name = std::move(name);
  s.parent = parent;
  s.type = type;
  return s;
}

void expectRefusal(const WorkCell& wc, const std::string& fragment) {
  try {
    (void)writeWorkCell(wc, {});
    FAIL() << "expected std::invalid_argument mentioning " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(WorkCellWriterRefuses, ADeviceMountedOnAnotherDevicesFrame) {
  WorkCell wc("x");
  const auto a = wc.frames().add(spec("A.Base", FrameTree::kWorld));
  const auto b = wc.frames().add(spec("B.Base", a));
  wc.addDevice({"A", Device::Kind::kSerial, a, {a}, {}, {}});
  wc.addDevice({"B", Device::Kind::kSerial, b, {b}, {}, {}});
  expectRefusal(wc, "mounted on \"A.Base\" of another device");
}

TEST(WorkCellWriterRefuses, WorkcellFramesNoneOfWhichHangsOnWorld) {
  WorkCell wc("x");
  const auto a = wc.frames().add(spec("A.Base", FrameTree::kWorld));
  wc.frames().add(spec("Tool", a));
  wc.addDevice({"A", Device::Kind::kSerial, a, {a}, {}, {}});
  expectRefusal(wc, "no workcell-level frame hangs on WORLD");
}

TEST(WorkCellWriterRefuses, ASerialDeviceThatIsNotAChain) {
  WorkCell wc("x");
  const auto base = wc.frames().add(spec("S.Base", FrameTree::kWorld));
  const auto j = wc.frames().add(spec("S.J", base, FrameType::kRevolute));
  wc.frames().add(spec("S.Side", base));
  wc.addDevice({"S", Device::Kind::kSerial, base, {j}, {}, {}});
  expectRefusal(wc, "is not a chain at frame \"S.Side\"");
}

TEST(WorkCellWriterRefuses, ADeviceFrameOutsideTheDevicesScope) {
  WorkCell wc("x");
  const auto base = wc.frames().add(spec("Base", FrameTree::kWorld));
  wc.addDevice({"D", Device::Kind::kTree, base, {base}, {}, {}});
  expectRefusal(wc, "is not named \"D.<name>\"");
}

TEST(WorkCellWriterRefuses, ALimitedJointOutsideEveryDevice) {
  WorkCell wc("x");
  FrameSpec j = spec("Hinge", FrameTree::kWorld, FrameType::kRevolute);
  j.limits.lower = -1;
  j.limits.upper = 1;
  wc.frames().add(j);
  expectRefusal(wc, "belongs to no device");
}

TEST(WorkCellWriterRefuses, TreeEndsWhoseFrameOrderGivesAnotherJointOrder) {
  WorkCell wc("x");
  auto& t = wc.frames();
  const auto base = t.add(spec("T.Base", FrameTree::kWorld));
  const auto a = t.add(spec("T.A", base, FrameType::kRevolute));
  FrameSpec aEnd = spec("T.AEnd", a);
  aEnd.endEffector = true;
  const auto aEndId = t.add(aEnd);
  const auto b = t.add(spec("T.B", base, FrameType::kRevolute));
  FrameSpec bEnd = spec("T.BEnd", b);
  bEnd.endEffector = true;
  const auto bEndId = t.add(bEnd);
  wc.addDevice({"T", Device::Kind::kTree, base, {bEndId, aEndId}, {}, {}});
  expectRefusal(wc, "would give another joint order");
}

}  // namespace
