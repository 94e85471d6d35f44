// Malformed workcells: each must fail with exactly one error, at the right file and line, with
// a message that says what is wrong, and never crash, hang or throw anything but LoadError.
// Also run under AddressSanitizer+UBSan (CTest label "sanitize").
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <vector>

#include "rw/loaders/workcell_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::common::Diagnostic;
using rw::common::LoadError;
using visgrab::test::TempDir;
using visgrab::test::writeFile;

struct Case {
  const char* name;
  // Files to write (path relative to the temporary folder -> content); "main.wc.xml" is loaded.
  std::map<std::string, std::string> files;
  // Expected first (and only) error: file name (relative), line, and a piece of the message.
  std::string file;
  int line;
  std::string message;
  // A piece of the first include-chain entry, when the error is inside an included file.
  std::string includedFrom = {};
};

std::string lines(std::initializer_list<const char*> text) {
  std::string out;
  for (const char* line : text) out += std::string(line) + "\n";
  return out;
}

// A small valid device around one line of body, for cases about device content.
std::string device(const char* body) {
  return lines({"<WorkCell name=\"w\">", " <TreeDevice name=\"D\">", "  <Frame name=\"Base\"/>",
                "  <Joint name=\"J\" type=\"Revolute\"/>"}) +
         body + "\n" + lines({" </TreeDevice>", "</WorkCell>"});
}

// A small ParallelDevice: chain L (active joint J) and chain R (passive joint K) from Base;
// R's end is `reach` metres out (1 closes the loop, anything else cannot). `body` is line 7.
std::string parallel(const char* body, const char* reach = "1") {
  return lines({"<WorkCell name=\"w\">", " <ParallelDevice name=\"P\">", "  <Frame name=\"Base\"/>",
                "  <SerialChain name=\"L\"><Joint name=\"J\" type=\"Revolute\"/><Frame "
                "name=\"E\"><RPY>0 0 0</RPY><Pos>1 0 0</Pos></Frame></SerialChain>",
                "  <Frame name=\"RBase\" refframe=\"Base\"/>"}) +
         "  <SerialChain name=\"R\"><Joint name=\"K\" type=\"Revolute\" state=\"Passive\"/>"
         "<Frame name=\"E\"><RPY>0 0 0</RPY><Pos>" +
         reach + " 0 0</Pos></Frame></SerialChain>\n" + body + "\n" +
         lines({" </ParallelDevice>", "</WorkCell>"});
}

std::string workcell(const char* body) {
  return lines({"<WorkCell name=\"w\">", " <Frame name=\"Table\"/>"}) + body + "\n" +
         lines({"</WorkCell>"});
}

