// The parallel-jaw frame of a grasp description (<JawFrame>): how it is read and checked against
// the hand's model, and, for every hand that declares one, that the declared pad centre, closing
// axis and stroke are those of the model's own pad geometry, worked by forward kinematics at the
// jaw pre-shape's qOpen.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "grasp_test_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::grasp::HandGraspSetup;
using visgrab::grasp::JawFrame;
using visgrab::grasp::loadHandGraspSetup;
using visgrab::grasp::loadHandGraspSetupFromString;
using visgrab::test::sourceDir;

// A small PG70 description with `jaw` as its line 4 (empty: no <JawFrame>).
std::string pg70Description(const std::string& jaw) {
  return "<GraspDescription workcell=\"pg70.wc.xml\" device=\"PG70\" "
         "controller=\"GraspController\" "
         "tcp=\"TCPPG70\">\n"
         "  <PreShape name=\"PG70\" aliases=\"wide\" qOpen=\"0.034\" qClosed=\"0\"/>\n"
         "  <TauMax base=\"40\"/>\n" +
         jaw + "\n</GraspDescription>\n";
}

std::filesystem::path pg70VirtualFile() {
  return sourceDir() / "scenes/hands/pg70/inline.grasp.xml";
}

// The PG70's jaw frame at its wide pre-shape, worked by hand (pg70.wc.xml): TCPPG70 is Base
// (0, 0, 0.14) turned 90 deg about z (TCP x = Base y, the jaws' axis; TCP z = Base z); the jaws
// span Base z 0.093..0.163, so the pads' centre is Base (0, 0, 0.128) = TCP (0, 0, -0.012).
TEST(JawFrame, DeclaredInTheTcpIsATranslation) {
  const auto s = loadHandGraspSetupFromString(
      pg70Description("  <JawFrame preshape=\"wide\" position=\"0 0 -0.012\" stroke=\"0.083\" "
                      "tipDepth=\"0.035\"/>"),
      pg70VirtualFile());
  const JawFrame* jaw = s->jawFrame();
  ASSERT_NE(jaw, nullptr);
  EXPECT_TRANSFORM_NEAR(jaw->X_tcp_jaw, rw::math::makeTranslation(Vector3D(0, 0, -0.012)), 1e-12);
  EXPECT_EQ(jaw->stroke, 0.083);
  EXPECT_EQ(jaw->tipDepth, 0.035);
  EXPECT_EQ(jaw->preshape, 0u);
}

// Written in a finger frame, the jaw frame is taken at the pre-shape's qOpen. TCPRight sits on
// the right jaw, at Base (0, -0.017 - q, 0.093) with x = Base x, y = Base z, z = -Base y
// (RPY 0 0 90). At q = 0.034 the pads' centre Base (0, 0, 0.128) is TCPRight
// (0, 0.128 - 0.093, -(0 - (-0.051))) = (0, 0.035, -0.051); the approach Base z is TCPRight y,
// the closing axis TCP x = Base y is TCPRight -z. The result is the declaration above.
TEST(JawFrame, DeclaredInAFingerFrameIsTakenAtThePreshape) {
  const auto s = loadHandGraspSetupFromString(
      pg70Description(
          "  <JawFrame preshape=\"PG70\" frame=\"TCPRight\" position=\"0 0.035 -0.051\" "
          "approach=\"0 2 0\" closing=\"0 0 -1\" stroke=\"0.083\" tipDepth=\"0.035\"/>"),
      pg70VirtualFile());
  ASSERT_NE(s->jawFrame(), nullptr);
  EXPECT_TRANSFORM_NEAR(s->jawFrame()->X_tcp_jaw, rw::math::makeTranslation(Vector3D(0, 0, -0.012)),
                        1e-12);
}

TEST(JawFrame, WithoutTheElementTheHandHasNone) {
  const auto s = loadHandGraspSetupFromString(pg70Description(""), pg70VirtualFile());
  EXPECT_EQ(s->jawFrame(), nullptr);
}

