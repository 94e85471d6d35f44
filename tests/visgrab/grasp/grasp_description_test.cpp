// The hands' grasp descriptions: loading, the SDH's pre-shapes and torque rule against the
// reference's numbers, and one file:line error per malformed description.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "grasp_test_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"

namespace {

using rw::math::Q;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;
using visgrab::grasp::HandGraspSetup;
using visgrab::grasp::loadHandGraspSetupFromString;
using visgrab::grasp::resolve;
using visgrab::grasp::ResolvedGrasp;
using visgrab::grasp::ResolveStatus;
using visgrab::test::grasp::kDeg;
using visgrab::test::grasp::makeQ;
using visgrab::test::grasp::pg70;
using visgrab::test::grasp::sdh;

TEST(GraspDescription, SdhLoads) {
  const HandGraspSetup& s = sdh();
  EXPECT_EQ(s.deviceName(), "SchunkHand");
  EXPECT_EQ(s.controllerName(), "GraspController");
  EXPECT_EQ(s.tcpFrameName(), "SchunkHand.SDHTCP");
  EXPECT_EQ(s.dof(), 7);
  EXPECT_NEAR(s.X_base_tcp().translation().z(), 0.15, 1e-12);
  ASSERT_NE(s.contactIk(), nullptr);
  EXPECT_EQ(s.contactIk()->fingertips.size(), 3u);
  EXPECT_EQ(s.contactIk()->grasps.size(), 2u);
}

TEST(GraspDescription, SdhPreshapesAreVisGraBs) {
  // Reference §7.1 (radians; q order f1.J2, f1.J3, spread, f2.J2, f2.J3, f3.J2, f3.J3).
  struct Expected {
    const char* name;
    const char* alias;
    Q open;
    Q closed;
  };
  const Q parClosed = makeQ({-1.571, -1.571, 1.571, 0.0, 0.419, 0.0, 0.419});
  const Expected expected[] = {
      {"SDH_PAR", "par", makeQ({-1.571, -1.571, 1.571, -1.048, 0.174, -1.048, 0.174}), parClosed},
      {"SDH_PAR1", "SDH_PAR1_TABLE", makeQ({-1.571, -1.571, 1.571, -0.296, 0.240, -0.296, 0.240}),
       parClosed},
      {"SDH_PAR2", "SDH_PAR2_TABLE", makeQ({-1.571, -1.571, 1.571, -0.1, 0.1, -0.1, 0.1}),
       parClosed},
      {"SDH_BALL", "ball", makeQ({-1.048, 0.174, 1.047, -1.048, 0.174, -1.048, 0.174}),
       makeQ({0.0, 0.349, 1.047, 0.0, 0.349, 0.0, 0.349})},
      {"SDH_CYL", "cyl", makeQ({-1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174}),
       makeQ({0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349})},
  };
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.name);
    const auto* p = sdh().findPreshape(e.name);
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(sdh().findPreshape(e.alias), p);
    EXPECT_EQ(p->qOpen, e.open);
    EXPECT_EQ(p->qClosed, e.closed);
  }
  // Their torque limits by the rule (worked by hand): CYL spread 0 -> fingers 2, 3 get 1.0;
  // BALL spread 1.047 -> thumb 4 cos(1.047); PAR spread 1.571 -> thumb 0.2.
  EXPECT_VECTOR_NEAR(sdh().findPreshape("cyl")->tauMax, makeQ({2, 2, 10, 1, 2, 1, 2}), 1e-12);
  EXPECT_VECTOR_NEAR(sdh().findPreshape("ball")->tauMax,
                     makeQ({4 * std::cos(1.047), 2, 10, 2, 2, 2, 2}), 1e-12);
  EXPECT_VECTOR_NEAR(sdh().findPreshape("par")->tauMax, makeQ({0.2, 2, 10, 2, 2, 2, 2}), 1e-12);
}

// VisGraB's rule (reference §7.1), written out here independently of the description.
Q visgrabTau(double spread) {
  Q tau = makeQ({2, 2, 10, 2, 2, 2, 2});
  if (spread < 45 * kDeg) {
    tau[3] = tau[5] = tau[0] / (2 * std::cos(spread));
  } else {
    tau[0] = std::max(2 * std::cos(spread) * tau[3], 0.2);
  }
  return tau;
}

