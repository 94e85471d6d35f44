#include "visgrab/taskio/grasp_list.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rw/common/text_file.hpp"
#include "support/test_support.hpp"

namespace visgrab::taskio {
namespace {

using grasp::GraspKind;
using grasp::GraspRequest;
using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;

GraspRequest rawRequest() {
  GraspRequest r;
  r.sceneId = "textured/single/cocacola/03";
  r.method = "mine";
  r.id = "g1";
  r.kind = GraspKind::kRaw;
  r.X_W_tcp = rw::math::makeTransform(
      Eigen::AngleAxisd(0.7, Vector3D(1, 2, 3).normalized()).toRotationMatrix(),
      Vector3D(0.412, -0.0375, 0.9052));
  r.qOpen = Q::LinSpaced(7, -1.0, 0.3);
  r.qClosed = Q::LinSpaced(7, 0.1, 0.9);
  r.tauMax = Q::Constant(7, 2.0);
  return r;
}

std::vector<GraspRequest> allKinds() {
  std::vector<GraspRequest> out;
  out.push_back(rawRequest());
  GraspRequest noTau = rawRequest();
  noTau.id = "g1b";
  noTau.tauMax = Q();
  out.push_back(noTau);
  GraspRequest pre = rawRequest();
  pre.id = "g2";
  pre.kind = GraspKind::kPreshape;
  pre.qOpen = pre.qClosed = pre.tauMax = Q();
  pre.preshape = "SDH_BALL";
  out.push_back(pre);
  GraspRequest pq = rawRequest();
  pq.id = "g3";
  pq.kind = GraspKind::kPoseAndQ;
  pq.qClosed = pq.tauMax = Q();
  out.push_back(pq);
  GraspRequest c;
  c.sceneId = "plain/double/cocacola_saltcylinder/06";
  c.method = "mine";
  c.id = "g4";
  c.kind = GraspKind::kContacts;
  c.contacts = {{Vector3D(0.405, -0.03, 0.88), Vector3D(1, 0, 0)},
                {Vector3D(0.455, -0.045, 0.88), Vector3D(-0.7, 0.7, 0)},
                {Vector3D(0.455, -0.015, 0.88), Vector3D(-0.7, -0.7, 0)}};
  c.approach = Vector3D(0, 0, -1);
  out.push_back(c);
  GraspRequest c2 = c;
  c2.id = "g5";
  c2.contacts.pop_back();
  out.push_back(c2);
  GraspRequest jaw = rawRequest();
  jaw.id = "g6";
  jaw.kind = GraspKind::kJaw;
  jaw.qOpen = jaw.qClosed = jaw.tauMax = Q();
  jaw.X_W_jaw = jaw.X_W_tcp;
  jaw.X_W_tcp = rw::math::Transform3D::Identity();
  jaw.width = 0.0625;
  jaw.score = 0.875;
  out.push_back(jaw);
  GraspRequest unscored = jaw;
  unscored.id = "g7";
  unscored.score.reset();
  out.push_back(unscored);
  return out;
}

void expectSame(const GraspRequest& a, const GraspRequest& b) {
  EXPECT_EQ(a.sceneId, b.sceneId);
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.preshape, b.preshape);
  if (a.kind != GraspKind::kContacts) {
    EXPECT_TRANSFORM_NEAR(a.X_W_tcp, b.X_W_tcp, 1e-12);
  }
  EXPECT_EQ(a.qOpen, b.qOpen);
  EXPECT_EQ(a.qClosed, b.qClosed);
  EXPECT_EQ(a.tauMax, b.tauMax);
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (std::size_t i = 0; i < a.contacts.size(); ++i) {
    EXPECT_EQ(a.contacts[i].position, b.contacts[i].position);
    EXPECT_EQ(a.contacts[i].direction, b.contacts[i].direction);
  }
  if (a.kind == GraspKind::kContacts) {
    EXPECT_EQ(a.approach, b.approach);
  }
  if (a.kind == GraspKind::kJaw) {
    EXPECT_TRANSFORM_NEAR(a.X_W_jaw, b.X_W_jaw, 1e-12);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.score, b.score);
  }
}

TEST(GraspListTest, RoundTripKeepsEveryKind) {
  const auto requests = allKinds();
  const std::string text = formatGraspList(requests);
  const auto back = parseGraspList(text, "list.csv");
  EXPECT_TRUE(back.rejected.empty()) << (back.rejected.empty() ? "" : back.rejected[0].format());
  ASSERT_EQ(back.requests.size(), requests.size());
  for (std::size_t i = 0; i < requests.size(); ++i) {
    SCOPED_TRACE(requests[i].id);
    expectSame(requests[i], back.requests[i]);
    EXPECT_EQ(back.requests[i].sourceFile, "list.csv");
    EXPECT_EQ(back.requests[i].sourceLine, static_cast<int>(i) + 7);  // after a 6-line header
  }
}