// Axes at right angles within 1e-6 (the cosine after normalising) pass: rounded numbers in a file
// are not an error; 1e-5 is.
TEST(JawFrame, AxesAtRightAnglesWithinOneMillionth) {
  const auto s = loadHandGraspSetupFromString(
      pg70Description("  <JawFrame preshape=\"PG70\" position=\"0 0 0\" closing=\"1 0 5e-7\" "
                      "stroke=\"0.08\" tipDepth=\"0\"/>"),
      pg70VirtualFile());
  ASSERT_NE(s->jawFrame(), nullptr);
  // x = closing normalised, z = approach, y = z x x.
  const auto R = s->jawFrame()->X_tcp_jaw.linear();
  EXPECT_NEAR(R.col(1).dot(Vector3D::UnitY()), 1.0, 1e-12);
  EXPECT_NEAR(R.col(2).dot(Vector3D::UnitZ()), 1.0, 1e-12);
}

struct BadJawCase {
  const char* what;
  std::string element;
  const char* message;
};

TEST(JawFrame, BadDeclarationsGiveOneErrorAtTheElement) {
  const auto jaw = [](const std::string& attributes) { return "  <JawFrame " + attributes + "/>"; };
  const std::string ok = "position=\"0 0 0\" stroke=\"0.08\" tipDepth=\"0.01\"";
  const BadJawCase cases[] = {
      {"unknown pre-shape", jaw("preshape=\"NOPE\" " + ok),
       "<JawFrame> names unknown pre-shape \"NOPE\" (the description's pre-shapes: PG70)"},
      {"unknown frame", jaw("preshape=\"PG70\" frame=\"Nowhere\" " + ok),
       "<JawFrame> names unknown frame \"Nowhere\" (no such frame in device \"PG70\""},
      {"zero approach", jaw("preshape=\"PG70\" approach=\"0 0 0\" " + ok),
       "<JawFrame> approach must not be zero"},
      {"zero closing", jaw("preshape=\"PG70\" closing=\"0 0 0\" " + ok),
       "<JawFrame> closing must not be zero"},
      {"not at right angles", jaw("preshape=\"PG70\" closing=\"1 0 0.01\" " + ok),
       "<JawFrame> approach and closing must be at right angles, but they are 89.4271 deg apart "
       "(the cosine of the angle is 0.0099995; at most 1e-06 is accepted)"},
      {"zero stroke", jaw("preshape=\"PG70\" position=\"0 0 0\" stroke=\"0\" tipDepth=\"0.01\""),
       "<JawFrame> stroke must be greater than 0 (the opening between the pads at the pre-shape, "
       "m), not 0"},
      {"negative stroke",
       jaw("preshape=\"PG70\" position=\"0 0 0\" stroke=\"-0.08\" tipDepth=\"0.01\""),
       "stroke must be greater than 0 (the opening between the pads at the pre-shape, m), not "
       "-0.08"},
      {"negative tip depth",
       jaw("preshape=\"PG70\" position=\"0 0 0\" stroke=\"0.08\" tipDepth=\"-0.001\""),
       "<JawFrame> tipDepth must be at least 0 (the fingertips' front lies beyond the pad centre "
       "along the approach), not -0.001"},
      {"not a number", jaw("preshape=\"PG70\" position=\"0 0 0\" stroke=\"wide\" tipDepth=\"0\""),
       "stroke"},
      {"two numbers for a position",
       jaw("preshape=\"PG70\" position=\"0 0\" stroke=\"0.08\" tipDepth=\"0\""), "position"},
      {"missing stroke", jaw("preshape=\"PG70\" position=\"0 0 0\" tipDepth=\"0\""), "stroke"},
  };
  for (const BadJawCase& c : cases) {
    SCOPED_TRACE(c.what);
    try {
      loadHandGraspSetupFromString(pg70Description(c.element), pg70VirtualFile());
      ADD_FAILURE() << "loaded";
    } catch (const rw::common::LoadError& e) {
      ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
      const auto& d = e.diagnostics().front();
      EXPECT_EQ(d.line, 4) << d.format();
      EXPECT_EQ(d.column, 3) << d.format();
      EXPECT_NE(d.message.find(c.message), std::string::npos) << d.format();
      EXPECT_NE(d.format().find("inline.grasp.xml:4:3: error:"), std::string::npos) << d.format();
    }
  }
}

// The element comes last, after <ContactIK> (which may be left out): before <TauMax> it is out
// of order, at its own line.
TEST(JawFrame, ComesLast) {
  const std::string xml =
      "<GraspDescription workcell=\"pg70.wc.xml\" device=\"PG70\" controller=\"GraspController\" "
      "tcp=\"TCPPG70\">\n"
      "  <PreShape name=\"PG70\" qOpen=\"0.034\" qClosed=\"0\"/>\n"
      "  <JawFrame preshape=\"PG70\" position=\"0 0 0\" stroke=\"0.08\" tipDepth=\"0\"/>\n"
      "  <TauMax base=\"40\"/>\n"
      "</GraspDescription>\n";
  try {
    loadHandGraspSetupFromString(xml, pg70VirtualFile());
    ADD_FAILURE() << "loaded";
  } catch (const rw::common::LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 3) << e.what();
    EXPECT_NE(e.diagnostics()[0].message.find("<JawFrame>"), std::string::npos) << e.what();
  }
}

