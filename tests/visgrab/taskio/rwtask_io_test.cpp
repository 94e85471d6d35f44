#include "visgrab/taskio/rwtask_io.hpp"

#include <gtest/gtest.h>

#include <string>

#include "support/test_support.hpp"

namespace visgrab::taskio {
namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;

Transform3D pose(double angle, const Vector3D& axis, const Vector3D& p) {
  return rw::math::makeTransform(Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(), p);
}

/// A task like RobWork's gtest reference (reference §3.4): every field set.
GraspTask referenceTask() {
  GraspTask task;
  task.gripperId = "SchunkHand";
  task.tcpId = "SchunkHand.SDHTCP";
  task.graspControllerId = "GraspController";
  setStringProperty(task.otherProperties, "SceneID", "textured/single/cocacola/03");
  GraspSubTask sub;
  sub.refframe = "object";
  sub.objectId = "cocacola";
  sub.taskId = "taskId1";
  sub.offset = pose(0.3, Vector3D(0, 0, 1), Vector3D(0.01, 0.02, 0.03));
  sub.approach = rw::math::makeTranslation(Vector3D(0, 0, 0.04));
  sub.retract = rw::math::makeTranslation(Vector3D(0, 0, 0.1));
  sub.openQ = Q::LinSpaced(7, -1.571, 0.174);
  sub.closeQ = Q::LinSpaced(7, 0.0, 0.419);
  sub.tauMax = Q::Constant(7, 2.0);
  setStringProperty(sub.otherProperties, "VisGraBID", "run7.g1");
  for (int i = 0; i < 3; ++i) {
    GraspTarget t;
    t.pose = pose(0.1 * (i + 1), Vector3D(1, i, 2), Vector3D(0.1 * i, -0.2, 1.0 / 3.0));
    sub.targets.push_back(t);
  }
  GraspResult r;
  r.testStatus = 1;
  r.liftResult = 0.123;
  r.gripperConfigurationGrasp = Q::Constant(7, 0.25);
  r.gripperConfigurationLift = Q::Constant(7, 0.26);
  r.qualityBeforeLifting = Eigen::Vector3d(0.1, 0.2, 0.3);
  r.qualityAfterLifting = Eigen::Vector2d(0.4, 0.5);
  r.objectTtcpTarget = pose(0.2, Vector3D(0, 1, 0), Vector3D(1, 2, 3));
  r.objectTtcpApproach = pose(0.3, Vector3D(0, 1, 1), Vector3D(1, 2, 4));
  r.objectTtcpGrasp = pose(0.4, Vector3D(1, 1, 0), Vector3D(1, 2, 5));
  r.objectTtcpLift = pose(0.5, Vector3D(1, 0, 0), Vector3D(1, 2, 6));
  for (int i = 0; i < 4; ++i) {
    r.contactsGrasp.push_back(
        {Vector3D(i, 1, 2), Vector3D(0, 0, 1), Vector3D(0.5 * i, 0.25, -1.5)});
  }
  for (int i = 0; i < 2; ++i) {
    r.contactsLift.push_back({Vector3D(-i, 1, 2), Vector3D(1, 0, 0), Vector3D(3, 2, 1)});
  }
  r.interferenceTs = {pose(0.1, Vector3D(1, 0, 0), Vector3D(0, 0, 1)), Transform3D::Identity()};
  r.interferenceDistances = {0.1, 0.2, 0.3, 0.4};
  r.interferenceAngles = {0.4, 0.5, 0.6};
  r.interferences = {0.7, 0.8};
  r.interference = 1.123;
  sub.targets[0].result = r;
  GraspResult other;
  other.testStatus = 2;  // CollisionInitially: no lift fields
  sub.targets[2].result = other;
  task.subTasks.push_back(sub);
  GraspSubTask world;
  world.targets.push_back(GraspTarget{});
  task.subTasks.push_back(world);
  return task;
}

void expectSameQ(const Q& a, const Q& b) {
  ASSERT_EQ(a.size(), b.size());
  for (Eigen::Index i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
}

void expectSameResult(const GraspResult& a, const GraspResult& b) {
  EXPECT_EQ(a.testStatus, b.testStatus);
  EXPECT_EQ(a.liftResult, b.liftResult);
  expectSameQ(a.gripperConfigurationGrasp, b.gripperConfigurationGrasp);
  expectSameQ(a.gripperConfigurationLift, b.gripperConfigurationLift);
  expectSameQ(a.qualityBeforeLifting, b.qualityBeforeLifting);
  expectSameQ(a.qualityAfterLifting, b.qualityAfterLifting);
  EXPECT_TRANSFORM_NEAR(a.objectTtcpTarget, b.objectTtcpTarget, 1e-15);
  EXPECT_TRANSFORM_NEAR(a.objectTtcpApproach, b.objectTtcpApproach, 1e-15);
  EXPECT_TRANSFORM_NEAR(a.objectTtcpGrasp, b.objectTtcpGrasp, 1e-15);
  EXPECT_TRANSFORM_NEAR(a.objectTtcpLift, b.objectTtcpLift, 1e-15);
  ASSERT_EQ(a.contactsGrasp.size(), b.contactsGrasp.size());
  for (std::size_t i = 0; i < a.contactsGrasp.size(); ++i) {
    EXPECT_EQ(a.contactsGrasp[i].position, b.contactsGrasp[i].position);
    EXPECT_EQ(a.contactsGrasp[i].normal, b.contactsGrasp[i].normal);
    EXPECT_EQ(a.contactsGrasp[i].force, b.contactsGrasp[i].force);
  }
  ASSERT_EQ(a.contactsLift.size(), b.contactsLift.size());
  for (std::size_t i = 0; i < a.contactsLift.size(); ++i) {
    EXPECT_EQ(a.contactsLift[i].position, b.contactsLift[i].position);
    EXPECT_EQ(a.contactsLift[i].force, b.contactsLift[i].force);
  }
  ASSERT_EQ(a.interferenceTs.size(), b.interferenceTs.size());
  for (std::size_t i = 0; i < a.interferenceTs.size(); ++i) {
    EXPECT_TRANSFORM_NEAR(a.interferenceTs[i], b.interferenceTs[i], 1e-15);
  }
  EXPECT_EQ(a.interferenceDistances, b.interferenceDistances);
  EXPECT_EQ(a.interferenceAngles, b.interferenceAngles);
  EXPECT_EQ(a.interferences, b.interferences);
  EXPECT_EQ(a.interference, b.interference);
}

void expectSameTask(const GraspTask& a, const GraspTask& b) {
  EXPECT_EQ(a.gripperId, b.gripperId);
  EXPECT_EQ(a.tcpId, b.tcpId);
  EXPECT_EQ(a.graspControllerId, b.graspControllerId);
  EXPECT_EQ(stringProperty(a.otherProperties, "SceneID"),
            stringProperty(b.otherProperties, "SceneID"));
  ASSERT_EQ(a.subTasks.size(), b.subTasks.size());
  for (std::size_t s = 0; s < a.subTasks.size(); ++s) {
    const GraspSubTask& x = a.subTasks[s];
    const GraspSubTask& y = b.subTasks[s];
    EXPECT_EQ(x.refframe, y.refframe);
    EXPECT_EQ(x.objectId, y.objectId);
    EXPECT_EQ(x.taskId, y.taskId);
    EXPECT_TRANSFORM_NEAR(x.offset, y.offset, 1e-15);
    EXPECT_TRANSFORM_NEAR(x.approach, y.approach, 1e-15);
    EXPECT_TRANSFORM_NEAR(x.retract, y.retract, 1e-15);
    expectSameQ(x.openQ, y.openQ);
    expectSameQ(x.closeQ, y.closeQ);
    expectSameQ(x.tauMax, y.tauMax);
    EXPECT_EQ(stringProperty(x.otherProperties, "VisGraBID"),
              stringProperty(y.otherProperties, "VisGraBID"));
    ASSERT_EQ(x.targets.size(), y.targets.size());
    for (std::size_t t = 0; t < x.targets.size(); ++t) {
      SCOPED_TRACE("sub-task " + std::to_string(s) + " target " + std::to_string(t));
      EXPECT_TRANSFORM_NEAR(x.targets[t].pose, y.targets[t].pose, 1e-15);
      ASSERT_EQ(x.targets[t].result.has_value(), y.targets[t].result.has_value());
      if (x.targets[t].result) expectSameResult(*x.targets[t].result, *y.targets[t].result);
    }
  }
}

TEST(RwTaskIoTest, WriteThenReadKeepsEveryField) {
  const GraspTask task = referenceTask();
  const std::string text = formatRwTask(task);
  std::vector<rw::common::Diagnostic> warnings;
  const GraspTask back = parseRwTask(text, "mem.rwtask.xml", &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0].format();
  expectSameTask(task, back);
  // Writing the read model again gives the same text.
  EXPECT_EQ(formatRwTask(back), text);
}

TEST(RwTaskIoTest, WritesPropertiesAlphabeticallyWithRobWorksNames) {
  const std::string text = formatRwTask(referenceTask());
  const auto at = [&](const char* s) { return text.find(s); };
  EXPECT_NE(at("<Name>ObjectTtcptTarget</Name>"), std::string::npos);
  EXPECT_LT(at("<Name>Approach</Name>"), at("<Name>CloseQ</Name>"));
  EXPECT_LT(at("<Name>TauMax</Name>"), at("<Name>VisGraBID</Name>"));
  EXPECT_LT(at("<Name>VisGraBID</Name>"), at("<Name>refframe</Name>"));
  EXPECT_LT(at("<Name>GraspController</Name>"), at("<Name>Gripper</Name>"));
  EXPECT_LT(at("<Name>SceneID</Name>"), at("<Name>TCP</Name>"));
  EXPECT_NE(at("<Name>LiftStatus</Name>"), std::string::npos);
  EXPECT_NE(at("<PropertyMap/>"), std::string::npos);  // the target without result
}

TEST(RwTaskIoTest, ReadsRobWorksPg70Task) {
  REQUIRE_COMPAT_DATA(data);
  const auto file = data / "scene/grasping/grasptask_pg70_box.rwtask.xml";
  std::vector<rw::common::Diagnostic> warnings;
  const GraspTask task = readRwTask(file, &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0].format();
  EXPECT_EQ(task.gripperId, "PG70");
  EXPECT_EQ(task.tcpId, "PG70.TCPPG70");
  EXPECT_EQ(task.graspControllerId, "GraspController");
  ASSERT_EQ(task.subTasks.size(), 1u);
  const GraspSubTask& sub = task.subTasks[0];
  EXPECT_EQ(sub.refframe, "object");
  EXPECT_TRANSFORM_NEAR(sub.offset, Transform3D::Identity(), 0.0);
  EXPECT_TRANSFORM_NEAR(sub.approach, rw::math::makeTranslation(Vector3D(0, 0, 0.04)), 0.0);
  EXPECT_TRANSFORM_NEAR(sub.retract, rw::math::makeTranslation(Vector3D(0, 0, 0.1)), 0.0);
  EXPECT_EQ(sub.openQ, Q::Constant(1, 0.035));
  EXPECT_EQ(sub.closeQ, Q::Constant(1, 0.0));
  EXPECT_EQ(sub.tauMax.size(), 0);
  ASSERT_EQ(sub.targets.size(), 100u);
  // All targets succeeded; the file holds two grasp widths (54 x 0.0245, 46 x 0.0315).
  int narrow = 0;
  int wide = 0;
  for (const auto& t : sub.targets) {
    ASSERT_TRUE(t.result);
    EXPECT_EQ(t.result->testStatus, 1);
    ASSERT_EQ(t.result->gripperConfigurationGrasp.size(), 1);
    narrow += t.result->gripperConfigurationGrasp[0] == 0.0245 ? 1 : 0;
    wide += t.result->gripperConfigurationGrasp[0] == 0.0315 ? 1 : 0;
  }
  EXPECT_EQ(narrow, 54);
  EXPECT_EQ(wide, 46);
  EXPECT_EQ(sub.targets[0].result->gripperConfigurationGrasp, Q::Constant(1, 0.0245));
  // Target 0 as written in the file.
  Transform3D first = Transform3D::Identity();
  first.translation() = Vector3D(0.004442837307065087, 0, -0.02311382284533061);
  first.linear() << 0, 0.1372859959809743, -0.9905314509431349, 1, 0, 0, 0, -0.9905314509431348,
      -0.1372859959809743;
  EXPECT_TRANSFORM_NEAR(sub.targets[0].pose, first, 0.0);
  EXPECT_TRANSFORM_NEAR(sub.targets[0].result->objectTtcpTarget, first, 0.0);
  EXPECT_EQ(sub.targets[0].result->qualityAfterLifting, Q::Constant(1, 0.9999500024998749));

  // Writing it back and reading our output gives the same model.
  const GraspTask back = parseRwTask(formatRwTask(task), "out.rwtask.xml");
  expectSameTask(task, back);
}

TEST(RwTaskIoTest, ReadsEveryTransformForm) {
  const std::string text = R"(<CartesianTask><Entities><CartesianTask><Targets>
  <CartesianTarget id="0"><Transform3D>1 0 0 0.1  0 1 0 0.2  0 0 1 0.3</Transform3D></CartesianTarget>
  <CartesianTarget id="1"><Transform3D><Pos unit="mm">100 200 300</Pos><RPY unit="deg">90 0 0</RPY></Transform3D></CartesianTarget>
  <CartesianTarget id="2"><Transform3D><Pos>0 0 0</Pos><EAA>0 0 1.5707963267948966</EAA></Transform3D></CartesianTarget>
  <CartesianTarget id="3"><Transform3D><Pos>0 0 0</Pos><Quaternion>0 0 0.7071067811865476 0.7071067811865476</Quaternion></Transform3D></CartesianTarget>
  <CartesianTarget id="4"><Transform3D><Pos>0 0 0</Pos><Rotation3D>0 0 0.7071067811865476 0.7071067811865476</Rotation3D></Transform3D></CartesianTarget>
  <CartesianTarget id="5"><Transform3D><Matrix>0 -1 0 0.1  1 0 0 0.2  0 0 1 0.3</Matrix></Transform3D></CartesianTarget>
  <CartesianTarget id="6"><Transform3D><Pos unit="cm">1 2 3</Pos><Rotation3D>0 -1 0 1 0 0 0 0 1</Rotation3D></Transform3D></CartesianTarget>
  </Targets></CartesianTask></Entities></CartesianTask>)";
  const GraspTask task = parseRwTask(text, "forms.rwtask.xml");
  ASSERT_EQ(task.subTasks.size(), 1u);
  const auto& t = task.subTasks[0].targets;
  ASSERT_EQ(t.size(), 7u);
  const Transform3D rz90 = pose(std::numbers::pi / 2, Vector3D::UnitZ(), Vector3D::Zero());
  EXPECT_TRANSFORM_NEAR(t[0].pose, rw::math::makeTranslation(Vector3D(0.1, 0.2, 0.3)), 1e-15);
  EXPECT_TRANSFORM_NEAR(
      t[1].pose, pose(std::numbers::pi / 2, Vector3D::UnitZ(), Vector3D(0.1, 0.2, 0.3)), 1e-12);
  EXPECT_TRANSFORM_NEAR(t[2].pose, rz90, 1e-12);
  EXPECT_TRANSFORM_NEAR(t[3].pose, rz90, 1e-12);
  EXPECT_TRANSFORM_NEAR(t[4].pose, rz90, 1e-12);
  EXPECT_TRANSFORM_NEAR(
      t[5].pose, pose(std::numbers::pi / 2, Vector3D::UnitZ(), Vector3D(0.1, 0.2, 0.3)), 1e-12);
  EXPECT_TRANSFORM_NEAR(
      t[6].pose, pose(std::numbers::pi / 2, Vector3D::UnitZ(), Vector3D(0.01, 0.02, 0.03)), 1e-12);
  EXPECT_FALSE(t[0].result);
  EXPECT_EQ(task.subTasks[0].refframe, "WORLD");
}

TEST(RwTaskIoTest, BadValueIsAnErrorWithFileLineColumn) {
  const std::string text =
      "<CartesianTask><Entities><CartesianTask><Targets>\n"
      "  <CartesianTarget id=\"0\"><Transform3D><Pos>0 0</Pos></Transform3D></CartesianTarget>\n"
      "</Targets></CartesianTask></Entities></CartesianTask>\n";
  try {
    parseRwTask(text, "bad.rwtask.xml");
    FAIL() << "expected LoadError";
  } catch (const rw::common::LoadError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    const auto& d = e.diagnostics()[0];
    EXPECT_EQ(d.line, 2);
    EXPECT_EQ(d.column, 40);  // the <Pos>
    EXPECT_NE(d.message.find("expected 3 numbers"), std::string::npos) << d.format();
    EXPECT_NE(std::string(e.what()).find("bad.rwtask.xml:2:40"), std::string::npos) << e.what();
  }
}

TEST(RwTaskIoTest, WrongPropertyTypeAndMissingIdAreErrors) {
  const std::string text =
      "<CartesianTask><Entities><CartesianTask><Targets>\n"
      "  <CartesianTarget><Transform3D>1 0 0 0 0 1 0 0 0 0 1 0</Transform3D></CartesianTarget>\n"
      "</Targets><PropertyMap><Property><Name>OpenQ</Name><Value><String>a</String></Value>"
      "</Property></PropertyMap></CartesianTask></Entities></CartesianTask>\n";
  try {
    parseRwTask(text, "bad.rwtask.xml");
    FAIL() << "expected LoadError";
  } catch (const rw::common::LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 2u) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 2);
    EXPECT_NE(e.diagnostics()[0].message.find("no id attribute"), std::string::npos);
    EXPECT_NE(e.diagnostics()[1].message.find("expected a <Q> value"), std::string::npos);
  }
}