TEST(GraspListTest, RoundTripThroughAFile) {
  test::TempDir dir;
  const auto file = dir.path() / "grasps.csv";
  writeGraspList(allKinds(), file);
  const auto back = readGraspList(file);
  EXPECT_TRUE(back.rejected.empty());
  EXPECT_EQ(back.requests.size(), allKinds().size());
}

TEST(GraspListTest, ReadsAHandWrittenFile) {
  const std::string text =
      "# my grasps\n"
      "\n"
      "  textured/cocacola/img_03 , m , a , pose_q , 0.1,0.2,0.3, 0.7071068,0,0.7071068,0, "
      "3, 0.1,0.2,0.3   # trailing comment\n"
      "s1,m,b,preshape,0,0,1,1,0,0,0,SDH_BALL\r\n";
  const auto got = parseGraspList(text, "hand.csv");
  ASSERT_TRUE(got.rejected.empty()) << got.rejected[0].format();
  ASSERT_EQ(got.requests.size(), 2u);
  const GraspRequest& a = got.requests[0];
  EXPECT_EQ(a.sceneId, "textured/cocacola/img_03");
  EXPECT_EQ(a.kind, GraspKind::kPoseAndQ);
  EXPECT_EQ(a.sourceLine, 3);
  // (w, x, y, z) = (cos 45°, 0, sin 45°, 0): 90° about y, so x -> -z and z -> x.
  Transform3D expected = Transform3D::Identity();
  expected.linear() << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  expected.translation() = Vector3D(0.1, 0.2, 0.3);
  EXPECT_TRANSFORM_NEAR(a.X_W_tcp, expected, 1e-6);
  EXPECT_EQ(a.qOpen, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(got.requests[1].preshape, "SDH_BALL");
  EXPECT_EQ(got.requests[1].sourceLine, 4);
}

struct BadLine {
  const char* name;
  const char* line;
  const char* at;  // the diagnostic's column is where this text last occurs ("" = line end)
  const char* fragment;
};

class GraspListBadLineTest : public ::testing::TestWithParam<BadLine> {};

TEST_P(GraspListBadLineTest, GivesOneDiagnosticAndKeepsTheOthers) {
  const BadLine& bad = GetParam();
  const std::string good1 = "s,m,ok1,preshape,0,0,0,1,0,0,0,ball\n";
  const std::string good2 = "s,m,ok2,pose_q,0,0,0,1,0,0,0,1,0.5\n";
  const auto got = parseGraspList(good1 + bad.line + "\n" + good2, "bad.csv");
  ASSERT_EQ(got.requests.size(), 2u);
  EXPECT_EQ(got.requests[0].id, "ok1");
  EXPECT_EQ(got.requests[1].id, "ok2");
  ASSERT_EQ(got.rejected.size(), 1u);
  const auto& d = got.rejected[0];
  EXPECT_EQ(d.file, "bad.csv");
  EXPECT_EQ(d.line, 2);
  const std::string line = bad.line;
  const int column = *bad.at == '\0' ? static_cast<int>(line.size()) + 1
                                     : static_cast<int>(line.rfind(bad.at)) + 1;
  EXPECT_EQ(d.column, column);
  EXPECT_NE(d.message.find(bad.fragment), std::string::npos) << d.format();
  EXPECT_NE(d.format().find("bad.csv:2:"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    Lines, GraspListBadLineTest,
    ::testing::Values(
        BadLine{"BadNumber", "s,m,b,pose_q,0,0,x1,1,0,0,0,1,0.5", "x1", "position z"},
        BadLine{"NaN", "s,m,b,pose_q,0,0,0,1,0,0,0,1,nan", "nan", "q[0]"},
        BadLine{"NonUnitQuaternion", "s,m,b,pose_q,0,0,0,1,0,0,0.1,1,0.5", "1,0,0,0.1",
                "unit quaternion"},
        BadLine{"TooFewFields", "s,m,b,pose_q,0,0,0,1,0,0,0,2,0.5", "", "line ends early"},
        BadLine{"TooManyFields", "s,m,b,pose_q,0,0,0,1,0,0,0,1,0.5,7", "7", "too many fields"},
        BadLine{"ClosedCount", "s,m,b,raw,0,0,0,1,0,0,0,1,0.5,2,0.1,0.2,0", "2,0.1",
                "q_closed has 2"},
        BadLine{"TauCount", "s,m,b,raw,0,0,0,1,0,0,0,1,0.5,1,0.1,2,1,1", "2,1,1", "tau_max has 2"},
        BadLine{"ContactCount", "s,m,b,contacts,4,0,0,0,1,0,0", "4",
                "number of contacts: expected an integer from 2 to 3, got \"4\""},
        BadLine{"FractionalContactCount", "s,m,b,contacts,2.5,0,0,0,1,0,0", "2.5",
                "number of contacts: expected an integer from 2 to 3, got \"2.5\""},
        BadLine{"ZeroApproach", "s,m,b,contacts,2,0,0,0,1,0,0,1,0,0,-1,0,0,0,0,0", "0,0,0",
                "approach direction is zero"},
        BadLine{"UnknownKind", "s,m,b,grip,0,0,0", "grip", "unknown kind \"grip\""},
        BadLine{"EmptyPreshape", "s,m,b,preshape,0,0,0,1,0,0,0,", "", "pre-shape name is empty"},
        BadLine{"EmptyId", "s,m,,pose_q,0,0,0,1,0,0,0,1,0.5", ",pose_q", "grasp id is empty"},
        BadLine{"DuplicateId", "s,m,ok1,pose_q,0,0,0,1,0,0,0,1,0.5", "s,m,ok1", "first on line 1"}),
    [](const ::testing::TestParamInfo<BadLine>& p) { return std::string(p.param.name); });

TEST(GraspListTest, DocumentedExamplesRead) {
  std::string doc;
  ASSERT_TRUE(rw::common::readTextFile(test::sourceDir() / "docs/grasp-format.md", doc).empty());
  const std::string start = "### Example\n\n```\n";
  const auto from = doc.find(start);
  ASSERT_NE(from, std::string::npos);
  const auto to = doc.find("```", from + start.size());
  const auto example =
      parseGraspList(doc.substr(from + start.size(), to - from - start.size()), "grasp-format.md");
  EXPECT_TRUE(example.rejected.empty()) << example.rejected[0].format();
  EXPECT_EQ(example.requests.size(), 5u);
  // What the documented Python snippet writes.
  const auto python = parseGraspList(
      "textured/single/cocacola/03,mine,g1,raw,0.412,-0.0375,0.9052,0.7071067811865476,0.0,"
      "0.7071067811865476,0.0,7,0.0,0.0,0.0,0.0,0.0,0.0,0.0,7,0.5,0.5,0.0,0.5,0.5,0.5,0.5,0\n"
      "textured/single/cocacola/03,mine,g2,preshape,0.4,-0.02,0.91,0.0,1.0,0.0,0.0,SDH_BALL\n",
      "python.csv");
  EXPECT_TRUE(python.rejected.empty());
  EXPECT_EQ(python.requests.size(), 2u);
}

TEST(GraspListTest, UnknownPreshapeNameIsNotChecked) {
  const auto got = parseGraspList("s,m,b,preshape,0,0,0,1,0,0,0,no_such_shape\n", "x.csv");
  EXPECT_TRUE(got.rejected.empty());
  ASSERT_EQ(got.requests.size(), 1u);
  EXPECT_EQ(got.requests[0].preshape, "no_such_shape");
}

TEST(GraspListTest, QuaternionSlightlyOffUnitIsNormalised) {
  const auto got = parseGraspList("s,m,b,pose_q,0,0,0,1.0005,0,0,0,1,0.5\n", "x.csv");
  ASSERT_TRUE(got.rejected.empty());
  EXPECT_TRANSFORM_NEAR(got.requests[0].X_W_tcp, Transform3D::Identity(), 1e-12);
}

TEST(GraspListTest, WriterRefusesTextThatCannotBeRead) {
  GraspRequest r = rawRequest();
  r.id = "a,b";
  EXPECT_THROW(formatGraspList({r}), std::invalid_argument);
  r = rawRequest();
  r.kind = GraspKind::kPreshape;
  r.preshape = "";
  EXPECT_THROW(formatGraspList({r}), std::invalid_argument);
}

TEST(GraspListTest, KindNamesRoundTrip) {
  for (GraspKind k :
       {GraspKind::kRaw, GraspKind::kPreshape, GraspKind::kPoseAndQ, GraspKind::kContacts}) {
    EXPECT_EQ(kindFromName(grasp::kindName(k)), k);
  }
  EXPECT_FALSE(kindFromName("Raw"));
}

}  // namespace
}  // namespace visgrab::taskio