// --- The hands' declared jaw frames against their pad geometry --------------------------------

// A pad: the frame carrying it and the name of its collision geometry (a Box, or a Cylinder
// whose end cap is the grip face).
struct JawPad {
  std::string frame;
  std::string geometry;
};

// The centre of the face of a pad's box or cylinder that faces `towards` (unit, world), in the
// world at `state`: of the box's six faces (the cylinder's two end caps) the one whose outward
// normal is closest to `towards`; towards = 0: the geometry's centre.
Vector3D gripFaceCentre(const HandGraspSetup& hand, const rw::kinematics::State& state,
                        const JawPad& pad, const Vector3D& towards) {
  const auto& wc = hand.workcell();
  auto frame = wc.findFrame(hand.deviceName() + "." + pad.frame);
  if (!frame.valid()) frame = wc.findFrame(pad.frame);
  EXPECT_TRUE(frame.valid()) << pad.frame;
  const auto* object = wc.findObject(frame);
  EXPECT_NE(object, nullptr) << pad.frame;
  if (object == nullptr) return Vector3D::Zero();
  for (const auto& g : object->collision) {
    if (g.name != pad.geometry) continue;
    const Transform3D X_W_g =
        rw::kinematics::worldTransform(wc.frames(), state, frame) * g.X_frame_geometry;
    if (towards.isZero()) return X_W_g.translation();
    const auto& p = g.geometry->parameters();
    std::vector<Vector3D> halfAxes;  // in the geometry's frame: centre to face centre
    if (g.geometry->type() == rw::geometry::GeometryType::kBox) {
      halfAxes = {Vector3D(p[0] / 2, 0, 0), Vector3D(0, p[1] / 2, 0), Vector3D(0, 0, p[2] / 2)};
    } else {
      EXPECT_EQ(g.geometry->type(), rw::geometry::GeometryType::kCylinder) << pad.geometry;
      halfAxes = {Vector3D(0, 0, p[1] / 2)};
    }
    Vector3D best = X_W_g.translation();
    double bestDot = -2.0;
    for (const Vector3D& h : halfAxes) {
      for (const double sign : {1.0, -1.0}) {
        const Vector3D offset = X_W_g.linear() * (sign * h);
        const double d = offset.normalized().dot(towards);
        if (d > bestDot) {
          bestDot = d;
          best = X_W_g.translation() + offset;
        }
      }
    }
    return best;
  }
  ADD_FAILURE() << "no collision geometry " << pad.geometry << " on " << pad.frame;
  return Vector3D::Zero();
}

// The declared jaw frame against the model: with the jaws at the jaw pre-shape's qOpen, the
// declared pad centre is midway between the two pads' grip faces (within 1 mm), the closing axis
// is along the line between them (within 1 deg), and the stroke is their distance (within 1 mm).
void expectJawFrameOnThePads(const HandGraspSetup& hand, const JawPad& a, const JawPad& b) {
  const JawFrame* jaw = hand.jawFrame();
  ASSERT_NE(jaw, nullptr) << hand.deviceName();
  rw::kinematics::State state = hand.defaultState();
  hand.device().setQ(hand.preshapes()[jaw->preshape].qOpen, state);
  // The geometries' centres give the direction from one pad to the other.
  const Vector3D ca = gripFaceCentre(hand, state, a, Vector3D::Zero());
  const Vector3D cb = gripFaceCentre(hand, state, b, Vector3D::Zero());
  const Vector3D d = (cb - ca).normalized();
  const Vector3D fa = gripFaceCentre(hand, state, a, d);
  const Vector3D fb = gripFaceCentre(hand, state, b, -d);
  const Transform3D X_W_jaw =
      rw::kinematics::worldTransform(hand.workcell().frames(), state, hand.tcpFrame()) *
      jaw->X_tcp_jaw;
  const Vector3D mid = 0.5 * (fa + fb);
  EXPECT_LT((X_W_jaw.translation() - mid).norm(), 1e-3)
      << hand.deviceName() << ": declared " << X_W_jaw.translation().transpose() << ", pads' "
      << mid.transpose();
  const Vector3D between = fb - fa;
  const double cosine = std::abs(between.normalized().dot(X_W_jaw.linear().col(0)));
  EXPECT_GT(cosine, std::cos(1.0 * visgrab::test::grasp::kDeg))
      << hand.deviceName() << ": closing axis " << X_W_jaw.linear().col(0).transpose()
      << ", pad to pad " << between.normalized().transpose();
  EXPECT_NEAR(jaw->stroke, between.norm(), 1e-3) << hand.deviceName();
}