TEST(RwTaskIoTest, NonIntegerTestStatusNamesTheProperty) {
  const std::string text =
      "<CartesianTask><Entities><CartesianTask><Targets>\n"
      "  <CartesianTarget id=\"0\"><Transform3D>1 0 0 0 0 1 0 0 0 0 1 0</Transform3D>\n"
      "<PropertyMap><Property><Name>TestStatus</Name><Value><Integer>2.5</Integer></Value>"
      "</Property></PropertyMap></CartesianTarget>\n"
      "</Targets></CartesianTask></Entities></CartesianTask>\n";
  try {
    parseRwTask(text, "bad.rwtask.xml");
    FAIL() << "expected LoadError";
  } catch (const rw::common::LoadError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 3);
    EXPECT_EQ(e.diagnostics()[0].message,
              "property 'TestStatus': expected an integer from -1000000000 to 1000000000, got "
              "\"2.5\"");
  }
}

TEST(RwTaskIoTest, MalformedXmlThrows) {
  EXPECT_THROW(parseRwTask("<CartesianTask><Entities></CartesianTask>", "x.xml"),
               rw::common::LoadError);
  EXPECT_THROW(parseRwTask("<visgrab/>", "x.xml"), rw::common::LoadError);
}

TEST(RwTaskIoTest, UnknownPropertyTypesAreKeptWithAWarning) {
  const std::string text =
      "<CartesianTask><Entities/><PropertyMap>\n"
      "<Property><Name>Weird</Name><Value><Banana kind=\"ripe\">3</Banana></Value></Property>\n"
      "<Property><Name>Nested</Name><Value><PropertyMap><Property><Name>a</Name><Value>"
      "<Integer>1</Integer></Value></Property></PropertyMap></Value></Property>\n"
      "</PropertyMap></CartesianTask>";
  std::vector<rw::common::Diagnostic> warnings;
  const GraspTask task = parseRwTask(text, "x.xml", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].line, 2);
  EXPECT_NE(warnings[0].message.find("<Banana>"), std::string::npos);
  ASSERT_EQ(task.otherProperties.size(), 2u);
  const std::string out = formatRwTask(task);
  EXPECT_NE(out.find("<Banana kind=\"ripe\">3</Banana>"), std::string::npos) << out;
  const GraspTask back = parseRwTask(out, "y.xml");
  ASSERT_EQ(back.otherProperties.size(), 2u);
  // Written in alphabetical order: Nested, then Weird.
  EXPECT_EQ(back.otherProperties[0].name, "Nested");
  EXPECT_EQ(back.otherProperties[0].value.children.size(), 1u);
  EXPECT_EQ(back.otherProperties[1].name, "Weird");
  EXPECT_EQ(back.otherProperties[1].value.attributeOr("kind", ""), "ripe");
}

