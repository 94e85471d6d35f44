#include <gtest/gtest.h>

#include <string>

#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"

namespace {

using visgrab::test::RunResult;
using visgrab::test::runVisgrab;

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

TEST(VisgrabCli, WcInfoPrintsTheSdhJointOrder) {
  const auto sdh = visgrab::test::sourceDir() / "scenes/hands/sdh/sdh.wc.xml";
  const RunResult r = runVisgrab("wc info " + quoted(sdh));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("7 DOF"), std::string::npos) << r.output;
  // Joint order is RobWork's: thumb, spread, finger 2, (coupled spread), finger 3.
  const auto f1 = r.output.find("0  SchunkHand.f1.Joint2");
  const auto spread = r.output.find("2  SchunkHand.F2Joint1");
  const auto coupled = r.output.find("-  SchunkHand.F3Joint1");
  const auto f3 = r.output.find("6  SchunkHand.f3.Joint3");
  ASSERT_NE(f1, std::string::npos) << r.output;
  ASSERT_NE(spread, std::string::npos) << r.output;
  ASSERT_NE(coupled, std::string::npos) << r.output;
  ASSERT_NE(f3, std::string::npos) << r.output;
  EXPECT_LT(f1, spread);
  EXPECT_LT(spread, coupled);
  EXPECT_LT(coupled, f3);
}

TEST(VisgrabCli, WcCheckIsCleanOnTheBundledHands) {
  for (const char* hand : {"scenes/hands/sdh/sdh.wc.xml", "scenes/hands/pg70/pg70.wc.xml",
                           "scenes/hands/robotiq2f85/robotiq2f85.wc.xml"}) {
    const RunResult r = runVisgrab("wc check " + quoted(visgrab::test::sourceDir() / hand));
    EXPECT_EQ(r.exitCode, 0) << hand << "\n" << r.output;
    EXPECT_NE(r.output.find("0 error(s)"), std::string::npos) << r.output;
  }
}

TEST(VisgrabCli, WcCheckReportsFileAndLineAndExitsOne) {
  visgrab::test::TempDir dir;
  const auto file = visgrab::test::writeFile(dir.path() / "bad.wc.xml",
                                             "<WorkCell name=\"w\">\n"
                                             "  <Frame name=\"a\" refframe=\"WORLD\"/>\n"
                                             "  <Frame name=\"b\" refframe=\"nowhere\"/>\n"
                                             "</WorkCell>\n");
  const RunResult r = runVisgrab("wc check " + quoted(file));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bad.wc.xml:3:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nowhere"), std::string::npos) << r.output;
}

// RobWork's Robotiq models: check and info show each parallel device's junctions, legs,
// actuated joints and full DOF (RobWork's numbers: 3 junctions and full DOF 12 for distance
// control, 2 junctions, 4 actuated joints and full DOF 9 for finger control).
TEST(VisgrabCli, WcCheckAndInfoShowTheJunctionsOfParallelDevices) {
  REQUIRE_COMPAT_DATA(data);
  const auto robotiq = data / "devices/Robotiq-2-finger-85/robotiq.wc.xml";
  for (const char* command : {"wc check ", "wc info "}) {
    SCOPED_TRACE(command);
    const RunResult r = runVisgrab(command + quoted(robotiq));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* line : {"full DOF 12 (3 active + 9 passive), 13 joints", "junctions (3):",
                             "full DOF 9 (3 active + 6 passive), 10 joints", "junctions (2):",
                             "actuated joints (4): RobotiqFingerControl.LeftMotor.MotorJoint, "
                             "RobotiqFingerControl.LeftPassive.PassiveJoint, "
                             "RobotiqFingerControl.RightMotor.MotorJoint, "
                             "RobotiqFingerControl.RightPassive.PassiveJoint",
                             "leg \"LeftPassive Distance\": RobotiqDistanceControl.Base -> "
                             "RobotiqDistanceControl.DistanceEnd",
                             "leg \"RightPassive\": RobotiqDistanceControl.Base -> "
                             "RobotiqDistanceControl.RightPassiveEnd"}) {
      EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
    }
  }
}

TEST(VisgrabCli, WcInfoOnAMissingFileExitsOne) {
  const RunResult r = runVisgrab("wc info /nonexistent/x.wc.xml");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/x.wc.xml"), std::string::npos) << r.output;
}

TEST(VisgrabCli, UsageMistakesExitTwo) {
  EXPECT_EQ(runVisgrab("").exitCode, 2);
  EXPECT_EQ(runVisgrab("wc").exitCode, 2);
  EXPECT_EQ(runVisgrab("wc info").exitCode, 2);
  EXPECT_EQ(runVisgrab("wc info a b").exitCode, 2);
  EXPECT_EQ(runVisgrab("wc info --bogus x").exitCode, 2);
  EXPECT_EQ(runVisgrab("frobnicate").exitCode, 2);
  EXPECT_EQ(runVisgrab("--help").exitCode, 0);
}

}  // namespace