std::vector<Case> cases() {
  return {
      {"NotWellFormed",
       {{"main.wc.xml", lines({"<WorkCell name=\"w\">", " <Frame name=\"x\">", "</WorkCell>"})}},
       "main.wc.xml",
       3,
       "not well-formed XML: expected end of tag 'Frame' (opened at line 2)"},
      {"EmptyFile", {{"main.wc.xml", ""}}, "main.wc.xml", 1, "the file holds no element"},
      {"BinaryGarbage",
       {{"main.wc.xml", std::string("\x89PNG\r\n\x1a\n\x00\xff\xfe junk", 17)}},
       "main.wc.xml",
       1,
       "not well-formed XML"},
      {"TwoRootElements",
       {{"main.wc.xml", "<WorkCell name=\"a\"/>\n<WorkCell name=\"b\"/>\n"}},
       "main.wc.xml",
       2,
       "a workcell file has one root element"},
      {"WrongRootElement",
       {{"main.wc.xml", "<Frame name=\"x\"/>\n"}},
       "main.wc.xml",
       1,
       "<Frame> cannot be the root element"},
      {"UnknownElement",
       {{"main.wc.xml", workcell(" <Frame name=\"x\"><Foo/></Frame>")}},
       "main.wc.xml",
       3,
       "unknown element <Foo> in <Frame name=\"x\">"},
      {"UnknownAttribute",
       {{"main.wc.xml", workcell(" <Frame name=\"x\" colour=\"red\"/>")}},
       "main.wc.xml",
       3,
       "<Frame name=\"x\">: unknown attribute \"colour\""},
      {"MissingAttribute",
       {{"main.wc.xml", workcell(" <Frame refframe=\"Table\"/>")}},
       "main.wc.xml",
       3,
       "missing required attribute \"name\""},
      {"ElementInWrongPlace",
       {{"main.wc.xml", workcell(" <Frame name=\"x\"><Box x=\"1\" y=\"1\" z=\"1\"/></Frame>")}},
       "main.wc.xml",
       3,
       "<Box> is not allowed in <Frame name=\"x\">"},
      {"TextInFrame",
       {{"main.wc.xml", workcell(" <Frame name=\"x\">hello</Frame>")}},
       "main.wc.xml",
       3,
       "text is not allowed here (\"hello\")"},
      {"RpyWithTwoNumbers",
       {{"main.wc.xml", workcell(" <Frame name=\"x\"><RPY>0 0</RPY><Pos>0 0 0</Pos></Frame>")}},
       "main.wc.xml",
       3,
       "<RPY>: expected 3 numbers, got 2"},
      {"TransformWithElevenNumbers",
       {{"main.wc.xml",
         workcell(" <Frame name=\"x\"><Transform>1 0 0 0 0 1 0 0 0 0 1</Transform></Frame>")}},
       "main.wc.xml",
       3,
       "<Transform>: expected 12 numbers, got 11"},
      {"NonNumericText",
       {{"main.wc.xml", workcell(" <Frame name=\"x\"><RPY>0 0 0</RPY><Pos>0 a 0</Pos></Frame>")}},
       "main.wc.xml",
       3,
       "<Pos>: \"a\" is not a number"},
      {"NonNumericAttribute",
       {{"main.wc.xml",
         workcell(" <Drawable name=\"d\" refframe=\"Table\"><Box x=\"1\" y=\"abc\" z=\"1\"/>"
                  "</Drawable>")}},
       "main.wc.xml",
       3,
       "<Box>: attribute y: \"abc\" is not a number"},
      {"NotANumberValue",
       {{"main.wc.xml", workcell(" <Frame name=\"x\"><RPY>NaN 0 0</RPY><Pos>0 0 0</Pos></Frame>")}},
       "main.wc.xml",
       3,
       "\"NaN\" is not a finite number"},
      {"HugeNumber",
       {{"main.wc.xml",
         workcell(" <Frame name=\"x\"><RPY>0 0 0</RPY><Pos>1e999 0 0</Pos></Frame>")}},
       "main.wc.xml",
       3,
       "1e999"},
      {"LonePos",
       {{"main.wc.xml", workcell(" <Frame name=\"x\"><Pos>0 0 1</Pos></Frame>")}},
       "main.wc.xml",
       3,
       "<Pos> without <RPY>"},
      {"NegativeBoxSize",
       {{"main.wc.xml",
         workcell(" <Drawable name=\"d\" refframe=\"Table\"><Box x=\"-1\" y=\"1\" z=\"1\"/>"
                  "</Drawable>")}},
       "main.wc.xml",
       3,
       "<Box>: x must be > 0 (got -1)"},
      {"UnknownRefframe",
       {{"main.wc.xml", workcell(" <Frame name=\"Cup\" refframe=\"Tabel\"/>")}},
       "main.wc.xml",
       3,
       "unknown refframe \"Tabel\"; did you mean \"Table\"?"},
      {"UnknownModelRefframe",
       {{"main.wc.xml",
         workcell(" <Drawable name=\"d\" refframe=\"Chair\"><Sphere radius=\"1\"/></Drawable>")}},
       "main.wc.xml",
       3,
       "<Drawable name=\"d\">: unknown refframe \"Chair\""},
      {"FrameCycle",
       {{"main.wc.xml", workcell(" <Frame name=\"A\" refframe=\"B\"/>\n"
                                 " <Frame name=\"B\" refframe=\"A\"/>")}},
       "main.wc.xml",
       3,
       "frame cycle: A -> B -> A"},
      {"DuplicateName",
       {{"main.wc.xml", workcell(" <Frame name=\"Table\"/>")}},
       "main.wc.xml",
       3,
       "duplicate frame name \"Table\""},
      {"ReservedWorldName",
       {{"main.wc.xml", workcell(" <Frame name=\"WORLD\"/>")}},
       "main.wc.xml",
       3,
       "reserved for the world frame"},
      {"DuplicateDevice",
       {{"main.wc.xml", workcell(" <TreeDevice name=\"D\"><Frame name=\"B\"/></TreeDevice>\n"
                                 " <TreeDevice name=\"D\"><Frame name=\"C\"/></TreeDevice>")}},
       "main.wc.xml",
       4,
       "a device named \"D\" is already declared at line 3"},
      {"MinAboveMax",
       {{"main.wc.xml",
         device(
             "  <Joint name=\"j1\" type=\"Revolute\"><PosLimit min=\"90\" max=\"45\"/></Joint>")}},
       "main.wc.xml",
       5,
       "<Joint name=\"j1\">: <PosLimit> min 90 > max 45"},
      {"UnknownJointType",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Rotary\"/>")}},
       "main.wc.xml",
       5,
       "unknown type \"Rotary\"; expected one of Fixed, Movable, EndEffector, Revolute, Prismatic"},
      {"UnsupportedJointType",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Spherical\"/>")}},
       "main.wc.xml",
       5,
       "joint type \"Spherical\" is not supported by this project"},
      {"UnknownFrameType",
       {{"main.wc.xml", workcell(" <Frame name=\"x\" type=\"Floating\"/>")}},
       "main.wc.xml",
       3,
       "<Frame name=\"x\">: unknown type \"Floating\""},
      {"UnknownJointState",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Revolute\" state=\"Asleep\"/>")}},
       "main.wc.xml",
       5,
       "<Joint name=\"j1\">: attribute state: expected \"Active\" or \"Passive\", got \"Asleep\""},
      {"DependOnMissingJoint",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Revolute\">\n"
                               "   <Depend on=\"Nope\" gain=\"1\" offset=\"0\"/></Joint>")}},
       "main.wc.xml",
       6,
       "<Depend on=\"Nope\">: no joint \"Nope\" in scope \"D.\""},
      {"DependOnFixedFrame",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Revolute\">\n"
                               "   <Depend on=\"Base\" gain=\"1\" offset=\"0\"/></Joint>")}},
       "main.wc.xml",
       6,
       "\"D.Base\" is not a joint"},
      {"DependInFixedJoint",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Fixed\">\n"
                               "   <Depend on=\"J\" gain=\"1\" offset=\"0\"/></Joint>")}},
       "main.wc.xml",
       6,
       "only Revolute and Prismatic joints can <Depend>"},
      {"DependOnDependentJoint",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Prismatic\">"
                               "<Depend on=\"J\" gain=\"1\" offset=\"0\"/></Joint>\n"
                               "  <Joint name=\"j2\" type=\"Prismatic\">\n"
                               "   <Depend on=\"j1\" gain=\"1\" offset=\"0\"/></Joint>")}},
       "main.wc.xml",
       7,
       "\"D.j1\" depends on another joint itself"},
      {"DependOnLaterJoint",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Revolute\">\n"
                               "   <Depend on=\"j2\" gain=\"1\" offset=\"0\"/></Joint>\n"
                               "  <Joint name=\"j2\" type=\"Revolute\"/>")}},
       "main.wc.xml",
       6,
       "must be declared before the joints that depend on it"},
      {"UnknownRefjoint",
       {{"main.wc.xml", device("  <VelLimit refjoint=\"K\" max=\"1\"/>")}},
       "main.wc.xml",
       5,
       "<VelLimit refjoint=\"K\">: unknown refjoint \"D.K\""},
      {"QWithWrongCount",
       {{"main.wc.xml", device("  <Q name=\"Home\">0 0</Q>")}},
       "main.wc.xml",
       5,
       "<Q name=\"Home\">: 2 values, but device \"D\" has 1 degree of freedom"},
      {"MisspeltFrame",
       {{"main.wc.xml", workcell(" <Frme name=\"x\"/>")}},
       "main.wc.xml",
       3,
       "did you mean <Frame>?"},
      {"QInWorkCell",
       {{"main.wc.xml", workcell(" <Q name=\"Home\">0</Q>")}},
       "main.wc.xml",
       3,
       "<Q> is not allowed in <WorkCell name=\"w\">"},
      // A workcell-level element inside a device (RobWork's MARVIN cells do this): reported as
      // itself, not as an earlier child "out of order" (Xerces prints a device body's unbounded
      // choice without its repetition).
      {"CalibrationInADevice",
       {{"main.wc.xml", device("  <Calibration file=\"c.xml\"/>")}},
       "main.wc.xml",
       5,
       "<Calibration> is not allowed in <TreeDevice name=\"D\">"},
      {"DhJointWithTwoForms",
       {{"main.wc.xml",
         device("  <DHJoint name=\"j1\" alpha=\"0\" a=\"0\" d=\"0\" theta=\"0\" offset=\"0\"/>")}},
       "main.wc.xml",
       5,
       "needs exactly one of the attributes d"},
      {"MobileDevice",
       {{"main.wc.xml", workcell(" <MobileDevice name=\"M\"><Frame name=\"B\"/></MobileDevice>")}},
       "main.wc.xml",
       3,
       "<MobileDevice> is not supported by this project (SerialDevice, TreeDevice and "
       "ParallelDevice are)"},
      {"JunctionWithUnknownChain",
       {{"main.wc.xml", parallel("  <Junction><Chains>L</Chains>\n  <Chains>Nope</Chains>"
                                 "</Junction>")}},
       "main.wc.xml",
       8,
       "<Chains>: unknown SerialChain \"Nope\"; the chains of device \"P\" are: L, R"},
      {"JunctionWithOneLeg",
       {{"main.wc.xml", parallel("  <Junction><Chains>L</Chains></Junction>")}},
       "main.wc.xml",
       7,
       "<Junction>: a junction joins at least two legs (<Chains> elements), got 1"},
      {"JunctionWithEmptyChains",
       {{"main.wc.xml", parallel("  <Junction><Chains>L</Chains>\n  <Chains> </Chains>"
                                 "</Junction>")}},
       "main.wc.xml",
       8,
       "<Chains>: names no SerialChain"},
      {"JunctionLegsFromDifferentStarts",
       {{"main.wc.xml",
         parallel("  <Frame name=\"X\" refframe=\"L.E\"/><SerialChain name=\"X\"><Frame "
                  "name=\"F\"><RPY>0 0 0</RPY><Pos>0 0 1</Pos></Frame></SerialChain>\n"
                  "  <Junction><Chains>R</Chains>\n  <Chains>X</Chains></Junction>")}},
       "main.wc.xml",
       9,
       "<Chains>: the leg starts at frame \"P.L.E\", the junction's first leg at \"P.Base\"; the "
       "legs of a junction start at one frame"},
      {"JunctionChainsThatDoNotFollow",
       {{"main.wc.xml", parallel("  <Junction><Chains>R L</Chains>\n  <Chains>L</Chains>"
                                 "</Junction>")}},
       "main.wc.xml",
       7,
       "<Chains>: chain \"L\" starts at frame \"P.Base\", not at \"P.R.E\" where the leg so far "
       "ends"},
      {"JunctionLegsEndingAtOneFrame",
       {{"main.wc.xml", parallel("  <Junction><Chains>L</Chains>\n  <Chains>L</Chains>"
                                 "</Junction>")}},
       "main.wc.xml",
       8,
       "<Chains>: the leg ends at frame \"P.L.E\" like an earlier leg of the junction"},
      {"PassiveJointOnNoLeg",
       {{"main.wc.xml",
         parallel("  <Frame name=\"Y\" refframe=\"Base\"/><SerialChain name=\"Y\">\n"
                  "   <Joint name=\"F\" type=\"Revolute\" state=\"Passive\"/></SerialChain>\n"
                  "  <Junction><Chains>L</Chains><Chains>R</Chains></Junction>")}},
       "main.wc.xml",
       8,
       "<Joint name=\"F\">: a passive joint on no leg of a <Junction>; nothing determines its "
       "value"},
      {"ParallelFrameOnLaterFrame",
       {{"main.wc.xml", parallel("  <Frame name=\"Z\" refframe=\"Later\"/><Frame name=\"Later\" "
                                 "refframe=\"Base\"/>\n"
                                 "  <Junction><Chains>L</Chains><Chains>R</Chains></Junction>")}},
       "main.wc.xml",
       7,
       "<Frame name=\"Z\">: in a ParallelDevice a frame hangs on an earlier frame of the same "
       "device; \"P.Later\" is not one"},
      {"ParallelHomeThatCannotClose",
       {{"main.wc.xml", parallel("  <Junction><Chains>L</Chains><Chains>R</Chains></Junction>\n"
                                 "  <Q name=\"Home\">0.5</Q>",
                                 "2")}},
       "main.wc.xml",
       8,
       "<Q name=\"Home\">: device \"P\": junction 1 (leg \"L\", leg \"R\") cannot be closed: "
       "residual 1 m"},
      {"JunctionInTreeDevice",
       {{"main.wc.xml",
         workcell(" <TreeDevice name=\"D\"><Frame name=\"Base\"/>\n  <Junction><Chains>L</Chains>"
                  "<Chains>R</Chains></Junction></TreeDevice>")}},
       "main.wc.xml",
       4,
       "<Junction> is not allowed in <TreeDevice name=\"D\">"},
      {"CustomGeometry",
       {{"main.wc.xml", workcell(" <Drawable name=\"d\" refframe=\"Table\">"
                                 "<Custom type=\"gear\" param=\"1 2\"/></Drawable>")}},
       "main.wc.xml",
       3,
       "unknown Custom geometry type \"gear\"; this project knows \"Frustum\""},
      {"FrustumWithTwoParams",
       {{"main.wc.xml", workcell(" <Drawable name=\"d\" refframe=\"Table\">"
                                 "<Custom type=\"Frustum\" param=\"1 2\"/></Drawable>")}},
       "main.wc.xml",
       3,
       "param must be three numbers: bottom radius, top radius, height (got 2)"},
      {"FrustumWithNegativeRadius",
       {{"main.wc.xml", workcell(" <Drawable name=\"d\" refframe=\"Table\">\n"
                                 "  <Custom type=\"Frustum\" param=\"-1 2 3\"/></Drawable>")}},
       "main.wc.xml",
       4,
       "Frustum"},
      {"MissingMesh",
       {{"main.wc.xml", workcell(" <Drawable name=\"d\" refframe=\"Table\">\n"
                                 "  <Polytope file=\"meshes/nothere\"/></Drawable>")}},
       "main.wc.xml",
       4,
       "mesh \"meshes/nothere\" not found: looked in "},
      {"GarbageMesh",
       {{"main.wc.xml", workcell(" <Drawable name=\"d\" refframe=\"Table\">\n"
                                 "  <Polytope file=\"junk\"/></Drawable>")},
        {"junk.stl", "solid junk\nthis is not a mesh\n"}},
       "main.wc.xml",
       4,
       "junk.stl"},
      {"MissingInclude",
       {{"main.wc.xml", workcell(" <Include file=\"nothere.wc.xml\"/>")}},
       "main.wc.xml",
       3,
       "<Include file=\"nothere.wc.xml\">: cannot read"},
      {"IncludeOfAnUnsetVariable",
       {{"main.wc.xml", workcell(" <Include file=\"${VISGRAB_TEST_NEVER_SET}/a.xml\"/>")}},
       "main.wc.xml",
       3,
       "the environment variable VISGRAB_TEST_NEVER_SET is not set"},
      {"IncludeOfAnUnclosedVariable",
       {{"main.wc.xml", workcell(" <Include file=\"${HOME/a.xml\"/>")}},
       "main.wc.xml",
       3,
       "\"${\" without its \"}\""},
      {"IncludeCycle",
       {{"main.wc.xml", workcell(" <Include file=\"a.xml\"/>")},
        {"a.xml", "<Frame name=\"A\"/>\n<Include file=\"main.wc.xml\"/>\n"}},
       "a.xml",
       2,
       "include cycle: ",
       "main.wc.xml:3"},
      {"UseOfUnknownDefine",
       {{"main.wc.xml", workcell(" <Use id=\"nope\"/>")}},
       "main.wc.xml",
       3,
       "<Use id=\"nope\">: no <Define id=\"nope\"> before it"},
      {"DefineIsPerFile",
       {{"main.wc.xml", workcell(" <Include file=\"defs.xml\"/>\n <Use id=\"part\"/>")},
        {"defs.xml", "<Define id=\"part\"><Frame name=\"P\"/></Define>\n"}},
       "main.wc.xml",
       4,
       "no <Define id=\"part\">"},
      {"ErrorInIncludedFile",
       {{"main.wc.xml", workcell(" <Include file=\"parts/frames.xml\"/>")},
        {"parts/frames.xml",
         "<Frame name=\"A\"/>\n<Frame name=\"B\">\n <RPY>0 0</RPY>"
         "<Pos>0 0 0</Pos></Frame>\n"}},
       "frames.xml",
       3,
       "<RPY>: expected 3 numbers, got 2",
       "main.wc.xml:3"},
      {"SemanticErrorInIncludedFile",
       {{"main.wc.xml", workcell(" <Include file=\"parts/frames.xml\"/>")},
        {"parts/frames.xml", "\n\n<Frame name=\"B\" refframe=\"Nowhere\"/>\n"}},
       "frames.xml",
       3,
       "unknown refframe \"Nowhere\"",
       "main.wc.xml:3"},
      {"MisplacedIncludedElement",
       {{"main.wc.xml", workcell(" <Include file=\"limits.xml\"/>")},
        {"limits.xml", "<PosLimit refjoint=\"J\" min=\"0\" max=\"1\"/>\n"}},
       "limits.xml",
       1,
       "<PosLimit> is not allowed in <WorkCell name=\"w\">",
       "main.wc.xml:3"},
      {"TransformNotARotation",
       {{"main.wc.xml",
         workcell(" <Frame name=\"x\"><Transform>1 0 0 0 0 1 0 0 0 0 -1 0</Transform></Frame>")}},
       "main.wc.xml",
       3,
       "the 3x3 part is not a rotation"},
      {"TwoRpy",
       {{"main.wc.xml",
         workcell(" <Frame name=\"x\"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><RPY>1 1 1</RPY></Frame>")}},
       "main.wc.xml",
       3,
       "<Frame name=\"x\">: more than one <RPY>"},
      {"TransformAndRpy",
       {{"main.wc.xml", workcell(" <Frame name=\"x\">\n  <Transform>1 0 0 0 0 1 0 0 0 0 1 0"
                                 "</Transform>\n  <RPY>0 0 0</RPY></Frame>")}},
       "main.wc.xml",
       5,
       "give either <Transform> or <RPY> and <Pos>, not both"},
      {"TwoDepends",
       {{"main.wc.xml", device("  <Joint name=\"j1\" type=\"Revolute\">"
                               "<Depend on=\"J\" gain=\"1\" offset=\"0\"/>\n"
                               "   <Depend on=\"J\" gain=\"2\" offset=\"0\"/></Joint>")}},
       "main.wc.xml",
       6,
       "more than one <Depend>"},
      {"DhJointWithRpy",
       {{"main.wc.xml", device("  <DHJoint name=\"j1\" alpha=\"0\" a=\"0\" d=\"0\" offset=\"0\">"
                               "<RPY>0 0 0</RPY><Pos>0 0 0</Pos></DHJoint>")}},
       "main.wc.xml",
       5,
       "a DHJoint is placed by its DH parameters"},
      {"HgpFormWithCraigType",
       {{"main.wc.xml",
         device(
             "  <DHJoint name=\"j1\" alpha=\"0\" a=\"0\" b=\"0\" offset=\"0\" type=\"craig\"/>")}},
       "main.wc.xml",
       5,
       "the b parameter belongs to the HGP parallel convention"},
      {"UnknownDhType",
       {{"main.wc.xml",
         device(
             "  <DHJoint name=\"j1\" alpha=\"0\" a=\"0\" d=\"0\" offset=\"0\" type=\"Craig\"/>")}},
       "main.wc.xml",
       5,
       "unknown DH type \"Craig\"; expected craig, schilling or HGP"},
      {"LimitOnFixedFrame",
       {{"main.wc.xml", device("  <PosLimit refjoint=\"Base\" min=\"0\" max=\"1\"/>")}},
       "main.wc.xml",
       5,
       "<PosLimit refjoint=\"Base\">: \"D.Base\" is not a joint"},
      {"NegativeVelocityLimit",
       {{"main.wc.xml", device("  <VelLimit refjoint=\"J\" max=\"-1\"/>")}},
       "main.wc.xml",
       5,
       "max must be >= 0 (got -1)"},
      {"DeviceWithoutFrames",
       {{"main.wc.xml", workcell(" <TreeDevice name=\"E\"><Property name=\"p\">v</Property>"
                                 "</TreeDevice>")}},
       "main.wc.xml",
       3,
       "<TreeDevice name=\"E\">: the device has no frames"},
      {"WorkCellModelWithoutRefframe",
       {{"main.wc.xml",
         workcell(" <CollisionModel name=\"c\"><Sphere radius=\"1\"/></CollisionModel>")}},
       "main.wc.xml",
       3,
       "a workcell-level model needs a refframe"},
      {"BadBoolean",
       {{"main.wc.xml", workcell(" <Frame name=\"x\" daf=\"maybe\"/>")}},
       "main.wc.xml",
       3,
       "attribute daf: expected true or false, got \"maybe\""},
      {"BadColmodel",
       {{"main.wc.xml", workcell(" <Drawable name=\"d\" refframe=\"Table\" colmodel=\"Off\">"
                                 "<Plane/></Drawable>")}},
       "main.wc.xml",
       3,
       "attribute colmodel: expected \"Enabled\" or \"Disabled\", got \"Off\""},
      {"DoctypeNotSupported",
       {{"main.wc.xml", "<?xml version=\"1.0\"?>\n<!DOCTYPE WorkCell>\n<WorkCell name=\"w\"/>\n"}},
       "main.wc.xml",
       2,
       "DOCTYPE declarations are not supported"},
      {"UnterminatedComment",
       {{"main.wc.xml", "<WorkCell name=\"w\">\n<!-- no end\n</WorkCell>\n\n"}},
       "main.wc.xml",
       3,
       "unterminated comment"},
      {"ExtraClosingTag",
       {{"main.wc.xml", "<WorkCell name=\"w\">\n</WorkCell>\n</Frame>\n"}},
       "main.wc.xml",
       3,
       "closing tag without a matching start tag"},
      {"MissingCollisionSetup",
       {{"main.wc.xml", device("  <CollisionSetup file=\"nothere.prox.xml\"/>")}},
       "main.wc.xml",
       5,
       "<CollisionSetup file=\"nothere.prox.xml\">: cannot read"},
      {"CollisionSetupUnknownTag",
       {{"main.wc.xml", device("  <CollisionSetup file=\"cs.prox.xml\"/>")},
        {"cs.prox.xml",
         "<CollisionSetup>\n <Exclude>\n  <FramePair first=\"Base\" "
         "second=\"J\"/>\n </Exclude>\n <Excluded/>\n</CollisionSetup>\n"}},
       "cs.prox.xml",
       5,
       "unknown element <Excluded> in <CollisionSetup>",
       "main.wc.xml:5"},
      {"ColourOutOfRange",
       {{"main.wc.xml", workcell(" <Drawable name=\"d\" refframe=\"Table\"><RGB>1.5 0 0</RGB>"
                                 "<Box x=\"1\" y=\"1\" z=\"1\"/></Drawable>")}},
       "main.wc.xml",
       3,
       "<RGB>: colour components must be in [0, 1]"},
      {"TwoColours",
       {{"main.wc.xml",
         workcell(" <Drawable name=\"d\" refframe=\"Table\"><RGB>1 0 0</RGB><RGB>0 1 0</RGB>"
                  "<Box x=\"1\" y=\"1\" z=\"1\"/></Drawable>")}},
       "main.wc.xml",
       3,
       "more than one <RGB>"},
      {"ProximitySetupUnknownTag",
       {{"main.wc.xml", device("  <ProximitySetup file=\"p.xml\"/>")},
        {"p.xml",
         "<ProximitySetup>\n <Exclude PatternA=\"*\" PatternB=\"*\"/>\n <Ignore/>\n"
         "</ProximitySetup>\n"}},
       "p.xml",
       3,
       "unknown element <Ignore> in <ProximitySetup>",
       "main.wc.xml:5"},
  };
}