TEST(RwTaskIoTest, NonOrthonormalRotationIsProjectedWithAWarning) {
  const std::string text =
      "<CartesianTask><Entities><CartesianTask><Targets><CartesianTarget id=\"0\"><Transform3D>"
      "<Pos>0 0 0</Pos><Rotation3D>1.1 0 0 0 1 0 0 0 1</Rotation3D></Transform3D>"
      "</CartesianTarget></Targets></CartesianTask></Entities></CartesianTask>";
  std::vector<rw::common::Diagnostic> warnings;
  const GraspTask task = parseRwTask(text, "x.xml", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].severity, rw::common::Diagnostic::Severity::kWarning);
  EXPECT_TRANSFORM_NEAR(task.subTasks[0].targets[0].pose, Transform3D::Identity(), 1e-12);
}

TEST(RwTaskIoTest, RequestsComposeRefframeOffsetTarget) {
  GraspTask task = referenceTask();
  const Transform3D X_W_object = pose(0.4, Vector3D(0, 0, 1), Vector3D(0.5, 0, 0.8));
  EXPECT_THROW(toGraspRequests(task, "s", "m"), std::invalid_argument);
  const auto requests = toGraspRequests(task, "s", "m", [&](const std::string& frame) {
    return frame == "object" ? std::optional(X_W_object) : std::nullopt;
  });
  ASSERT_EQ(requests.size(), 4u);
  const GraspSubTask& sub = task.subTasks[0];
  EXPECT_TRANSFORM_NEAR(requests[1].X_W_tcp, X_W_object * sub.offset * sub.targets[1].pose, 1e-15);
  EXPECT_EQ(requests[1].id, "taskId1.1");
  EXPECT_EQ(requests[1].kind, grasp::GraspKind::kRaw);
  EXPECT_EQ(requests[1].qOpen, sub.openQ);
  EXPECT_EQ(requests[1].qClosed, sub.closeQ);
  EXPECT_EQ(requests[1].tauMax, sub.tauMax);
  EXPECT_EQ(requests[3].id, "1.0");  // no task id: sub-task index
  EXPECT_TRANSFORM_NEAR(requests[3].X_W_tcp, Transform3D::Identity(), 0.0);
}

