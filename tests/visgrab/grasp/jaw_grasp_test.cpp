// Parallel-jaw grasps end to end: a grasp-list line of kind jaw read (and its bad widths
// rejected at file:line:col), resolved through a hand's jaw frame to the TCP pose worked by hand,
// and the input errors of a hand without a jaw frame and of a width beyond the stroke.
#include <gtest/gtest.h>

#include <string>

#include "grasp_test_support.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;
using visgrab::grasp::HandGraspSetup;
using visgrab::grasp::loadHandGraspSetup;
using visgrab::grasp::resolve;
using visgrab::grasp::ResolveStatus;
using visgrab::taskio::parseGraspList;
using visgrab::test::grasp::makeQ;

const HandGraspSetup& franka() {
  static const auto setup =
      loadHandGraspSetup(visgrab::test::sourceDir() / "scenes/hands/franka/franka.grasp.xml");
  return *setup;
}

// One jaw grasp, the hand pointing down: the jaw frame at (0.1, 0.2, 0.3) turned half a turn
// about the world's y (quaternion w x y z = 0 0 1 0): its x (closing) is world -x, its z
// (approach) world -z.
constexpr const char* kLine =
    "plain/single/box/01, net, 7, jaw, 0.1,0.2,0.3, 0,0,1,0, 0.05, 0.93\n";

Transform3D jawPose() {
  Transform3D X = Transform3D::Identity();
  X.linear() << -1, 0, 0, 0, 1, 0, 0, 0, -1;
  X.translation() = Vector3D(0.1, 0.2, 0.3);
  return X;
}

TEST(JawGrasp, AGraspListLineIsRead) {
  const auto got = parseGraspList(kLine, "jaw.csv");
  ASSERT_TRUE(got.rejected.empty()) << got.rejected.front().format();
  ASSERT_EQ(got.requests.size(), 1u);
  const GraspRequest& r = got.requests.front();
  EXPECT_EQ(r.kind, GraspKind::kJaw);
  EXPECT_EQ(r.id, "7");
  EXPECT_TRANSFORM_NEAR(r.X_W_jaw, jawPose(), 1e-15);
  EXPECT_EQ(r.width, 0.05);
  ASSERT_TRUE(r.score.has_value());
  EXPECT_EQ(*r.score, 0.93);
  // The score is optional.
  const auto bare = parseGraspList("s, m, g, jaw, 0,0,0, 1,0,0,0, 0.08\n", "jaw.csv");
  ASSERT_TRUE(bare.rejected.empty()) << bare.rejected.front().format();
  EXPECT_FALSE(bare.requests.front().score.has_value());
}

TEST(JawGrasp, BadWidthsAreRejectedAtTheirField) {
  struct Case {
    const char* line;
    const char* where;
    const char* message;
  };
  const Case cases[] = {
      // "s, m, g, jaw, 0,0,0, 1,0,0,0, " is 30 characters: the width is field at column 31.
      {"s, m, g, jaw, 0,0,0, 1,0,0,0, -0.01\n",
       "jaw.csv:1:31: error:", "width is negative, expected an opening in m"},
      {"s, m, g, jaw, 0,0,0, 1,0,0,0, wide\n", "jaw.csv:1:31: error:", "width"},
      {"s, m, g, jaw, 0,0,0, 1,0,0,0\n", "jaw.csv:1:", "width"},
      {"s, m, g, jaw, 0,0,0, 1,0,0,0, 0.05, 0.9, 1\n", "jaw.csv:1:", "too many fields"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.line);
    const auto got = parseGraspList(c.line, "jaw.csv");
    ASSERT_EQ(got.rejected.size(), 1u);
    const std::string text = got.rejected.front().format();
    EXPECT_NE(text.find(c.where), std::string::npos) << text;
    EXPECT_NE(text.find(c.message), std::string::npos) << text;
  }
}

