// `visgrab sim` and `visgrab grasp` on the simulator tests' SDH scene.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"

namespace {

using visgrab::test::RunResult;
using visgrab::test::runVisgrab;

std::string scene() {
  return "'" +
         (visgrab::test::sourceDir() / "tests/rwsim/simulator/data/sdh_box.dwc.xml").string() + "'";
}

const std::string kCylinder =
    " --hand SchunkHand --pose 0 0 0.05 0 180 0"
    " --qopen -1.048 0.174 0 -1.048 0.174 -1.048 0.174 --qclose 0 0.349 0 0 0.349 0 0.349"
    " --taumax 2.1,1.4,2.1,1.05,0.7,1.05,0.7";

TEST(SimCli, SimWritesPosesPerStep) {
  visgrab::test::TempDir dir;
  const auto csv = dir.path() / "poses.csv";
  const RunResult r =
      runVisgrab("sim " + scene() + " --time 0.05 --dt 0.01 --out '" + csv.string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("simulated 0.05 s in 5 steps"), std::string::npos) << r.output;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "time,body,x,y,z,qw,qx,qy,qz");
  int rows = 0;
  std::string last;
  for (std::string line; std::getline(in, line);) {
    ++rows;
    last = line;
  }
  EXPECT_EQ(rows, 6 * 11);  // t = 0 and 5 steps, 11 bodies
  EXPECT_EQ(last.rfind("0.05,SchunkHand.f3.Joint3,", 0), 0u) << last;
}

TEST(SimCli, SimPrintsFinalPosesWithoutOut) {
  const RunResult r = runVisgrab("sim " + scene() + " --time 0.02");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("final poses"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  Box  "), std::string::npos) << r.output;
}

TEST(SimCli, GraspReportsOutcomeCodeAndQualities) {
  const RunResult r = runVisgrab("grasp " + scene() + kCylinder);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("outcome: stable (RobWork code 1)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Q_lift: 0.9"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Q_GWS: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Q_GWS,unit: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("contacts after lifting"), std::string::npos) << r.output;
}

TEST(SimCli, GraspTakesATrialProtocol) {
  // --protocol lift is the default protocol: the same report.
  const RunResult plain = runVisgrab("grasp " + scene() + kCylinder);
  const RunResult lift = runVisgrab("grasp " + scene() + kCylinder + " --protocol lift");
  ASSERT_EQ(lift.exitCode, 0) << lift.output;
  EXPECT_EQ(lift.output, plain.output);
  // The shake shakes along and about the hand's jaw frame: a device named alone has none, so
  // it is refused, saying what to give instead.
  const RunResult bare = runVisgrab("grasp " + scene() + kCylinder + " --protocol shake");
  EXPECT_EQ(bare.exitCode, 2) << bare.output;
  EXPECT_NE(bare.output.find("--protocol: the protocol \"shake\" gives an axis in the jaw frame, "
                             "but device SchunkHand declares no jaw frame (<JawFrame> in its grasp "
                             "description, docs/grasp-utilities.md): give a hand description"),
            std::string::npos)
      << bare.output;
  // With the SDH's description it runs (no gravity, two fingers judged); its verdict is the
  // trial's.
  const RunResult shake =
      runVisgrab("grasp " + scene() + " --hand '" +
                 (visgrab::test::sourceDir() / "scenes/hands/sdh").string() +
                 "' --pose 0 0 0.05 0 180 0 --preshape SDH_CYL --protocol shake");
  ASSERT_EQ(shake.exitCode, 0) << shake.output;
  EXPECT_NE(shake.output.find("outcome: "), std::string::npos) << shake.output;
  // An unknown name lists the known protocols; a bad file names its line.
  const RunResult unknown = runVisgrab("grasp " + scene() + kCylinder + " --protocol wobble");
  EXPECT_EQ(unknown.exitCode, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("unknown protocol \"wobble\""), std::string::npos)
      << unknown.output;
  EXPECT_NE(unknown.output.find("known: lift, shake"), std::string::npos) << unknown.output;
  visgrab::test::TempDir dir;
  const auto bad = dir.path() / "bad.xml";
  std::ofstream(bad) << "<TrialProtocol name=\"b\">\n  <Phases>\n    <Lift height=\"0\"/>\n"
                        "  </Phases>\n</TrialProtocol>\n";
  const RunResult broken =
      runVisgrab("grasp " + scene() + kCylinder + " --protocol '" + bad.string() + "'");
  EXPECT_NE(broken.exitCode, 0) << broken.output;
  EXPECT_NE(broken.output.find("bad.xml:3:5: error: <Lift>: attribute height: expected a number "
                               "> 0, got 0"),
            std::string::npos)
      << broken.output;
}

TEST(SimCli, BadArgumentsAreUsageErrors) {
  struct Case {
    std::string args;
    std::string message;
  };
  const std::string open7 = " --qopen -1.048 0.174 0 -1.048 0.174 -1.048 0.174";
  const std::string close7 = " --qclose 0 0.349 0 0 0.349 0 0.349";
  const Case cases[] = {
      {"sim " + scene(), "--time SECONDS is required"},
      {"sim " + scene() + " --time -1", "--time must be > 0"},
      {"sim " + scene() + " --time 1 --speed 2", "unknown option --speed"},
      {"grasp " + scene() + " --hand SchunkHand" + open7 + close7, "--pose"},
      {"grasp " + scene() + " --hand SchunkHand --pose 0 0 0.05 0 180" + open7 + close7,
       "--pose needs 6 numbers"},
      {"grasp " + scene() + " --hand SchunkHand --pose 0 0 0.05 0 180 0 --qopen 0 0 0" + close7,
       "--qopen has 3 values but SchunkHand has 7 DOF"},
      {"grasp " + scene() + " --hand Robot --pose 0 0 0.05 0 180 0" + open7 + close7,
       "no rigid device 'Robot'"},
      {"grasp " + scene() + kCylinder + " --taumax 1 1", "--taumax given twice"},
      {"grasp " + scene() + " --hand SchunkHand --pose 0 0 0.05x 0 180 0" + open7 + close7,
       "'0.05x' is not a number"},
  };
  for (const Case& c : cases) {
    const RunResult r = runVisgrab(c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find("usage: visgrab "), std::string::npos) << r.output;
  }
}

}  // namespace