TEST(JawFrame, Pg70PadCentreAndStroke) {
  // pg70.grasp.xml: the jaws' boxes; their grip faces are 0.015 + 2 x 0.034 = 0.083 apart.
  expectJawFrameOnThePads(visgrab::test::grasp::pg70(), {"RightFinger", "RightJaw"},
                          {"LeftFinger", "LeftJaw"});
}

TEST(JawFrame, SdhTwoFingerPreshapePadCentreAndStroke) {
  // sdh.grasp.xml: fingers 2 and 3 in SDH_WIDE; each fingertip pad is a cylinder across the
  // distal link whose end cap is the flat grip face.
  expectJawFrameOnThePads(visgrab::test::grasp::sdh(), {"f2.Joint3", "FingertipPad"},
                          {"f3.Joint3", "FingertipPad"});
}

TEST(JawFrame, Robotiq2F85PadCentreAndStroke) {
  const auto hand = loadHandGraspSetup(sourceDir() / "scenes/hands/robotiq2f85");
  expectJawFrameOnThePads(*hand, {"RightInnerFinger", "RightPadGeo"},
                          {"LeftInnerFinger", "LeftPadGeo"});
}

TEST(JawFrame, FrankaPadCentreAndStroke) {
  const auto hand = loadHandGraspSetup(sourceDir() / "scenes/hands/franka");
  expectJawFrameOnThePads(*hand, {"RightFinger", "RightPadGeo"}, {"LeftFinger", "LeftPadGeo"});
  // The jaw frame is the TCP (franka.grasp.xml), 0.1034 along the base's z.
  EXPECT_TRANSFORM_NEAR(hand->jawFrame()->X_tcp_jaw, Transform3D::Identity(), 1e-12);
  EXPECT_TRANSFORM_NEAR(hand->X_base_tcp(), rw::math::makeTranslation(Vector3D(0, 0, 0.1034)),
                        1e-12);
}

// RobWork's Robotiq: its pads are meshes; the centres of their grip faces are RobWork's junction
// frames RightMotorEnd / LeftMotorEnd (robwork-robotiq.wc.xml's header: measured on the meshes),
// so the pads are taken there.
TEST(JawFrame, RobWorksRobotiqPadCentreAndStroke) {
  REQUIRE_COMPAT_DATA(data);  // the hand's workcell reads ${RW_COMPAT_DATA} itself
  static_cast<void>(data);
  const auto hand = loadHandGraspSetup(sourceDir() / "scenes/hands/robwork-robotiq");
  const JawFrame* jaw = hand->jawFrame();
  ASSERT_NE(jaw, nullptr);
  rw::kinematics::State state = hand->defaultState();
  hand->device().setQ(hand->preshapes()[jaw->preshape].qOpen, state);
  const auto& wc = hand->workcell();
  const auto at = [&](const char* name) -> Vector3D {  // a copy: not a view of a temporary
    auto f = wc.findFrame(hand->deviceName() + "." + name);
    EXPECT_TRUE(f.valid()) << name;
    return rw::kinematics::worldTransform(wc.frames(), state, f).translation();
  };
  const Vector3D fa = at("RightMotorEnd");
  const Vector3D fb = at("LeftMotorEnd");
  const Transform3D X_W_jaw =
      rw::kinematics::worldTransform(wc.frames(), state, hand->tcpFrame()) * jaw->X_tcp_jaw;
  EXPECT_LT((X_W_jaw.translation() - 0.5 * (fa + fb)).norm(), 1e-3);
  EXPECT_GT(std::abs((fb - fa).normalized().dot(X_W_jaw.linear().col(0))),
            std::cos(1.0 * visgrab::test::grasp::kDeg));
  EXPECT_NEAR(jaw->stroke, (fb - fa).norm(), 1e-3);
}

}  // namespace