// The Franka: its jaw frame is its TCP (franka.grasp.xml), so X_W_tcp = X_W_jaw; the
// configuration is FRANKA_OPEN's, q 0.04 -> 0, and the torque rule's 70 N.
TEST(JawGrasp, ResolvedOnTheFrankaTheTcpIsTheJawFrame) {
  GraspRequest r = parseGraspList(kLine, "jaw.csv").requests.front();
  const auto g = resolve(r, franka());
  ASSERT_TRUE(g.ok()) << g.message;
  EXPECT_TRANSFORM_NEAR(g.parameters.X_W_tcp, jawPose(), 1e-12);
  EXPECT_EQ(g.parameters.qOpen, makeQ({0.04}));
  EXPECT_EQ(g.parameters.qClosed, makeQ({0.0}));
  EXPECT_EQ(g.parameters.tauMax, makeQ({70.0}));
}

// The PG70: the jaw frame is TCP (0, 0, -0.012) (the pads' centre 12 mm short of TCPPG70,
// pg70.grasp.xml), so X_W_tcp = X_W_jaw * Trans(0, 0, 0.012): the same rotation, the origin
// 12 mm along the jaw's z (world -z): (0.1, 0.2, 0.3 - 0.012) = (0.1, 0.2, 0.288). The
// configuration is the pre-shape PG70's, 0.034 -> 0, 40 N.
TEST(JawGrasp, ResolvedOnThePg70TheTcpLiesBeyondThePads) {
  GraspRequest r = parseGraspList(kLine, "jaw.csv").requests.front();
  const auto g = resolve(r, visgrab::test::grasp::pg70());
  ASSERT_TRUE(g.ok()) << g.message;
  Transform3D expected = jawPose();
  expected.translation() = Vector3D(0.1, 0.2, 0.288);
  EXPECT_TRANSFORM_NEAR(g.parameters.X_W_tcp, expected, 1e-12);
  EXPECT_EQ(g.parameters.qOpen, makeQ({0.034}));
  EXPECT_EQ(g.parameters.qClosed, makeQ({0.0}));
  EXPECT_EQ(g.parameters.tauMax, makeQ({40.0}));
}

// A hand whose description declares no jaw frame (the SDH's without the element, inline) cannot
// run jaw grasps: an input error naming the hand and the missing element.
TEST(JawGrasp, AHandWithoutAJawFrameIsAnInputError) {
  const auto sdh = visgrab::grasp::loadHandGraspSetupFromString(
      "<GraspDescription workcell=\"sdh.wc.xml\" device=\"SchunkHand\" "
      "controller=\"GraspController\" tcp=\"SDHTCP\">\n"
      "  <PreShape name=\"SDH_WIDE\" aliases=\"wide\" tcp=\"ParallelTCP\"\n"
      "            qOpen=\"-1.571 -1.571 1.571 -0.296 0.240 -0.296 0.240\"\n"
      "            qClosed=\"-1.571 -1.571 1.571 0.0 0.419 0.0 0.419\"/>\n"
      "  <TauMax base=\"2\"/>\n"
      "</GraspDescription>\n",
      visgrab::test::sourceDir() / "scenes/hands/sdh/inline.grasp.xml");
  GraspRequest r = parseGraspList(kLine, "jaw.csv").requests.front();
  r.sourceLine = 1;
  const auto g = resolve(r, *sdh);
  EXPECT_EQ(g.status, ResolveStatus::kInputError);
  EXPECT_EQ(g.message,
            "jaw.csv:1: grasp \"7\": hand \"SchunkHand\" declares no jaw frame (<JawFrame> in its "
            "grasp description), which parallel-jaw grasps need");
}

// Wider than the Franka's stroke (0.08 m): an input error, never a silent clip.
TEST(JawGrasp, AWidthBeyondTheStrokeIsAnInputError) {
  GraspRequest r = parseGraspList(kLine, "jaw.csv").requests.front();
  r.width = 0.09;
  r.sourceLine = 1;
  const auto g = resolve(r, franka());
  EXPECT_EQ(g.status, ResolveStatus::kInputError);
  EXPECT_EQ(g.message,
            "jaw.csv:1: grasp \"7\": width 0.09 m is outside what hand \"Franka\" opens to (0 to "
            "its stroke 0.08 m)");
  r.width = 0.08;  // the stroke itself fits
  EXPECT_TRUE(resolve(r, franka()).ok());
}

}  // namespace