TEST(GraspDescription, SdhTauRuleMatchesVisGraB) {
  const auto q = [](double spread) { return makeQ({0.1, 0.2, spread, 0.3, 0.4, 0.5, 0.6}); };
  const auto& rule = sdh().tauRule();
  EXPECT_NEAR(rule.evaluate(q(0.0))[3], 1.0, 1e-12);
  EXPECT_NEAR(rule.evaluate(q(0.0))[5], 1.0, 1e-12);
  EXPECT_NEAR(rule.evaluate(q(30 * kDeg))[3], 1.1547005, 1e-6);
  EXPECT_NEAR(rule.evaluate(q(60 * kDeg))[0], 2.0, 1e-12);
  EXPECT_NEAR(rule.evaluate(q(90 * kDeg))[0], 0.2, 1e-12);
  for (const double deg : {0.0, 10.0, 30.0, 44.9, 45.0, 50.0, 60.0, 75.0, 90.0}) {
    SCOPED_TRACE(deg);
    EXPECT_VECTOR_NEAR(rule.evaluate(q(deg * kDeg)), visgrabTau(deg * kDeg), 1e-12);
  }
}

TEST(GraspDescription, SdhClosingRule) {
  EXPECT_VECTOR_NEAR(sdh().closeOffset(), makeQ({30 * kDeg, 0, 0, 30 * kDeg, 0, 30 * kDeg, 0}),
                     1e-12);
}

TEST(GraspDescription, Pg70Loads) {
  const HandGraspSetup& s = pg70();
  EXPECT_EQ(s.deviceName(), "PG70");
  EXPECT_EQ(s.tcpFrameName(), "PG70.TCPPG70");
  EXPECT_EQ(s.dof(), 1);
  EXPECT_EQ(s.findPreshape("PG70")->qOpen, makeQ({0.034}));
  EXPECT_EQ(s.findPreshape("PG70_SMALL")->qOpen, makeQ({0.01}));
  EXPECT_EQ(s.findPreshape("PG70_SMALL")->qClosed, makeQ({0.0}));
  EXPECT_EQ(s.findPreshape("PG70")->tauMax, makeQ({40.0}));
  EXPECT_VECTOR_NEAR(s.closeOffset(), makeQ({-0.02}), 1e-15);
}

// --- Malformed descriptions: one error each, at the right line ------------------------------

// A small valid SDH description; line numbers: PreShape 2, Closing 3-4, TauMax 6-8,
// ContactIK 9, Fingertips 10-11, Grasp 12-13.
std::string description(const std::string& root = "tcp=\"SDHTCP\"",
                        const std::string& preshape = "qOpen=\"0 0 0 0 0 0 0\"",
                        const std::string& offsetJoint = "f1.Joint2",
                        const std::string& adjustJoints = "f2.Joint2 f3.Joint2",
                        const std::string& tipFrame = "f2.TCP",
                        const std::string& fingers = "finger2 finger3") {
  return "<GraspDescription workcell=\"sdh.wc.xml\" device=\"SchunkHand\" "
         "controller=\"GraspController\" " +
         root +
         ">\n"
         "  <PreShape name=\"P\" " +
         preshape +
         " qClosed=\"0 0 0 0 0 0 0\"/>\n"
         "  <Closing>\n"
         "    <Offset joint=\"" +
         offsetJoint +
         "\" value=\"30\"/>\n"
         "  </Closing>\n"
         "  <TauMax base=\"2 2 10 2 2 2 2\">\n"
         "    <Adjust angleJoint=\"F2Joint1\" below=\"45\" joints=\"" +
         adjustJoints +
         "\" source=\"f1.Joint2\" gain=\"0.5\" function=\"secant\"/>\n"
         "  </TauMax>\n"
         "  <ContactIK backoff=\"0.01\" maxPositionError=\"0.01\" maxDirectionError=\"30\" "
         "maxApproachError=\"60\" directionWeight=\"0.01\" approachWeight=\"0.02\" "
         "approachAxis=\"0 0 1\">\n"
         "    <Fingertip name=\"finger2\" frame=\"" +
         tipFrame +
         "\" point=\"0 0 0.005\" normal=\"0 0 1\"/>\n"
         "    <Fingertip name=\"finger3\" frame=\"f3.TCP\" point=\"0 0 0.005\" normal=\"0 0 1\"/>\n"
         "    <Grasp contacts=\"2\" fingers=\"" +
         fingers +
         "\">\n"
         "      <Seed q=\"-1.571 -1.571 1.571 0 0.5 0 0.5\"/></Grasp>\n"
         "  </ContactIK>\n"
         "</GraspDescription>\n";
}

