// The dynamic workcell loader on small scenes written inline (reference §2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rwsim/loaders/dwc_test_scene.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::common::Diagnostic;
using rw::math::Vector3D;
using rwsim::dynamics::Body;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DynamicWorkCell;
using visgrab::test::writeFile;
using visgrab::test::dwc::SceneDir;
using visgrab::test::dwc::sdhController;
using visgrab::test::dwc::sdhDevice;

class DynamicWorkCellLoader : public ::testing::Test {
 protected:
  std::unique_ptr<DynamicWorkCell> load(const std::string& text) {
    warnings_.clear();
    try {
      return rwsim::loaders::loadDynamicWorkCell(scene_.writeTop(text), &warnings_);
    } catch (const rw::common::LoadError& e) {
      ADD_FAILURE() << e.what();
      return nullptr;
    }
  }

  /// Warnings whose message contains `text`.
  std::vector<Diagnostic> warningsWith(const std::string& text) const {
    std::vector<Diagnostic> out;
    std::copy_if(warnings_.begin(), warnings_.end(), std::back_inserter(out),
                 [&](const Diagnostic& d) { return d.message.find(text) != std::string::npos; });
    return out;
  }

  const Body& body(const DynamicWorkCell& dwc, const std::string& name) const {
    const auto index = dwc.findBody(name);
    EXPECT_TRUE(index.valid()) << name;
    return dwc.bodies().at(index.valid() ? index.index() : 0);
  }

  SceneDir scene_;
  std::vector<Diagnostic> warnings_;
};

// One P and D pair in <PDParams> stands for every DOF (issue 20): the same gains as seven pairs.
TEST_F(DynamicWorkCellLoader, OnePdPairIsTheSameForEveryDof) {
  const auto one = load(SceneDir::dwc(sdhDevice() + sdhController(1)));
  ASSERT_TRUE(one);
  const auto seven = load(SceneDir::dwc(sdhDevice() + sdhController(7)));
  ASSERT_TRUE(seven);
  const auto* a = one->findController("GraspController");
  const auto* b = seven->findController("GraspController");
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(a->p, Eigen::VectorXd::Constant(7, 10.0));
  EXPECT_EQ(a->d, Eigen::VectorXd::Constant(7, 0.003));
  EXPECT_EQ(a->p, b->p);
  EXPECT_EQ(a->d, b->d);
}

