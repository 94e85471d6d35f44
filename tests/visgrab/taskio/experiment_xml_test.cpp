#include "visgrab/taskio/experiment_xml.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/test_support.hpp"

namespace visgrab::taskio {
namespace {

using grasp::GraspKind;
using rw::math::Q;
using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;

// g1 (<grasp id="g1">) starts on line 16.
const char* const kExperiment = R"(<visgrab>
  <experiment id="run7">
    <sceneInfo><sceneID> bottle_flat_03 </sceneID><notes>ignored</notes></sceneInfo>
    <gripper>
      <name>SchunkHand</name>
      <tcpframe>SchunkHand.SDHTCP</tcpframe>
      <preshape id="ball">
        <qopen>9 9 9</qopen><qclose>9 9 9</qclose><maxtau></maxtau>
      </preshape>
      <preshape id="ball">
        <qopen>-1.0 0.2 1.05 -1.0 0.2 -1.0 0.2</qopen>
        <qclose>0.0 0.35 1.05 0.0 0.35 0.0 0.35</qclose>
        <maxtau>2 2 2 2 2 2 2</maxtau>
      </preshape>
    </gripper>
    <grasp id="g1">
      <pose>
        <position>412.0 -37.5 905.2</position>
        <quaternion>0.7071067811865476 0 0.7071067811865476 0</quaternion>
      </pose>
      <qopen>0 0 0 0 0 0 0</qopen>
      <qclose>0.5 0.5 0 0.5 0.5 0.5 0.5</qclose>
      <maxtau>2 2 2 2 2 2 2</maxtau>
    </grasp>
    <preshapegrasp id="g2">
      <pose>
        <position>400 -20 910</position>
        <rotmatrix>1 0 0  0 -1 0  0 0 -1</rotmatrix>
      </pose>
      <preshape id="ball"/>
    </preshapegrasp>
    <contactgrasp id="g3">
      <contact><pos>405 -30 880</pos><dir>1 0 0</dir></contact>
      <contact><pos>455 -45 880</pos><dir>-0.7 0.7 0</dir></contact>
      <contact><pos>455 -15 880</pos><dir>-0.7 -0.7 0</dir></contact>
      <approachVector>0 0 -1</approachVector>
    </contactgrasp>
    <grasp id="g4">
      <pose>
        <position>0 0 1000</position>
        <rotmatrix>1 0 0  0 -1 0  0 0 -1</rotmatrix>
        <quaternion>0 0 0 1</quaternion>
      </pose>
      <qopen>0</qopen><qclose>1</qclose><maxtau></maxtau>
    </grasp>
    <grasp id="g5">
      <pose><position>0 0 0</position></pose>
      <qopen>0</qopen><qclose>1</qclose><maxtau>3</maxtau>
    </grasp>
    <notes>ignored too</notes>
  </experiment>
  <experiment id="other">
    <sceneInfo><sceneID>s2</sceneID></sceneInfo>
    <vg:preshapegrasp id="g1" xmlns:vg="urn:x"><vg:pose><vg:position>1 2 3</vg:position></vg:pose><vg:preshape id="p"/></vg:preshapegrasp>
    <gripper><preshape id="p"><qopen>1</qopen><qclose>2</qclose><maxtau>3</maxtau></preshape></gripper>
  </experiment>
</visgrab>
)";

TEST(ExperimentXmlTest, ReadsEveryGraspKind) {
  const auto got = parseExperimentXml(kExperiment, "exp.xml");
  ASSERT_TRUE(got.rejected.empty()) << got.rejected[0].format();
  ASSERT_EQ(got.requests.size(), 6u);

  const auto& g1 = got.requests[0];
  EXPECT_EQ(g1.sceneId, "bottle_flat_03");  // trimmed
  EXPECT_EQ(g1.method, "run7");
  EXPECT_EQ(g1.id, "g1");
  EXPECT_EQ(g1.kind, GraspKind::kRaw);
  EXPECT_EQ(g1.sourceFile, "exp.xml");
  EXPECT_EQ(g1.sourceLine, 16);
  // millimetres -> metres; quaternion (w, x, y, z) = (cos 45°, 0, sin 45°, 0): 90° about y.
  Transform3D X1 = Transform3D::Identity();
  X1.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  X1.translation() = Vector3D(0.412, -0.0375, 0.9052);
  EXPECT_TRANSFORM_NEAR(g1.X_W_tcp, X1, 1e-12);
  EXPECT_EQ(g1.qOpen, Q::Zero(7));
  Q closed(7);
  closed << 0.5, 0.5, 0, 0.5, 0.5, 0.5, 0.5;
  EXPECT_EQ(g1.qClosed, closed);
  EXPECT_EQ(g1.tauMax, Q::Constant(7, 2));

  // Pre-shape grasp: the later definition of "ball" wins; own id (not the pre-shape's).
  const auto& g2 = got.requests[1];
  EXPECT_EQ(g2.id, "g2");
  EXPECT_EQ(g2.kind, GraspKind::kRaw);
  EXPECT_EQ(g2.preshape, "ball");
  Transform3D X2 = Transform3D::Identity();
  X2.linear() << 1, 0, 0, 0, -1, 0, 0, 0, -1;  // row-major
  X2.translation() = Vector3D(0.4, -0.02, 0.91);
  EXPECT_TRANSFORM_NEAR(g2.X_W_tcp, X2, 1e-12);
  Q open(7);
  open << -1.0, 0.2, 1.05, -1.0, 0.2, -1.0, 0.2;
  EXPECT_EQ(g2.qOpen, open);
  EXPECT_EQ(g2.qClosed.size(), 7);
  EXPECT_EQ(g2.qClosed[1], 0.35);
  EXPECT_EQ(g2.tauMax, Q::Constant(7, 2));

  const auto& g3 = got.requests[2];
  EXPECT_EQ(g3.kind, GraspKind::kContacts);
  ASSERT_EQ(g3.contacts.size(), 3u);
  EXPECT_TRUE(g3.contacts[1].position.isApprox(Vector3D(0.455, -0.045, 0.88), 1e-15));
  EXPECT_EQ(g3.contacts[1].direction, Vector3D(-0.7, 0.7, 0));  // as written, not normalised
  EXPECT_EQ(g3.approach, Vector3D(0, 0, -1));

  // Both rotations: the later one (the quaternion, 180° about z) wins.
  const auto& g4 = got.requests[3];
  Transform3D X4 = Transform3D::Identity();
  X4.linear() << -1, 0, 0, 0, -1, 0, 0, 0, 1;
  X4.translation() = Vector3D(0, 0, 1);
  EXPECT_TRANSFORM_NEAR(g4.X_W_tcp, X4, 1e-12);
  EXPECT_EQ(g4.tauMax.size(), 0);

  // No rotation: identity.
  EXPECT_TRANSFORM_NEAR(got.requests[4].X_W_tcp, Transform3D::Identity(), 0.0);

  // Prefixed elements are read; the gripper may come after the grasps.
  const auto& o = got.requests[5];
  EXPECT_EQ(o.method, "other");
  EXPECT_EQ(o.sceneId, "s2");
  EXPECT_EQ(o.qOpen, Q::Constant(1, 1));
  EXPECT_EQ(o.tauMax, Q::Constant(1, 3));
  EXPECT_TRANSFORM_NEAR(o.X_W_tcp, rw::math::makeTranslation(Vector3D(0.001, 0.002, 0.003)), 1e-15);
}

struct BadGrasp {
  const char* name;
  const char* element;  // placed on line 4
  int line;
  const char* fragment;
};

class ExperimentBadGraspTest : public ::testing::TestWithParam<BadGrasp> {};

TEST_P(ExperimentBadGraspTest, RejectsThatGraspOnly) {
  const BadGrasp& bad = GetParam();
  const std::string text = std::string("<visgrab><experiment id=\"e\">\n") +
                           "<sceneInfo><sceneID>s</sceneID></sceneInfo>\n" +
                           "<gripper><preshape id=\"p\"><qopen>1</qopen><qclose>2</qclose>"
                           "<maxtau/></preshape></gripper>\n" +
                           bad.element + "\n" +
                           "<grasp id=\"ok\"><pose><position>0 0 0</position></pose>"
                           "<qopen>0</qopen><qclose>1</qclose><maxtau/></grasp>\n" +
                           "</experiment></visgrab>\n";
  const auto got = parseExperimentXml(text, "bad.xml");
  ASSERT_EQ(got.requests.size(), 1u);
  EXPECT_EQ(got.requests[0].id, "ok");
  ASSERT_EQ(got.rejected.size(), 1u);
  EXPECT_EQ(got.rejected[0].file, "bad.xml");
  EXPECT_EQ(got.rejected[0].line, bad.line);
  EXPECT_GT(got.rejected[0].column, 0);
  EXPECT_NE(got.rejected[0].message.find(bad.fragment), std::string::npos)
      << got.rejected[0].format();
}

INSTANTIATE_TEST_SUITE_P(
    Grasps, ExperimentBadGraspTest,
    ::testing::Values(
        BadGrasp{"NonUnitQuaternion",
                 "<grasp id=\"b\"><pose><position>0 0 0</position><quaternion>1 0 0 0.5"
                 "</quaternion></pose><qopen>0</qopen><qclose>1</qclose><maxtau/></grasp>",
                 4, "unit quaternion"},
        BadGrasp{"QuaternionCount",
                 "<grasp id=\"b\"><pose><position>0 0 0</position><quaternion>1 0 0"
                 "</quaternion></pose><qopen>0</qopen><qclose>1</qclose><maxtau/></grasp>",
                 4, "expected 4 numbers"},
        BadGrasp{"PositionCount",
                 "<grasp id=\"b\"><pose><position>0 0</position></pose><qopen>0</qopen>"
                 "<qclose>1</qclose><maxtau/></grasp>",
                 4, "expected 3 numbers"},
        BadGrasp{"NotARotation",
                 "<grasp id=\"b\"><pose><position>0 0 0</position><rotmatrix>2 0 0 0 1 0 0 0 1"
                 "</rotmatrix></pose><qopen>0</qopen><qclose>1</qclose><maxtau/></grasp>",
                 4, "not a rotation matrix"},
        BadGrasp{"BadNumber",
                 "<grasp id=\"b\"><pose><position>0 0 nan</position></pose><qopen>0</qopen>"
                 "<qclose>1</qclose><maxtau/></grasp>",
                 4, "nan"},
        BadGrasp{"QLengths",
                 "<grasp id=\"b\"><pose><position>0 0 0</position></pose><qopen>0</qopen>"
                 "<qclose>1 2</qclose><maxtau/></grasp>",
                 4, "as many as <qopen>"},
        BadGrasp{"MissingQ", "<grasp id=\"b\"><pose><position>0 0 0</position></pose></grasp>", 4,
                 "missing <qopen>"},
        BadGrasp{"UnknownPreshape",
                 "<preshapegrasp id=\"b\"><pose><position>0 0 0</position></pose>"
                 "<preshape id=\"q\"/></preshapegrasp>",
                 4, "pre-shape \"q\" is not defined"},
        BadGrasp{"OneContact",
                 "<contactgrasp id=\"b\"><contact><pos>0 0 0</pos><dir>1 0 0</dir></contact>"
                 "<approachVector>0 0 -1</approachVector></contactgrasp>",
                 4, "expected 2 or 3"},
        BadGrasp{"ZeroDirection",
                 "<contactgrasp id=\"b\"><contact><pos>0 0 0</pos><dir>0 0 0</dir></contact>"
                 "<contact><pos>0 0 0</pos><dir>1 0 0</dir></contact>"
                 "<approachVector>0 0 -1</approachVector></contactgrasp>",
                 4, "zero vector"},
        BadGrasp{"NoApproach",
                 "<contactgrasp id=\"b\"><contact><pos>0 0 0</pos><dir>0 1 0</dir></contact>"
                 "<contact><pos>0 0 0</pos><dir>1 0 0</dir></contact></contactgrasp>",
                 4, "missing <approachVector>"},
        BadGrasp{"DuplicateId",
                 "<grasp id=\"ok\"><pose><position>0 0 0</position></pose><qopen>0</qopen>"
                 "<qclose>1</qclose><maxtau/></grasp>",
                 5, "duplicate grasp id"}),
    [](const ::testing::TestParamInfo<BadGrasp>& p) { return std::string(p.param.name); });

TEST(ExperimentXmlTest, ExperimentWithoutSceneIsSkippedWithOneDiagnostic) {
  const std::string text =
      "<visgrab>\n<experiment id=\"e\"><grasp id=\"a\"/></experiment>\n"
      "<experiment id=\"f\"><sceneInfo><sceneID>s</sceneID></sceneInfo>"
      "<grasp id=\"a\"><pose><position>0 0 0</position></pose><qopen>0</qopen><qclose>1</qclose>"
      "<maxtau/></grasp></experiment>\n</visgrab>";
  const auto got = parseExperimentXml(text, "x.xml");
  ASSERT_EQ(got.rejected.size(), 1u);
  EXPECT_EQ(got.rejected[0].line, 2);
  EXPECT_NE(got.rejected[0].message.find("missing <sceneInfo>"), std::string::npos);
  ASSERT_EQ(got.requests.size(), 1u);
  EXPECT_EQ(got.requests[0].method, "f");
}

TEST(ExperimentXmlTest, WholeFileProblemsThrow) {
  EXPECT_THROW(parseExperimentXml("<visgrab><experiment></visgrab>", "x.xml"),
               rw::common::LoadError);
  EXPECT_THROW(parseExperimentXml("<CartesianTask/>", "x.xml"), rw::common::LoadError);
  EXPECT_THROW(readExperimentXml("/no/such/file.xml"), rw::common::LoadError);
}

}  // namespace
}  // namespace visgrab::taskio