std::filesystem::path virtualFile() {
  return visgrab::test::sourceDir() / "scenes/hands/sdh/inline.grasp.xml";
}

TEST(GraspDescription, InlineTemplateLoads) {
  const auto s = loadHandGraspSetupFromString(description(), virtualFile());
  EXPECT_EQ(s->preshapes().size(), 1u);
  EXPECT_EQ(s->contactIk()->grasps.size(), 1u);
}

struct BadCase {
  const char* what;
  std::string xml;
  int line;
  const char* message;
};

TEST(GraspDescription, MalformedGiveOneErrorAtTheirLine) {
  const BadCase cases[] = {
      {"missing TCP frame", description("tcp=\"NoSuchTcp\""), 1, "unknown TCP frame \"NoSuchTcp\""},
      {"wrong q length", description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0\""), 2,
       "qOpen has 3 values, expected 7"},
      {"unknown closing joint", description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"", "f9.J2"),
       4, "unknown joint \"f9.J2\""},
      {"dependent joint", description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"", "F3Joint1"), 4,
       "joint \"F3Joint1\" is dependent"},
      {"unknown tau joint",
       description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"", "f1.Joint2", "f2.Joint2 bogus"), 7,
       "unknown joint \"bogus\""},
      {"unknown fingertip frame",
       description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"", "f1.Joint2", "f2.Joint2",
                   "f2.Nope"),
       10, "unknown fingertip frame \"f2.Nope\""},
      {"unknown finger",
       description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"", "f1.Joint2", "f2.Joint2", "f2.TCP",
                   "finger2 pinky"),
       12, "unknown fingertip \"pinky\""},
      {"finger count",
       description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"", "f1.Joint2", "f2.Joint2", "f2.TCP",
                   "finger2"),
       12, "names 1 fingers; expected one per contact"},
      {"not a number", description("tcp=\"SDHTCP\"", "qOpen=\"0 0 x 0 0 0 0\""), 2,
       "attribute qOpen"},
      {"unexpected attribute", description("tcp=\"SDHTCP\" device2=\"x\""), 1, "device2"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.what);
    try {
      loadHandGraspSetupFromString(c.xml, virtualFile());
      ADD_FAILURE() << "loaded";
    } catch (const rw::common::LoadError& e) {
      int errors = 0;
      for (const auto& d : e.diagnostics()) {
        if (d.severity != rw::common::Diagnostic::Severity::kError) continue;
        ++errors;
        EXPECT_EQ(d.line, c.line) << d.format();
        EXPECT_NE(d.message.find(c.message), std::string::npos) << d.format();
        EXPECT_NE(d.format().find("inline.grasp.xml:" + std::to_string(c.line) + ":"),
                  std::string::npos)
            << d.format();
      }
      EXPECT_EQ(errors, 1) << e.what();
    }
  }
}

// Schema errors say what is wrong (issue 20): a required element left out, elements out of
// order or given twice, a misspelt one; each at the line of the element concerned.
TEST(GraspDescription, SchemaErrorsSayWhatIsWrong) {
  const std::string xml = description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"");
  const std::size_t tauBegin = xml.find("  <TauMax");
  const std::size_t tauEnd = xml.find("  <ContactIK");
  const std::string tau = xml.substr(tauBegin, tauEnd - tauBegin);
  const std::size_t closingBegin = xml.find("  <Closing>");
  const std::string closing = xml.substr(closingBegin, tauBegin - closingBegin);
  std::string withoutTau = xml;
  withoutTau.erase(tauBegin, tau.size());
  std::string swapped = xml;
  swapped.replace(closingBegin, closing.size() + tau.size(), tau + closing);
  std::string twice = xml;
  twice.insert(tauEnd, tau);
  std::string misspelt = xml;
  misspelt.replace(misspelt.find("<Closing>"), 9, "<Closng>");
  misspelt.replace(misspelt.find("</Closing>"), 10, "</Closng>");
  const BadCase cases[] = {
      {"missing", withoutTau, 6, "missing <TauMax> (required before <ContactIK>)"},
      {"out of order", swapped, 6, "<Closing> is out of order: it must come before <TauMax>"},
      {"twice", twice, 9,
       "<TauMax> is given twice; <GraspDescription> allows only one (the first is at line 6)"},
      {"misspelt", misspelt, 3,
       "unknown element <Closng> in <GraspDescription>; did you mean "
       "<Closing>?"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.what);
    try {
      loadHandGraspSetupFromString(c.xml, virtualFile());
      ADD_FAILURE() << "loaded";
    } catch (const rw::common::LoadError& e) {
      ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
      EXPECT_EQ(e.diagnostics()[0].line, c.line) << e.what();
      EXPECT_EQ(e.diagnostics()[0].message, c.message) << e.what();
    }
  }
}