class MalformedWorkCell : public ::testing::TestWithParam<Case> {};

TEST_P(MalformedWorkCell, ReportsExactlyOneErrorAtTheRightPlace) {
  const Case& c = GetParam();
  TempDir dir;
  for (const auto& [path, text] : c.files) writeFile(dir.path() / path, text);
  const auto main = dir.path() / "main.wc.xml";
  std::vector<Diagnostic> diagnostics;
  try {
    rw::loaders::loadWorkCell(main);
    FAIL() << "loaded without error";
  } catch (const LoadError& e) {
    diagnostics = e.diagnostics();
  }
  std::vector<Diagnostic> errors;
  for (const Diagnostic& d : diagnostics) {
    if (d.severity == Diagnostic::Severity::kError) errors.push_back(d);
  }
  ASSERT_EQ(errors.size(), 1u) << [&] {
    std::string all;
    for (const Diagnostic& d : errors) all += d.format() + "\n";
    return all;
  }();
  const Diagnostic& error = errors.front();
  EXPECT_EQ(std::filesystem::path(error.file).filename(), c.file) << error.format();
  EXPECT_EQ(error.line, c.line) << error.format();
  EXPECT_NE(error.message.find(c.message), std::string::npos) << error.format();
  if (c.includedFrom.empty()) {
    EXPECT_TRUE(error.includedFrom.empty()) << error.format();
  } else {
    ASSERT_FALSE(error.includedFrom.empty()) << error.format();
    EXPECT_NE(error.includedFrom.front().find(c.includedFrom), std::string::npos) << error.format();
  }
  // checkWorkCell reports the same, without throwing.
  const auto checked = rw::loaders::checkWorkCell(main);
  ASSERT_FALSE(checked.empty());
  std::size_t checkedErrors = 0;
  for (const Diagnostic& d : checked) {
    if (d.severity == Diagnostic::Severity::kError) ++checkedErrors;
  }
  EXPECT_EQ(checkedErrors, 1u);
}