TEST_F(DynamicWorkCellLoader, LoadsBodiesDevicesAndControllers) {
  const auto dwc = load(SceneDir::dwc(R"(<Gravity>0 0 -9.81</Gravity>
<FixedBody frame="Table"><MaterialID>Rubber</MaterialID></FixedBody>
<RigidBody frame="Object">
  <Mass>0.7</Mass><EstimateInertia/><Integrator>Euler</Integrator><ObjectID>soft</ObjectID>
  <Property name="LinearDamping" type="float">0.1</Property>
</RigidBody>
<KinematicBody frame="Ghost"><MaterialID>Plastic</MaterialID></KinematicBody>
)" + sdhDevice() + sdhController()));
  ASSERT_TRUE(dwc);
  EXPECT_TRUE(warnings_.empty()) << warnings_.front().format();
  EXPECT_VECTOR_NEAR(dwc->gravity(), Vector3D(0, 0, -9.81), 0.0);
  EXPECT_EQ(body(*dwc, "Table").kind, BodyKind::kFixed);
  EXPECT_EQ(body(*dwc, "Table").material, "Rubber");
  EXPECT_EQ(body(*dwc, "Table").objectType, "hard");
  EXPECT_EQ(body(*dwc, "Ghost").kind, BodyKind::kKinematic);

  const Body& object = body(*dwc, "Object");
  EXPECT_EQ(object.kind, BodyKind::kRigid);
  EXPECT_EQ(object.material, "Plastic");  // the default
  EXPECT_EQ(object.objectType, "soft");
  const auto& tree = dwc->workcell().frames();
  ASSERT_EQ(object.geometryFrames.size(), 2u);
  EXPECT_EQ(tree.frame(object.geometryFrames[1]).name(), "Handle");
  // Box 0.1 x 0.2 x 0.3 (0.006 m^3) at (0.01, 0, 0) and cube 0.1 (0.001 m^3) at (0, 0, 0.2).
  EXPECT_VECTOR_NEAR(object.mass.cog, Vector3D(0.006 * 0.01, 0, 0.001 * 0.2) / 0.007, 1e-15);
  const double rho = 0.7 / 0.007;
  const double zBody = object.mass.cog.z();
  const double zKnob = 0.2 - object.mass.cog.z();
  const double dxBody = 0.01 - object.mass.cog.x();
  const double dxKnob = object.mass.cog.x();
  const double iyy = rho * 0.006 * (0.01 + 0.09) / 12 +
                     rho * 0.006 * (dxBody * dxBody + zBody * zBody) + rho * 0.001 * 0.02 / 12 +
                     rho * 0.001 * (dxKnob * dxKnob + zKnob * zKnob);
  EXPECT_NEAR(object.mass.inertia(1, 1), iyy, 1e-14);
  EXPECT_DOUBLE_EQ(std::get<double>(object.properties.at("LinearDamping").value), 0.1);

  const auto device = dwc->findDevice("SchunkHand");
  ASSERT_TRUE(device.valid());
  const auto& hand = dwc->device(device);
  EXPECT_EQ(hand.forceLimits, std::vector<double>(8, 2.0));
  EXPECT_EQ(dwc->body(hand.baseBody).name, "SchunkHand.Base");
  for (std::size_t j = 0; j < 8; ++j) {
    const Body& link = dwc->body(hand.linkBodies[j]);
    EXPECT_EQ(link.frame, hand.device->joints()[j]);
    EXPECT_EQ(link.device, device);
    EXPECT_GT(link.mass.inertia.determinant(), 0.0);
  }
  ASSERT_NE(dwc->findController("GraspController"), nullptr);
  EXPECT_EQ(dwc->findController("GraspController")->p.size(), 7);
  EXPECT_EQ(dwc->fileName(), (scene_.path() / "top.dwc.xml").lexically_normal().string());
}

TEST_F(DynamicWorkCellLoader, GivenCogAndInertiaAreTakenAsWritten) {
  const auto dwc = load(SceneDir::dwc(R"(<RigidBody frame="Object">
  <Mass>2</Mass><Integrator>Euler</Integrator>
  <COG>0.1 0 0</COG><Inertia>2 0.1 0  0.1 3 0  0 0 4</Inertia>
</RigidBody>
<RigidBody frame="Ghost"><Mass>1</Mass><Integrator>Euler</Integrator><COG>0 0 0</COG><Inertia>1 2 3</Inertia></RigidBody>
)"));
  ASSERT_TRUE(dwc);
  const Body& object = body(*dwc, "Object");
  EXPECT_VECTOR_NEAR(object.mass.cog, Vector3D(0.1, 0, 0), 0.0);
  EXPECT_DOUBLE_EQ(object.mass.inertia(0, 1), 0.1);
  EXPECT_DOUBLE_EQ(object.mass.inertia(2, 2), 4.0);
  EXPECT_VECTOR_NEAR(Eigen::VectorXd(body(*dwc, "Ghost").mass.inertia.diagonal()),
                     Eigen::VectorXd(Vector3D(1, 2, 3)), 0.0);
}

TEST_F(DynamicWorkCellLoader, AGivenCogMovesTheEstimatedInertiaByTheParallelAxisTheorem) {
  const auto dwc = load(SceneDir::dwc(R"(<RigidBody frame="Object">
  <Mass>0.7</Mass><Integrator>Euler</Integrator><EstimateInertia/>
</RigidBody>
)"));
  const auto moved = load(SceneDir::dwc(R"(<RigidBody frame="Object">
  <Mass>0.7</Mass><Integrator>Euler</Integrator><EstimateInertia/><COG>0 0 0</COG>
</RigidBody>
)"));
  ASSERT_TRUE(dwc && moved);
  const auto& a = body(*dwc, "Object").mass;
  const auto& b = body(*moved, "Object").mass;
  EXPECT_VECTOR_NEAR(b.cog, Vector3D::Zero(), 0.0);
  const Vector3D d = -a.cog;
  const Eigen::Matrix3d shift =
      0.7 * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  EXPECT_TRUE(b.inertia.isApprox(a.inertia + shift, 1e-12));
}

TEST_F(DynamicWorkCellLoader, RobWorksLeniencyIsReportedAsWarnings) {
  const auto dwc = load(SceneDir::dwc(R"(<PhysicsEngine>
  <Property name="MaxIter" type="int">20</Property>
  <Property name="Eps" type="double">0.001</Property>
  <Property name="Gains" type="Q">1 2 3</Property>
  <Property name="StepMethod">WorldQuickStep</Property>
  <CollisionMargin>0.01</CollisionMargin><AutoDisable>False</AutoDisable>
</PhysicsEngine>
<MaterialData><Material id="Rubber"/></MaterialData>
<FrictionMap>
  <Pair first="Plastic" second="Steel"><FrictionData type="Coulomb"><Mu>0.1</Mu></FrictionData></Pair>
  <Pair first="Rubber" second="Plastic"><FrictionData type="Coulomb"><Mu>0.2</Mu></FrictionData></Pair>
</FrictionMap>
<RigidBody frame="Object"><Mass>1</Mass><EstimateInertia/></RigidBody>
<KinematicBody frame="Ghost"/>
<TactileArraySensor frame="Object"><Name>S</Sensor></TactileArraySensor>
<ContactModel type="Newton"/>
)"));
  ASSERT_TRUE(dwc);
  const auto& engine = dwc->engineProperties();
  EXPECT_EQ(engine.at("MaxIter"), "20");
  EXPECT_EQ(engine.at("Eps"), "0.001");
  EXPECT_EQ(engine.at("Gains"), "1 2 3");
  EXPECT_EQ(engine.at("StepMethod"), "WorldQuickStep");
  EXPECT_EQ(warningsWith("type \"double\" is rejected by RobWork").size(), 1u);
  EXPECT_EQ(warningsWith("declared twice").size(), 1u);
  EXPECT_EQ(warningsWith("unknown material \"Steel\"").size(), 1u);
  EXPECT_EQ(warningsWith("RobWork keeps the first").size(), 1u);
  EXPECT_DOUBLE_EQ(dwc->materials().mu("Plastic", "Rubber"), 0.7);
  EXPECT_EQ(warningsWith("missing <Integrator>").size(), 1u);
  EXPECT_EQ(warningsWith("requires a <MaterialID> in a KinematicBody").size(), 1u);
  EXPECT_EQ(warningsWith("not simulated by this project").size(), 1u);
  EXPECT_EQ(warningsWith("</Sensor> closes <Name>").size(), 1u);
  EXPECT_EQ(warningsWith("<ContactModel type=").size(), 0u);
  EXPECT_EQ(warningsWith("ignored (RobWork ignores it too)").size(), 1u);
  for (const Diagnostic& w : warnings_) {
    EXPECT_EQ(w.file, (scene_.path() / "top.dwc.xml").string());
    EXPECT_GT(w.line, 2);
  }
}

TEST_F(DynamicWorkCellLoader, ABodyWithoutVolumeGetsASmallSphereWithAWarning) {
  const auto dwc =
      load(SceneDir::dwc("<RigidBody frame=\"Ghost\"><Mass>2</Mass><Integrator>Euler</Integrator>"
                         "<EstimateInertia/></RigidBody>\n"));
  ASSERT_TRUE(dwc);
  ASSERT_EQ(warningsWith("radius 0.0001 m").size(), 1u);
  EXPECT_EQ(warningsWith("radius 0.0001 m")[0].line, 3);
  const double i = 0.4 * 2 * 1e-8;
  EXPECT_NEAR(body(*dwc, "Ghost").mass.inertia(0, 0), i, 1e-20);
}

TEST_F(DynamicWorkCellLoader, AssociatedFramesAddTheirGeometry) {
  const auto dwc =
      load(SceneDir::dwc("<RigidBody frame=\"Ghost\"><Mass>1</Mass><Integrator>Euler</Integrator>"
                         "<EstimateInertia/><Associate object=\"Table\"/></RigidBody>\n"));
  ASSERT_TRUE(dwc);
  const Body& ghost = body(*dwc, "Ghost");
  EXPECT_EQ(dwc->bodyOfFrame(dwc->workcell().findFrame("Table")), dwc->findBody("Ghost"));
  // The table top (1 x 1 x 0.1 at z -0.05) seen from Ghost at (1, 0, 0).
  EXPECT_VECTOR_NEAR(ghost.mass.cog, Vector3D(-1, 0, -0.05), 1e-12);
  EXPECT_TRUE(warningsWith("radius").empty());
}

TEST_F(DynamicWorkCellLoader, IncludesAreRelativeToTheTopLevelFileWithAFallback) {
  // sub/a.xml includes "sub/b.xml" (RobWork's rule: relative to the top-level folder) and
  // "c.xml", which exists only next to a.xml (found with a warning).
  writeFile(scene_.path() / "sub/a.xml", R"(<IncludeData>
  <Include file="sub/b.xml"/>
  <Include file="c.xml"/>
</IncludeData>)");
  writeFile(scene_.path() / "sub/b.xml", "<IncludeData><Gravity>0 0 -9.8</Gravity></IncludeData>");
  writeFile(scene_.path() / "sub/c.xml", "<IncludeData><FixedBody frame=\"Table\"/></IncludeData>");
  const auto dwc = load(SceneDir::dwc("<Include file=\"sub/a.xml\"/>\n"));
  ASSERT_TRUE(dwc);
  EXPECT_DOUBLE_EQ(dwc->gravity().z(), -9.8);
  EXPECT_TRUE(dwc->findBody("Table").valid());
  const auto fallback = warningsWith("relative to the including file");
  ASSERT_EQ(fallback.size(), 1u);
  EXPECT_EQ(fallback[0].line, 3);
  EXPECT_EQ(fallback[0].file, (scene_.path() / "sub/a.xml").string());
  ASSERT_EQ(fallback[0].includedFrom.size(), 1u);
  EXPECT_EQ(fallback[0].includedFrom[0], (scene_.path() / "top.dwc.xml").string() + ":3");
  EXPECT_EQ(warnings_.size(), 1u);
}

TEST_F(DynamicWorkCellLoader, IncludeRedirectsSwapTheHandInBothFiles) {
  // The scene includes the SDH (scene.wc.xml) and its dynamics (here); the redirects put the
  // PG70 in, from its own folder.
  const auto hands = visgrab::test::sourceDir() / "scenes/hands";
  writeFile(scene_.path() / "sdh_dynamics.xml",
            "<IncludeData>\n" + sdhDevice() + sdhController() + "</IncludeData>\n");
  // The PG70's links are of material Finger.
  std::string materials = visgrab::test::dwc::kMaterials;
  materials.replace(materials.find("<Material id=\"Rubber\"/>"), 0, "<Material id=\"Finger\"/>");
  writeFile(scene_.path() / "materials.xml", materials);
  const auto top = scene_.writeTop(SceneDir::dwc("<Include file=\"sdh_dynamics.xml\"/>\n"));
  const auto sdh = rwsim::loaders::loadDynamicWorkCell(top);
  EXPECT_TRUE(sdh->findDevice("SchunkHand").valid());

  rwsim::loaders::DynamicWorkCellLoadOptions options;
  options.includeRedirects[hands / "sdh/sdh.wc.xml"] = hands / "pg70/pg70.wc.xml";
  options.includeRedirects[scene_.path() / "sdh_dynamics.xml"] =
      hands / "pg70/pg70_dynamics.dwc.xml";
  const auto pg70 = rwsim::loaders::loadDynamicWorkCell(top, options);
  EXPECT_FALSE(pg70->findDevice("SchunkHand").valid());
  ASSERT_TRUE(pg70->findDevice("PG70").valid());
  EXPECT_NE(pg70->workcell().findDevice("PG70"), nullptr);
  EXPECT_EQ(pg70->workcell().findDevice("SchunkHand"), nullptr);
  EXPECT_TRUE(pg70->workcell().findFrame("Mount").valid());
}

// A device whose base is a plain frame (RobWork's Robotiq) is simulated with a kinematic base
// on the Movable frame that holds its base rigidly, named without the device's prefix (this
// project's extension); that body carries the base's geometry. A frame that does not hold the
// base is an error.
TEST_F(DynamicWorkCellLoader, AKinematicBaseMayBeTheMovableFrameHoldingTheDevicesBase) {
  writeFile(scene_.path() / "mounted.wc.xml", R"(<WorkCell name="Mounted">
  <Frame name="Other" refframe="WORLD" type="Movable"><RPY>0 0 0</RPY><Pos>1 0 0</Pos></Frame>
  <Frame name="Mount" refframe="WORLD" type="Movable"><RPY>0 0 0</RPY><Pos>0 0 0.3</Pos></Frame>
  <TreeDevice name="Jaw">
    <Frame name="Base"><RPY>0 0 0</RPY><Pos>0 0 0.02</Pos>
      <Drawable name="Housing"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.1" y="0.1" z="0.04"/></Drawable>
    </Frame>
    <Joint name="J" type="Prismatic"><RPY>0 0 0</RPY><Pos>0 0 0.05</Pos>
      <Drawable name="Finger"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.01" y="0.02" z="0.06"/></Drawable>
    </Joint>
    <PosLimit refjoint="J" min="0" max="0.04"/>
  </TreeDevice>
</WorkCell>
)");
  const auto dwcText = [](const std::string& base) {
    return "<DynamicWorkcell workcell=\"mounted.wc.xml\">\n"
           "  <Include file=\"materials.xml\"/>\n"
           "  <RigidDevice device=\"Jaw\">\n"
           "    <ForceLimit joint=\"J\">10</ForceLimit>\n"
           "    <KinematicBase frame=\"" +
           base +
           "\"><MaterialID>Plastic</MaterialID></KinematicBase>\n"
           "    <RigidJoint joint=\"J\"><Mass>0.1</Mass><EstimateInertia/></RigidJoint>\n"
           "  </RigidDevice>\n"
           "</DynamicWorkcell>\n";
  };
  const auto dwc = load(dwcText("Mount"));
  ASSERT_TRUE(dwc);
  const auto& device = dwc->device(dwc->findDevice("Jaw"));
  const Body& base = dwc->body(device.baseBody);
  EXPECT_EQ(base.kind, BodyKind::kKinematic);
  const auto& tree = dwc->workcell().frames();
  EXPECT_EQ(tree.frame(base.frame).name(), "Mount");
  EXPECT_NE(std::find(base.geometryFrames.begin(), base.geometryFrames.end(),
                      dwc->workcell().findFrame("Jaw.Base")),
            base.geometryFrames.end());

  try {
    rwsim::loaders::loadDynamicWorkCell(scene_.writeTop(dwcText("Other")));
    ADD_FAILURE() << "loaded";
  } catch (const rw::common::LoadError& e) {
    EXPECT_EQ(e.diagnostics().size(), 1u) << e.what();  // not also "unknown frame"
    EXPECT_EQ(e.diagnostics().front().line, 5) << e.what();
    EXPECT_NE(std::string(e.what()).find("frame \"Other\" is neither a frame of device \"Jaw\" "
                                         "nor a frame that holds its base \"Jaw.Base\" rigidly"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(DynamicWorkCellLoader, AnIncludeRedirectToAMissingFileIsAnErrorAtTheInclude) {
  const auto top = scene_.writeTop(SceneDir::dwc("<FixedBody frame=\"Table\"/>\n"));
  rwsim::loaders::DynamicWorkCellLoadOptions options;
  options.includeRedirects[scene_.path() / "materials.xml"] = scene_.path() / "gone.xml";
  try {
    rwsim::loaders::loadDynamicWorkCell(top, options);
    FAIL() << "no LoadError";
  } catch (const rw::common::LoadError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    const Diagnostic& d = e.diagnostics()[0];
    EXPECT_EQ(d.file, top.string());
    EXPECT_EQ(d.line, 2);
    EXPECT_NE(d.message.find("cannot read \"" + (scene_.path() / "gone.xml").string() +
                             "\" (redirected from \"" + (scene_.path() / "materials.xml").string() +
                             "\")"),
              std::string::npos)
        << d.message;
    EXPECT_NE(std::string(e.what()).find(top.string() + ":2:"), std::string::npos) << e.what();
  }
}

TEST_F(DynamicWorkCellLoader, LoadsFromAString) {
  std::vector<Diagnostic> warnings;
  const auto dwc =
      rwsim::loaders::loadDynamicWorkCellFromString(SceneDir::dwc("<FixedBody frame=\"Floor\"/>\n"),
                                                    scene_.path() / "virtual.dwc.xml", &warnings);
  ASSERT_TRUE(dwc);
  EXPECT_EQ(dwc->bodies().size(), 1u);
  EXPECT_TRUE(warnings.empty());
}

TEST_F(DynamicWorkCellLoader, RefBaseReusesABody) {
  const std::string device = sdhDevice("", "");
  std::string refDevice = device;
  const std::string kinematic =
      "<KinematicBase frame=\"Base\"><MaterialID>Plastic</MaterialID></KinematicBase>";
  refDevice.replace(refDevice.find(kinematic), kinematic.size(),
                    "<RefBase body=\"SchunkHand.Base\"/>");
  const auto dwc = load(SceneDir::dwc(
      "<KinematicBody frame=\"SchunkHand.Base\"><MaterialID>Rubber</MaterialID></KinematicBody>\n" +
      refDevice));
  ASSERT_TRUE(dwc);
  const auto& hand = dwc->devices().at(0);
  EXPECT_EQ(hand.baseBody, dwc->findBody("SchunkHand.Base"));
  EXPECT_EQ(dwc->body(hand.baseBody).material, "Rubber");
}

TEST_F(DynamicWorkCellLoader, CheckReportsWithoutThrowing) {
  const auto diagnostics = rwsim::loaders::checkDynamicWorkCell(
      scene_.writeTop(SceneDir::dwc("<RigidBody frame=\"Object\"><Mass>-1</Mass></RigidBody>\n")));
  ASSERT_FALSE(diagnostics.empty());
  EXPECT_TRUE(std::any_of(diagnostics.begin(), diagnostics.end(), [](const Diagnostic& d) {
    return d.severity == Diagnostic::Severity::kError;
  }));
  EXPECT_FALSE(rwsim::loaders::checkDynamicWorkCell(scene_.path() / "none.dwc.xml").empty());
}

// RobWorkSim's <Constraint>: type in any case, the transform (RPY in radians) in the parent's
// frame, one limit per free DOF; a device link may be a constraint's body; constrained bodies
// count as joint-connected (no contacts between them).
TEST_F(DynamicWorkCellLoader, ReadsConstraints) {
  const auto dwc = load(SceneDir::dwc(
      "<FixedBody frame=\"Table\"/>\n<RigidBody frame=\"Object\"><Integrator>Euler</Integrator>"
      "<Mass>0.5</Mass><EstimateInertia/></RigidBody>\n" +
      sdhDevice() + sdhController() +
      R"(<Constraint name="Hinge" type="revolute" parent="Table" child="Object">
  <Transform3D><Pos>0.1 0.2 0.3</Pos><RPY>1.5707963267948966 0 0</RPY></Transform3D>
  <Limits><Limit low="-0.5" high="1"/></Limits>
</Constraint>
<Constraint name="Grip" type="PrismaticUniversal" parent="SchunkHand.f1.Joint3" child="Object">
  <Limits><Limit high="0.01"/><Limit/><Limit low="-1" high="1"/></Limits>
</Constraint>
<Constraint name="Loose" type="FREE" parent="Object" child="SchunkHand.f2.Joint3"/>
)"));
  ASSERT_TRUE(dwc);
  ASSERT_EQ(dwc->constraints().size(), 3u);
  const auto* hinge = dwc->findConstraint("Hinge");
  ASSERT_NE(hinge, nullptr);
  EXPECT_EQ(hinge->type, rwsim::dynamics::ConstraintType::kRevolute);
  EXPECT_EQ(hinge->parent, dwc->findBody("Table"));
  EXPECT_EQ(hinge->child, dwc->findBody("Object"));
  EXPECT_TRUE(hinge->X_parent_constraint.translation().isApprox(Vector3D(0.1, 0.2, 0.3)));
  // RPY roll pi/2 (radians) about z: x -> y.
  EXPECT_TRUE(
      (hinge->X_parent_constraint.linear() * Vector3D::UnitX()).isApprox(Vector3D::UnitY(), 1e-12));
  ASSERT_EQ(hinge->limits.size(), 1u);
  EXPECT_EQ(hinge->limits[0].low, -0.5);
  EXPECT_EQ(hinge->limits[0].high, 1.0);
  const auto* grip = dwc->findConstraint("Grip");
  ASSERT_NE(grip, nullptr);
  EXPECT_EQ(grip->parent, dwc->findBody("SchunkHand.f1.Joint3"));
  ASSERT_EQ(grip->limits.size(), 3u);
  EXPECT_EQ(grip->limits[0].high, 0.01);
  EXPECT_TRUE(std::isinf(grip->limits[0].low));
  EXPECT_TRUE(std::isinf(grip->limits[1].high));
  EXPECT_TRUE(dwc->findConstraint("Loose")->X_parent_constraint.isApprox(
      rw::math::Transform3D::Identity()));
  const auto pairs = rwsim::dynamics::jointConnectedBodyPairs(*dwc);
  const auto has = [&](rwsim::dynamics::BodyId a, rwsim::dynamics::BodyId b) {
    return std::find(pairs.begin(), pairs.end(), std::make_pair(std::min(a, b), std::max(a, b))) !=
           pairs.end();
  };
  EXPECT_TRUE(has(hinge->parent, hinge->child));
  EXPECT_TRUE(has(grip->parent, grip->child));
  const auto* loose = dwc->findConstraint("Loose");
  EXPECT_FALSE(has(loose->parent, loose->child));  // a Free constraint joins nothing
  EXPECT_EQ(warningsWith("not simulated by this project").size(), 0u);
  EXPECT_EQ(warningsWith("without a <Spring> it has no effect").size(), 1u);
}

}  // namespace