// <Closing> is optional (issue 20): without it the hand loads and runs pre-shape grasps; pose + q
// grasps are rejected with a message naming the missing rule; a contact grasp needs its own.
TEST(GraspDescription, WithoutClosingPoseAndQGraspsAreRejectedWithTheReason) {
  const std::string full = description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"");
  const std::size_t closingBegin = full.find("  <Closing>");
  const std::size_t closingEnd = full.find("  <TauMax");
  std::string noClosing = full;
  noClosing.erase(closingBegin, closingEnd - closingBegin);
  // The contact IK's grasp gets a closing rule of its own.
  noClosing.replace(noClosing.find("</Grasp>"), 8,
                    "<Closing><Offset joint=\"f2.Joint2\" value=\"20\"/></Closing></Grasp>");
  const auto setup = loadHandGraspSetupFromString(noClosing, virtualFile());
  EXPECT_FALSE(setup->hasClosingRule());
  EXPECT_TRUE(loadHandGraspSetupFromString(full, virtualFile())->hasClosingRule());

  GraspRequest poseQ;
  poseQ.id = "g1";
  poseQ.kind = GraspKind::kPoseAndQ;
  poseQ.qOpen = rw::math::Q::Zero(7);
  const ResolvedGrasp rejected = resolve(poseQ, *setup);
  EXPECT_EQ(rejected.status, ResolveStatus::kInputError);
  EXPECT_EQ(rejected.reason,
            "hand \"SchunkHand\" has no closing rule (no <Closing> in its grasp description), "
            "which pose + q grasps need; use a pre-shape or raw grasp");
  GraspRequest shape;
  shape.id = "g2";
  shape.kind = GraspKind::kPreshape;
  shape.preshape = "P";
  EXPECT_TRUE(resolve(shape, *setup).ok()) << resolve(shape, *setup).message;

  // Without its own <Closing> the contact grasp has no rule either: an error at its line.
  std::string bare = full;
  bare.erase(closingBegin, closingEnd - closingBegin);
  try {
    loadHandGraspSetupFromString(bare, virtualFile());
    ADD_FAILURE() << "loaded";
  } catch (const rw::common::LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 9) << e.what();
    EXPECT_NE(e.diagnostics()[0].message.find("this contact grasp has no closing rule"),
              std::string::npos)
        << e.what();
  }
}

// One value in <TauMax base> stands for every DOF (issue 20): the same rule as seven equal ones.
TEST(GraspDescription, OneTauMaxBaseValueIsTheSameForEveryDof) {
  const std::string seven = description("tcp=\"SDHTCP\"", "qOpen=\"0 0 0 0 0 0 0\"");
  std::string one = seven;
  one.replace(one.find("base=\"2 2 10 2 2 2 2\""), 21, "base=\"3\"");
  std::string equal = seven;
  equal.replace(equal.find("base=\"2 2 10 2 2 2 2\""), 21, "base=\"3 3 3 3 3 3 3\"");
  const auto a = loadHandGraspSetupFromString(one, virtualFile());
  const auto b = loadHandGraspSetupFromString(equal, virtualFile());
  EXPECT_EQ(a->tauRule().base, rw::math::Q::Constant(7, 3.0));
  EXPECT_EQ(a->tauRule().base, b->tauRule().base);
  const rw::math::Q q = rw::math::Q::Constant(7, 0.3);
  EXPECT_EQ(a->tauRule().evaluate(q), b->tauRule().evaluate(q));
  // Two values for seven DOF stay an error.
  std::string two = seven;
  two.replace(two.find("base=\"2 2 10 2 2 2 2\""), 21, "base=\"3 4\"");
  EXPECT_THROW(loadHandGraspSetupFromString(two, virtualFile()), rw::common::LoadError);
}