INSTANTIATE_TEST_SUITE_P(Table, MalformedWorkCell, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return std::string(param.param.name);
                         });

std::size_t errorCount(const std::vector<Diagnostic>& diagnostics) {
  std::size_t n = 0;
  for (const Diagnostic& d : diagnostics) n += d.severity == Diagnostic::Severity::kError;
  return n;
}

TEST(MalformedWorkCellInput, MissingFileIsOneError) {
  TempDir dir;
  const auto diagnostics = rw::loaders::checkWorkCell(dir.path() / "nothere.wc.xml");
  ASSERT_EQ(errorCount(diagnostics), 1u);
  EXPECT_NE(diagnostics[0].message.find("no such file"), std::string::npos);
  EXPECT_THROW(rw::loaders::loadWorkCell(dir.path()), LoadError);  // a folder
}

TEST(MalformedWorkCellInput, TenMegabytesOfGarbageFailQuickly) {
  TempDir dir;
  std::mt19937 random(12345);
  std::string garbage(10u << 20, '\0');
  for (char& c : garbage) c = static_cast<char>(random() & 0xFF);
  const auto file = writeFile(dir.path() / "garbage.wc.xml", garbage);
  const auto diagnostics = rw::loaders::checkWorkCell(file);
  EXPECT_EQ(errorCount(diagnostics), 1u);
  // Printable garbage that is text inside a valid root.
  const auto text =
      writeFile(dir.path() / "text.wc.xml",
                "<WorkCell name=\"w\">" + std::string(10u << 20, 'x') + "</WorkCell>");
  const auto textDiagnostics = rw::loaders::checkWorkCell(text);
  ASSERT_EQ(errorCount(textDiagnostics), 1u);
  EXPECT_NE(textDiagnostics[0].message.find("text is not allowed"), std::string::npos);
}

