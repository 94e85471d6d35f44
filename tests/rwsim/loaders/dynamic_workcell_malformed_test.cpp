// Malformed dynamic workcells: each gives exactly one error, at the right file and line, with a
// message that says what was expected. Also run under AddressSanitizer+UBSan (label sanitize).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "rwsim/loaders/dwc_test_scene.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::common::Diagnostic;
using visgrab::test::dwc::SceneDir;
using visgrab::test::dwc::sdhController;
using visgrab::test::dwc::sdhDevice;

/// One malformed input.
struct Case {
  /// Test name.
  std::string name;
  /// The top-level file (written as top.dwc.xml next to scene.wc.xml and materials.xml).
  std::string top;
  /// Further files (name relative to the folder -> content).
  std::map<std::string, std::string> files;
  /// The file the error is in (relative to the folder).
  std::string errorFile = "top.dwc.xml";
  /// The error's line: the line of the first occurrence of this text in the error's file.
  std::string atText;
  /// Text the message must contain.
  std::string message;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

/// Line of the first occurrence of `text` in `content` (0 if absent).
int lineOf(const std::string& content, const std::string& text) {
  const auto at = content.find(text);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(
                 std::count(content.begin(), content.begin() + static_cast<long>(at), '\n'));
}

std::string rigidObject(const std::string& inside) {
  return "<RigidBody frame=\"Object\">\n<Integrator>Euler</Integrator>\n" + inside +
         "</RigidBody>\n";
}

/// The start of an executable file: not XML at all.
constexpr char kGarbage[] =
    "\x7f"
    "ELF\x02\x01\x01\0\0\0<\xff\xfe>\n";

const std::string kEstimate = "<Mass>0.5</Mass><EstimateInertia/>\n";

/// The table (fixed), the object (rigid) and the ghost (kinematic), then `constraints`.
std::string withConstraints(const std::string& constraints) {
  return SceneDir::dwc("<FixedBody frame=\"Table\"/>\n" + rigidObject(kEstimate) +
                       "<KinematicBody frame=\"Ghost\"><MaterialID>Plastic</MaterialID>"
                       "</KinematicBody>\n" +
                       constraints);
}

/// A <Constraint name="C" type=TYPE parent="Table" child="Object"> holding `inside`.
std::string constraint(const std::string& type, const std::string& inside,
                       const std::string& name = "C") {
  return "<Constraint name=\"" + name + "\" type=\"" + type +
         "\" parent=\"Table\" child=\"Object\">\n" + inside + "</Constraint>\n";
}

std::vector<Case> cases() {
  const std::string sdhWithBadJoint =
      sdhDevice("",
                "<RigidJoint joint=\"f4.Joint2\"><Mass>0.1</Mass><EstimateInertia/>"
                "</RigidJoint>\n");
  return {
      {"MissingWorkCellFile",
       "<DynamicWorkcell workcell=\"nowhere.wc.xml\">\n</DynamicWorkcell>\n",
       {},
       "top.dwc.xml",
       "<DynamicWorkcell",
       "cannot read the workcell file"},
      {"UnknownElement",
       SceneDir::dwc("<Gravity>0 0 -9.8</Gravity>\n<Wind>1 0 0</Wind>\n"),
       {},
       "top.dwc.xml",
       "<Wind>",
       "unknown element <Wind>"},
      {"MisspeltElement",
       SceneDir::dwc("<Gravty>0 0 -9.8</Gravty>\n"),
       {},
       "top.dwc.xml",
       "<Gravty>",
       "unknown element <Gravty> in <DynamicWorkcell>; did you mean <Gravity>?"},
      {"MissingMass",
       SceneDir::dwc(rigidObject("<EstimateInertia/>\n")),
       {},
       "top.dwc.xml",
       "<RigidBody",
       "missing <Mass>"},
      {"NegativeMass",
       SceneDir::dwc(rigidObject("<Mass>-0.5</Mass><EstimateInertia/>\n")),
       {},
       "top.dwc.xml",
       "<Mass>",
       "the mass must be > 0 kg, got -0.5"},
      {"MassIsNotANumber",
       SceneDir::dwc(rigidObject("<Mass>heavy</Mass><EstimateInertia/>\n")),
       {},
       "top.dwc.xml",
       "<Mass>",
       "\"heavy\" is not a number"},
      {"UnknownMaterial",
       SceneDir::dwc(rigidObject(kEstimate + "<MaterialID>Steel</MaterialID>\n")),
       {},
       "top.dwc.xml",
       "<MaterialID>",
       "unknown material \"Steel\""},
      {"UnknownObjectType",
       SceneDir::dwc(rigidObject(kEstimate + "<ObjectID>glass</ObjectID>\n")),
       {},
       "top.dwc.xml",
       "<ObjectID>",
       "unknown object type \"glass\""},
      {"MissingForceLimitOfTheDependentJoint",
       SceneDir::dwc(sdhDevice("F3Joint1") + sdhController()),
       {},
       "top.dwc.xml",
       "<RigidDevice",
       "missing <ForceLimit joint=\"F3Joint1\">"},
      {"RigidJointOnAnUnknownJoint",
       SceneDir::dwc(sdhWithBadJoint),
       {},
       "top.dwc.xml",
       "joint=\"f4.Joint2\"><Mass>",
       "\"f4.Joint2\" is not a joint of device \"SchunkHand\""},
      {"ForceLimitOnAnUnknownJoint",
       SceneDir::dwc(sdhDevice("", "<ForceLimit joint=\"Thumb\">1</ForceLimit>\n")),
       {},
       "top.dwc.xml",
       "joint=\"Thumb\"",
       "\"Thumb\" is not a joint of device"},
      {"KinematicBodyOnAFixedFrame",
       SceneDir::dwc("<KinematicBody frame=\"Table\"><MaterialID>Plastic</MaterialID>"
                     "</KinematicBody>\n"),
       {},
       "top.dwc.xml",
       "<KinematicBody",
       "frame \"Table\" is Fixed; a KinematicBody needs a "
       "Movable frame"},
      {"RigidBodyOnAnUnknownFrame",
       SceneDir::dwc("<RigidBody frame=\"Nothing\"><Integrator>Euler</Integrator>" + kEstimate +
                     "</RigidBody>\n"),
       {},
       "top.dwc.xml",
       "<RigidBody",
       "unknown frame \"Nothing\""},
      {"PDParamsWithTheWrongCount",
       SceneDir::dwc(sdhDevice() + sdhController(6)),
       {},
       "top.dwc.xml",
       "<PDParams>",
       "expected 14 numbers (a P and a D gain for each of the 7 DOF"},
      {"SyncTrueIsNotSupported",
       SceneDir::dwc(sdhDevice() + sdhController(7, "True")),
       {},
       "top.dwc.xml",
       "<Sync>",
       "not supported"},
      {"ControllerForADeviceWithoutRigidDevice",
       SceneDir::dwc(sdhController()),
       {},
       "top.dwc.xml",
       "<PDDeviceController",
       "device \"SchunkHand\" has no <RigidDevice>"},
      {"RigidDeviceWithoutBase",
       SceneDir::dwc("<RigidDevice device=\"SchunkHand\">\n<ForceLimit joint=\"F2Joint1\">1"
                     "</ForceLimit>\n</RigidDevice>\n"),
       {},
       "top.dwc.xml",
       "<RigidDevice",
       "missing base"},
      {"RigidDeviceOnAnUnknownDevice",
       SceneDir::dwc("<RigidDevice device=\"Robotiq\">\n<FixedBase frame=\"Base\"/>\n"
                     "</RigidDevice>\n"),
       {},
       "top.dwc.xml",
       "<RigidDevice",
       "unknown device \"Robotiq\""},
      {"IncludeOfAMissingFile",
       SceneDir::dwc("<Include file=\"missing.xml\"/>\n"),
       {},
       "top.dwc.xml",
       "missing.xml",
       "cannot read"},
      {"IncludeOfADynamicWorkcell",
       SceneDir::dwc("<Include file=\"other.dwc.xml\"/>\n"),
       {{"other.dwc.xml",
         "<!-- a whole scene -->\n<DynamicWorkcell workcell=\"scene.wc.xml\">\n"
         "</DynamicWorkcell>\n"}},
       "other.dwc.xml",
       "<DynamicWorkcell",
       "the root element must be <IncludeData>"},
      {"IncludeCycle",
       SceneDir::dwc("<Include file=\"loop.xml\"/>\n"),
       {{"loop.xml", "<IncludeData>\n  <Include file=\"loop.xml\"/>\n</IncludeData>\n"}},
       "loop.xml",
       "<Include file",
       "includes itself"},
      {"IncludeDataAsTheTopLevelFile",
       "<IncludeData>\n<Gravity>0 0 -9.8</Gravity>\n</IncludeData>\n",
       {},
       "top.dwc.xml",
       "<IncludeData>",
       "a file meant to be included"},
      {"UnclosedElementAtTheEnd",
       "<DynamicWorkcell workcell=\"scene.wc.xml\">\n<Include file=\"materials.xml\"/>\n"
       "<RigidBody frame=\"Object\">\n<Mass>1</Mass>\n",
       {},
       "top.dwc.xml",
       "<RigidBody",
       "<RigidBody> is not closed before the end of the file"},
      {"ClosingTagWithoutStartTag",
       SceneDir::dwc("") + "</Extra>\n",
       {},
       "top.dwc.xml",
       "</Extra>",
       "closing tag without a matching start tag"},
      {"BinaryGarbage",
       std::string(kGarbage, sizeof kGarbage - 1),
       {},
       "top.dwc.xml",
       "ELF",
       "not well-formed XML: byte 0x02 is not allowed"},
      {"InertiaWithFourValues",
       SceneDir::dwc(rigidObject("<Mass>1</Mass><COG>0 0 0</COG>\n<Inertia>1 1 1 1</Inertia>\n")),
       {},
       "top.dwc.xml",
       "<Inertia>",
       "expected 3 numbers (the diagonal) or 9 (row-major), got 4"},
      {"InertiaNotPositiveDefinite",
       SceneDir::dwc(rigidObject("<Mass>1</Mass><COG>0 0 0</COG>\n<Inertia>1 0 0  0 1 0  0 0 "
                                 "-1</Inertia>\n")),
       {},
       "top.dwc.xml",
       "<Inertia>",
       "not positive definite"},
      {"InertiaNotSymmetric",
       SceneDir::dwc(rigidObject("<Mass>1</Mass><COG>0 0 0</COG>\n<Inertia>1 0.5 0  0 1 0  0 0 "
                                 "1</Inertia>\n")),
       {},
       "top.dwc.xml",
       "<Inertia>",
       "not symmetric"},
      {"InertiaWithoutCog",
       SceneDir::dwc(rigidObject("<Mass>1</Mass><Inertia>1 1 1</Inertia>\n")),
       {},
       "top.dwc.xml",
       "<RigidBody",
       "<Inertia> needs a <COG>"},
      {"NeitherEstimateNorInertia",
       SceneDir::dwc(rigidObject("<Mass>1</Mass>\n")),
       {},
       "top.dwc.xml",
       "<RigidBody",
       "expected <EstimateInertia/> or <COG> with <Inertia>"},
      {"GravityWithTwoNumbers",
       SceneDir::dwc("<Gravity>0 -9.8</Gravity>\n"),
       {},
       "top.dwc.xml",
       "<Gravity>",
       "expected 3 numbers"},
      {"UnknownPropertyType",
       SceneDir::dwc("<PhysicsEngine>\n<Property name=\"x\" type=\"bool\">1</Property>\n"
                     "</PhysicsEngine>\n"),
       {},
       "top.dwc.xml",
       "<Property",
       "unknown type \"bool\" (expected string, int, float or Q)"},
      {"IntPropertyNotAnInteger",
       SceneDir::dwc("<PhysicsEngine>\n<Property name=\"x\" type=\"int\">2.5</Property>\n"
                     "</PhysicsEngine>\n"),
       {},
       "top.dwc.xml",
       "<Property",
       "<Property name=\"x\">: expected an integer from -2147483648 to 2147483647, got \"2.5\""},
      {"AutoDisableNotABoolean",
       SceneDir::dwc("<PhysicsEngine>\n<AutoDisable>maybe</AutoDisable>\n</PhysicsEngine>\n"),
       {},
       "top.dwc.xml",
       "<AutoDisable>",
       "expected true or false"},
      {"UndeclaredDefaultMaterial",
       "<DynamicWorkcell workcell=\"scene.wc.xml\">\n<MaterialData>\n<Default>Wood</Default>\n"
       "<Material id=\"Plastic\"/>\n</MaterialData>\n</DynamicWorkcell>\n",
       {},
       "top.dwc.xml",
       "<Default>",
       "the default material \"Wood\" is not declared"},
      {"NoMaterialAndNoDefault",
       "<DynamicWorkcell workcell=\"scene.wc.xml\">\n<FixedBody frame=\"Table\"/>\n"
       "</DynamicWorkcell>\n",
       {},
       "top.dwc.xml",
       "<FixedBody",
       "no <MaterialID> and no default material"},
      {"TwoBodiesOnOneFrame",
       SceneDir::dwc("<FixedBody frame=\"Table\"/>\n<FixedBody frame=\"Table\"><MaterialID>"
                     "Rubber</MaterialID></FixedBody>\n"),
       {},
       "top.dwc.xml",
       "<FixedBody frame=\"Table\"><Mat",
       "already carries the body"},
      {"FixedBodyWithoutGeometry",
       SceneDir::dwc("<FixedBody frame=\"Mount\"/>\n"),
       {},
       "top.dwc.xml",
       "<FixedBody",
       "has no collision geometry"},
      {"UnknownConstraintType",
       withConstraints(constraint("Hinge", "")),
       {},
       "top.dwc.xml",
       "<Constraint name=\"C\"",
       "unknown type \"Hinge\" (expected Fixed, Prismatic, Revolute, Universal, Spherical, Piston, "
       "PrismaticRotoid, PrismaticUniversal, Free; any case)"},
      {"ConstraintOnAnUnknownBody",
       withConstraints("<Constraint name=\"C\" type=\"Fixed\" parent=\"Table\" "
                       "child=\"Nothing\"/>\n"),
       {},
       "top.dwc.xml",
       "<Constraint name=\"C\"",
       "unknown child body \"Nothing\" (expected the frame name of a RigidBody"},
      {"ConstraintWithParentAsChild",
       withConstraints("<Constraint name=\"C\" type=\"Fixed\" parent=\"Object\" "
                       "child=\"Object\"/>\n"),
       {},
       "top.dwc.xml",
       "<Constraint name=\"C\"",
       "parent and child are the same body \"Object\"; expected two different bodies"},
      {"ConstraintBetweenTwoBodiesThatCannotMove",
       withConstraints("<Constraint name=\"C\" type=\"Revolute\" parent=\"Table\" "
                       "child=\"Ghost\"/>\n"),
       {},
       "top.dwc.xml",
       "<Constraint name=\"C\"",
       "parent \"Table\" is fixed and child \"Ghost\" is kinematic; expected at least one rigid "
       "body"},
      {"TwoConstraintsOfOneName",
       withConstraints(constraint("Fixed", "") +
                       "<Constraint name=\"C\" type=\"Spherical\" parent=\"Object\" "
                       "child=\"Ghost\"/>\n"),
       {},
       "top.dwc.xml",
       "<Constraint name=\"C\" type=\"Spherical\"",
       "a second constraint named \"C\" (the first is at line 9)"},
      {"ConstraintLimitsNotOnePerDof",
       withConstraints(constraint("Revolute",
                                  "<Limits>\n<Limit low=\"-1\"/>\n<Limit high=\"1\"/>\n"
                                  "</Limits>\n")),
       {},
       "top.dwc.xml",
       "<Limits>",
       "expected 1 <Limit> (one per free DOF of a Revolute constraint: rotation about z), got 2"},
      {"ConstraintLimitLowAboveHigh",
       withConstraints(
           constraint("Prismatic", "<Limits>\n<Limit low=\"0.5\" high=\"0.1\"/>\n</Limits>\n")),
       {},
       "top.dwc.xml",
       "<Limit low",
       "low 0.5 > high 0.1; expected low <= high"},
      {"ConstraintAngularLimitBeyondPi",
       withConstraints(constraint("Piston",
                                  "<Limits>\n<Limit low=\"-1\" high=\"1\"/>\n"
                                  "<Limit high=\"4\"/>\n</Limits>\n")),
       {},
       "top.dwc.xml",
       "<Limit high=\"4\"",
       "an angular limit must lie in [-pi, pi] rad"},
      {"SphericalConstraintWithLimits",
       withConstraints(
           constraint("Spherical", "<Limits>\n<Limit/>\n<Limit/>\n<Limit/>\n</Limits>\n")),
       {},
       "top.dwc.xml",
       "<Limits>",
       "a Spherical constraint takes no limits"},
      {"ConstraintSpringMatrixOfTheWrongSize",
       withConstraints(constraint("Universal",
                                  "<Spring>\n<Compliance>1 0 0 1</Compliance>\n"
                                  "<Damping>1 0 0</Damping>\n</Spring>\n")),
       {},
       "top.dwc.xml",
       "<Damping>",
       "expected 4 numbers (a 2 x 2 matrix for the free DOF of a Universal constraint), got 3"},
      {"ConstraintSpringIsNotSupportedYet",
       withConstraints(constraint("Revolute",
                                  "<Spring>\n<Compliance>0.001</Compliance>\n"
                                  "<Damping>0.1</Damping>\n</Spring>\n")),
       {},
       "top.dwc.xml",
       "<Spring>",
       "springs on constraints are not supported yet"},
      {"ConstraintRotationThatIsNoRotation",
       withConstraints(constraint("Fixed",
                                  "<Transform3D>\n<Rotation3D>1 0 0 0 1 0 0 0 2</Rotation3D>\n"
                                  "</Transform3D>\n")),
       {},
       "top.dwc.xml",
       "<Rotation3D>",
       "not a rotation matrix"},
      {"ErrorInTheWorkCell",
       "<DynamicWorkcell workcell=\"broken.wc.xml\">\n</DynamicWorkcell>\n",
       {{"broken.wc.xml",
         "<WorkCell name=\"B\">\n  <Frame name=\"A\"/>\n  <Frame name=\"C\" "
         "refframe=\"Nowhere\"/>\n</WorkCell>\n"}},
       "broken.wc.xml",
       "<Frame name=\"C\"",
       "unknown refframe \"Nowhere\""},
  };
}

class MalformedDynamicWorkCell : public ::testing::TestWithParam<Case> {};

TEST_P(MalformedDynamicWorkCell, GivesOneErrorAtTheRightPlace) {
  const Case& c = GetParam();
  SceneDir scene;
  for (const auto& [name, content] : c.files)
    visgrab::test::writeFile(scene.path() / name, content);
  const auto top = scene.writeTop(c.top);
  const std::string& errorText = c.errorFile == "top.dwc.xml" ? c.top : c.files.at(c.errorFile);
  const int line = lineOf(errorText, c.atText);
  ASSERT_GT(line, 0) << "the test's atText is not in " << c.errorFile;
  try {
    (void)rwsim::loaders::loadDynamicWorkCell(top);
    FAIL() << "loaded without error";
  } catch (const rw::common::LoadError& e) {
    std::vector<Diagnostic> errors;
    for (const Diagnostic& d : e.diagnostics()) {
      if (d.severity == Diagnostic::Severity::kError) errors.push_back(d);
    }
    ASSERT_EQ(errors.size(), 1u) << e.what();
    const Diagnostic& error = errors.front();
    EXPECT_EQ(error.file, (scene.path() / c.errorFile).string()) << e.what();
    EXPECT_EQ(error.line, line) << e.what();
    EXPECT_GT(error.column, 0) << e.what();
    EXPECT_NE(error.message.find(c.message), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.errorFile + ":" + std::to_string(line)),
              std::string::npos)
        << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Table, MalformedDynamicWorkCell, ::testing::ValuesIn(cases()),
                         [](const auto& param) { return param.param.name; });

TEST(MalformedDynamicWorkCellFile, AMissingFileIsOneError) {
  visgrab::test::TempDir dir;
  try {
    (void)rwsim::loaders::loadDynamicWorkCell(dir.path() / "none.dwc.xml");
    FAIL() << "loaded";
  } catch (const rw::common::LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_NE(e.diagnostics()[0].message.find("no such file"), std::string::npos);
  }
  EXPECT_THROW((void)rwsim::loaders::loadDynamicWorkCell(""), rw::common::LoadError);
}

TEST(MalformedDynamicWorkCellFile, ErrorsInTheWorkCellNameTheDynamicWorkCell) {
  SceneDir scene;
  visgrab::test::writeFile(
      scene.path() / "broken.wc.xml",
      "<WorkCell name=\"B\">\n<Frame name=\"A\"/>\n<Frame name=\"C\" refframe=\"X\"/>\n"
      "</WorkCell>\n");
  try {
    (void)rwsim::loaders::loadDynamicWorkCell(
        scene.writeTop("<DynamicWorkcell workcell=\"broken.wc.xml\">\n</DynamicWorkcell>\n"));
    FAIL() << "loaded";
  } catch (const rw::common::LoadError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    const auto& chain = e.diagnostics().front().includedFrom;
    ASSERT_FALSE(chain.empty());
    EXPECT_EQ(chain.back(), (scene.path() / "top.dwc.xml").string() + ":1");
  }
}

}  // namespace