TEST(GraspDescription, DuplicatePreshapeName) {
  std::string xml = description();
  const std::string line =
      "  <PreShape name=\"P\" qOpen=\"0 0 0 0 0 0 0\" qClosed=\"0 0 0 0 0 0 0\"/>\n";
  xml.insert(xml.find("  <Closing>"), line);
  try {
    loadHandGraspSetupFromString(xml, virtualFile());
    ADD_FAILURE() << "loaded";
  } catch (const rw::common::LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 3);
    EXPECT_NE(e.diagnostics()[0].message.find("already used (line 2)"), std::string::npos);
  }
}

TEST(GraspDescription, MissingWorkcellNamesTheDescription) {
  std::string xml = description();
  xml.replace(xml.find("sdh.wc.xml"), 10, "nope.wc.xml");
  try {
    loadHandGraspSetupFromString(xml, virtualFile());
    ADD_FAILURE() << "loaded";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("inline.grasp.xml:1"), std::string::npos) << e.what();
  }
}

// A hand whose device file cannot be edited (RobWork's Robotiq: a plain, fixed Base) is mounted
// on a Movable frame put before it in a fragment of several top-level elements, with its TCP
// after it: the mount is the frame the grasp utilities move, the TCP is rigid on it. Without a
// Movable frame above the base the description is an error that says what to add.
TEST(GraspDescription, AFixedBaseIsPlacedByTheMovableFrameHoldingIt) {
  visgrab::test::TempDir dir;
  const std::string device =
      "<TreeDevice name=\"Jaw\">\n"
      "  <Frame name=\"Base\"><RPY>0 0 0</RPY><Pos>0 0 0.02</Pos></Frame>\n"
      "  <Joint name=\"J\" type=\"Prismatic\"><RPY>0 0 0</RPY><Pos>0 0 0.05</Pos></Joint>\n"
      "  <PosLimit refjoint=\"J\" min=\"0\" max=\"0.04\"/>\n"
      "</TreeDevice>\n";
  const std::string tcp =
      "<Frame name=\"Tcp\" refframe=\"Jaw.Base\"><RPY>90 0 0</RPY><Pos>0 0 0.1</Pos></Frame>\n";
  visgrab::test::writeFile(dir.path() / "mounted.wc.xml",
                           "<Frame name=\"Mount\" type=\"Movable\"><RPY>0 0 0</RPY>"
                           "<Pos>0 0 0.3</Pos></Frame>\n" +
                               device + tcp);
  visgrab::test::writeFile(dir.path() / "bare.wc.xml", device + tcp);
  const auto description = [](const std::string& workcell) {
    return "<GraspDescription workcell=\"" + workcell +
           "\" device=\"Jaw\" controller=\"C\" tcp=\"Tcp\">\n"
           "  <PreShape name=\"P\" qOpen=\"0.04\" qClosed=\"0\"/>\n"
           "  <TauMax base=\"10\"/>\n"
           "</GraspDescription>\n";
  };
  const auto setup =
      loadHandGraspSetupFromString(description("mounted.wc.xml"), dir.path() / "h.grasp.xml");
  EXPECT_EQ(setup->workcell().frames().frame(setup->placementFrame()).name(), "Mount");
  EXPECT_EQ(setup->tcpFrameName(), "Tcp");
  // Mount -> Base 2 cm up, Base -> Tcp 10 cm up and turned 90 deg about z.
  EXPECT_VECTOR_NEAR(setup->X_base_tcp().translation(), rw::math::Vector3D(0, 0, 0.12), 1e-15);
  EXPECT_NEAR(setup->X_base_tcp().linear()(1, 0), 1.0, 1e-15);
  try {
    loadHandGraspSetupFromString(description("bare.wc.xml"), dir.path() / "h.grasp.xml");
    ADD_FAILURE() << "loaded";
  } catch (const rw::common::LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 1) << e.what();
    EXPECT_NE(e.diagnostics()[0].message.find(
                  "the base frame \"Jaw.Base\" of device \"Jaw\" must be Movable, or be held "
                  "rigidly by a Movable frame"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