TEST(MalformedWorkCellInput, DeepIncludeChainsStop) {
  TempDir dir;
  for (int i = 0; i < 40; ++i) {
    writeFile(dir.path() / ("inc" + std::to_string(i) + ".xml"),
              "<Include file=\"inc" + std::to_string(i + 1) + ".xml\"/>\n");
  }
  writeFile(dir.path() / "inc40.xml", "<Frame name=\"Deep\"/>\n");
  const auto main = writeFile(dir.path() / "main.wc.xml",
                              "<WorkCell name=\"w\">\n<Include file=\"inc0.xml\"/>\n</WorkCell>\n");
  const auto diagnostics = rw::loaders::checkWorkCell(main);
  ASSERT_EQ(errorCount(diagnostics), 1u);
  EXPECT_NE(diagnostics[0].message.find("nested deeper than 32"), std::string::npos);
  EXPECT_EQ(diagnostics[0].includedFrom.size(), 32u);
}

TEST(MalformedWorkCellInput, ExponentialDefineUseIsBounded) {
  std::string xml = "<WorkCell name=\"w\">\n<Define id=\"d0\"><Frame name=\"f\"/></Define>\n";
  for (int i = 1; i <= 30; ++i) {
    const std::string prev = "d" + std::to_string(i - 1);
    xml += "<Define id=\"d" + std::to_string(i) + "\"><Use id=\"" + prev + "\"/><Use id=\"" + prev +
           "\"/></Define>\n";
  }
  xml += "<Use id=\"d30\"/>\n</WorkCell>\n";
  TempDir dir;
  try {
    rw::loaders::loadWorkCellFromString(xml, dir.path() / "bomb.wc.xml");
    FAIL() << "loaded";
  } catch (const LoadError& e) {
    EXPECT_EQ(errorCount(e.diagnostics()), 1u) << e.what();
    EXPECT_NE(std::string(e.what()).find("grows beyond"), std::string::npos) << e.what();
  }
}