TEST(RwTaskIoTest, RequestsToTaskAndResultsBack) {
  grasp::GraspRequest r;
  r.sceneId = "textured/single/cocacola/03";
  r.id = "g7";
  r.X_W_tcp = pose(0.3, Vector3D(1, 0, 0), Vector3D(0.4, 0, 0.9));
  r.qOpen = Q::Constant(7, 0.1);
  r.qClosed = Q::Constant(7, 0.5);
  GraspTask task = fromGraspRequests({r, r}, "SchunkHand", "SchunkHand.SDHTCP");
  EXPECT_EQ(stringProperty(task.otherProperties, "SceneID"), r.sceneId);
  ASSERT_EQ(task.targetCount(), 2u);
  setResult(targetAt(task, 1), rwsim::trial::GraspOutcome::kSlipped, 0.75, 0.02, 0.005,
            Q::Constant(7, 0.3));
  EXPECT_THROW(targetAt(task, 2), std::out_of_range);
  const GraspTask back = parseRwTask(formatRwTask(task), "x.rwtask.xml");
  const auto requests = toGraspRequests(back, "textured/single/cocacola/03", "m");
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[0].id, "g7");
  EXPECT_TRANSFORM_NEAR(requests[0].X_W_tcp, r.X_W_tcp, 1e-15);
  EXPECT_EQ(requests[0].qOpen, r.qOpen);
  ASSERT_TRUE(back.subTasks[1].targets[0].result);
  const GraspResult& res = *back.subTasks[1].targets[0].result;
  EXPECT_EQ(res.testStatus, 5);  // RobWork's ObjectSlipped
  EXPECT_EQ(res.liftResult, 0.75);
  EXPECT_EQ(res.qualityAfterLifting, Q::Constant(1, 0.75));
  // The VisGraB-era plugin's order: q0 with the measured forces, q1 with unit forces.
  ASSERT_EQ(res.qualityBeforeLifting.size(), 2);
  EXPECT_EQ(res.qualityBeforeLifting[0], 0.02);
  EXPECT_EQ(res.qualityBeforeLifting[1], 0.005);
  EXPECT_EQ(res.gripperConfigurationGrasp, Q::Constant(7, 0.3));
  EXPECT_FALSE(back.subTasks[0].targets[0].result);
  grasp::GraspRequest notRaw = r;
  notRaw.kind = grasp::GraspKind::kContacts;
  EXPECT_THROW(fromGraspRequests({notRaw}, "a", "b"), std::invalid_argument);
}

}  // namespace
}  // namespace visgrab::taskio