TEST(MalformedWorkCellInput, DeeplyNestedElementsStop) {
  std::string xml = "<WorkCell name=\"w\">";
  for (int i = 0; i < 5000; ++i) xml += "<Define id=\"x\">";
  TempDir dir;
  EXPECT_THROW(rw::loaders::loadWorkCellFromString(xml, dir.path() / "deep.wc.xml"), LoadError);
}

TEST(MalformedWorkCellInput, RandomMutationsNeverCrash) {
  const std::string good = R"(<WorkCell name="w">
 <Frame name="Table"><RPY>0 0 0</RPY><Pos>0 0 0.7</Pos>
  <Drawable name="T"><Box x="1" y="1" z="0.04"/></Drawable></Frame>
 <TreeDevice name="D"><Frame name="Base" type="Movable"/>
  <Joint name="J" type="Revolute"><PosLimit min="-90" max="90"/></Joint>
  <Joint name="K" type="Revolute"><Depend on="J" gain="-1" offset="0"/></Joint>
  <Define id="x"><Frame name="E" type="EndEffector"/></Define><Use id="x"/>
  <Q name="Home">0</Q></TreeDevice>
</WorkCell>)";
  TempDir dir;
  std::mt19937 random(7);
  for (int round = 0; round < 300; ++round) {
    std::string text = good;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = random() % text.size();
      switch (random() % 3) {
        case 0:
          text.erase(at, 1 + random() % 5);
          break;
        case 1:
          text.insert(at, 1, "<>\"/= a0.-9x"[random() % 12]);
          break;
        default:
          text[at] = static_cast<char>(random() & 0xFF);
          break;
      }
    }
    try {
      rw::loaders::loadWorkCellFromString(text, dir.path() / "m.wc.xml");
    } catch (const LoadError& e) {
      EXPECT_GE(errorCount(e.diagnostics()), 1u);
    }
  }
}

}  // namespace
