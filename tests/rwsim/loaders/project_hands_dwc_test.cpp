// The project's own hand dynamics (scenes/hands/*/*.dwc.xml) and material file
// (scenes/materials.xml) load, and a scene in another folder can use them as documented in
// scenes/hands/README.md.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cstdlib>
#include <string>
#include <vector>

#include "rwsim/dynamics/loop_closure.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::common::Diagnostic;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DynamicWorkCell;
using visgrab::test::sourceDir;

std::unique_ptr<DynamicWorkCell> loadHand(const std::filesystem::path& file) {
  std::vector<Diagnostic> warnings;
  try {
    auto dwc = rwsim::loaders::loadDynamicWorkCell(file, &warnings);
    for (const Diagnostic& w : warnings) ADD_FAILURE() << w.format();
    return dwc;
  } catch (const rw::common::LoadError& e) {
    ADD_FAILURE() << e.what();
    return nullptr;
  }
}

void expectProjectMaterials(const DynamicWorkCell& dwc) {
  const auto& m = dwc.materials();
  EXPECT_EQ(m.materials(), (std::vector<std::string>{"Finger", "Object", "Table"}));
  EXPECT_EQ(m.defaultMaterial(), "Object");
  EXPECT_DOUBLE_EQ(m.mu("Finger", "Object"), 0.6);
  EXPECT_DOUBLE_EQ(m.mu("Finger", "Finger"), 0.8);
  EXPECT_DOUBLE_EQ(m.mu("Table", "Object"), 0.4);
  EXPECT_DOUBLE_EQ(m.mu("Object", "Object"), 0.4);
  EXPECT_DOUBLE_EQ(m.mu("Finger", "Table"), 0.4);
  EXPECT_EQ(m.frictionPairCount(), 5u);
}

void expectHand(const DynamicWorkCell& dwc, const std::string& name,
                const std::vector<double>& forceLimits, int dof) {
  const auto index = dwc.findDevice(name);
  ASSERT_TRUE(index.valid());
  const auto& device = dwc.device(index);
  EXPECT_EQ(device.forceLimits, forceLimits);
  const auto& base = dwc.body(device.baseBody);
  EXPECT_EQ(base.name, name + ".Base");
  EXPECT_EQ(base.kind, BodyKind::kKinematic);
  EXPECT_EQ(base.material, "Finger");
  for (const auto link : device.linkBodies) {
    ASSERT_TRUE(link.valid());
    const auto& body = dwc.body(link);
    SCOPED_TRACE(body.name);
    EXPECT_EQ(body.kind, BodyKind::kRigid);
    EXPECT_DOUBLE_EQ(body.mass.mass, 0.1);
    EXPECT_EQ(body.material, "Finger");
    EXPECT_GT(
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(body.mass.inertia).eigenvalues().minCoeff(),
        0.0);
  }
  const auto* pd = dwc.findController("GraspController");
  ASSERT_NE(pd, nullptr);
  EXPECT_EQ(pd->device, index);
  EXPECT_VECTOR_NEAR(pd->p, Eigen::VectorXd::Constant(dof, 10.0), 0.0);
  EXPECT_VECTOR_NEAR(pd->d, Eigen::VectorXd::Constant(dof, 0.003), 0.0);
}

TEST(ProjectHands, SdhDynamicsLoad) {
  const auto dwc = loadHand(sourceDir() / "scenes/hands/sdh/sdh.dwc.xml");
  ASSERT_TRUE(dwc);
  expectProjectMaterials(*dwc);
  expectHand(*dwc, "SchunkHand", {2.1, 1.4, 2.1, 2.1, 1.4, 2.1, 2.1, 1.4}, 7);
  EXPECT_DOUBLE_EQ(dwc->gravity().z(), -9.81);
  // The thumb's base block is rigid with the palm: it belongs to the base body.
  const auto base = dwc->findBody("SchunkHand.Base");
  EXPECT_EQ(dwc->bodyOfFrame(dwc->workcell().findFrame("SchunkHand.F1Base")), base);
  EXPECT_EQ(dwc->bodyOfFrame(dwc->workcell().findFrame("SchunkHand.F2Joint1Rev")),
            dwc->findBody("SchunkHand.F2Joint1"));
}

TEST(ProjectHands, Pg70DynamicsLoad) {
  const auto dwc = loadHand(sourceDir() / "scenes/hands/pg70/pg70.dwc.xml");
  ASSERT_TRUE(dwc);
  expectProjectMaterials(*dwc);
  expectHand(*dwc, "PG70", {40.0, 50.0}, 1);
  // A jaw box 0.03 x 0.07 x 0.015 at (0, 0.035, -+0.002) in its joint frame.
  const auto& jaw = dwc->body(dwc->findBody("PG70.RightFinger"));
  EXPECT_VECTOR_NEAR(jaw.mass.cog, rw::math::Vector3D(0, 0.035, -0.002), 1e-12);
  EXPECT_NEAR(jaw.mass.inertia(2, 2), 0.1 / 12 * (0.03 * 0.03 + 0.07 * 0.07), 1e-15);
}

TEST(ProjectHands, ASceneInAnotherFolderIncludesTheHandDynamicsAndTheMaterials) {
  // As scenes/hands/README.md says: the scene's own dwc includes the material file and the
  // hand's *_dynamics.dwc.xml, with paths relative to the scene's folder. Here the scene is in
  // a temporary folder, so the paths are absolute.
  visgrab::test::TempDir dir;
  const std::string scenes = (sourceDir() / "scenes").string();
  visgrab::test::writeFile(dir.path() / "scene.wc.xml", R"(<WorkCell name="Grasp">
  <Frame name="Table" refframe="WORLD">
    <RPY>0 0 0</RPY><Pos>0 0 0</Pos>
    <Drawable name="Top"><RPY>0 0 0</RPY><Pos>0 0 -0.02</Pos><Box x="1" y="1" z="0.04"/></Drawable>
  </Frame>
  <Frame name="Cup" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 0.05</Pos>
    <Drawable name="Geo"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Cylinder radius="0.04" z="0.1"/></Drawable>
  </Frame>
  <Frame name="HandMount" refframe="WORLD"><RPY>0 0 0</RPY><Pos>0 0 0.3</Pos></Frame>
  <Include file=")" + scenes + R"(/hands/pg70/pg70.wc.xml"/>
</WorkCell>)");
  const auto dwc = loadHand(visgrab::test::writeFile(dir.path() / "scene.dwc.xml",
                                                     R"(<DynamicWorkcell workcell="scene.wc.xml">
  <Gravity>0 0 -9.81</Gravity>
  <Include file=")" + scenes + R"(/materials.xml"/>
  <FixedBody frame="Table"><MaterialID>Table</MaterialID></FixedBody>
  <RigidBody frame="Cup"><Mass>0.2</Mass><EstimateInertia/><Integrator>Euler</Integrator></RigidBody>
  <Include file=")" + scenes + R"(/hands/pg70/pg70_dynamics.dwc.xml"/>
</DynamicWorkcell>)"));
  ASSERT_TRUE(dwc);
  const auto& cup = dwc->body(dwc->findBody("Cup"));
  EXPECT_EQ(cup.material, "Object");
  EXPECT_DOUBLE_EQ(dwc->materials().mu(cup.material, "Finger"), 0.6);
  expectHand(*dwc, "PG70", {40.0, 50.0}, 1);
}

}  // namespace

namespace {

// RobWork's Robotiq model as a hand (scenes/hands/robwork-robotiq, RW_COMPAT_DATA): the
// kinematic base is the Movable mount holding RobWork's plain Base (and carries its housing), a
// body for each of the eight links, none for the two LinkConnection joints, so the two
// junctions are closed by hinges there; 0.22 kg of links; one PD pair per DOF. Without the
// variable the hand does not load, and the message names it.
TEST(ProjectHands, RobWorksRobotiqDynamicsLoad) {
  REQUIRE_COMPAT_DATA(data);
  const auto file = sourceDir() / "scenes/hands/robwork-robotiq/robwork-robotiq.dwc.xml";
  std::vector<Diagnostic> warnings;
  const auto dwc = rwsim::loaders::loadDynamicWorkCell(file, &warnings);
  for (const Diagnostic& w : warnings) {
    // RobWork's own collision setup file: its two attributes are RobWork's, not used here.
    EXPECT_NE(w.message.find("UseIncludeAll and UseExcludeStaticPairs"), std::string::npos)
        << w.format();
  }
  expectProjectMaterials(*dwc);
  const auto index = dwc->findDevice("RobotiqFingerControl");
  ASSERT_TRUE(index.valid());
  const auto& device = dwc->device(index);
  const auto& base = dwc->body(device.baseBody);
  EXPECT_EQ(base.kind, BodyKind::kKinematic);
  EXPECT_EQ(dwc->workcell().frames().frame(base.frame).name(), "RobotiqMount");
  EXPECT_EQ(dwc->bodyOfFrame(dwc->workcell().findFrame("RobotiqFingerControl.Base")),
            device.baseBody);
  int links = 0;
  double mass = 0.0;
  for (const auto link : device.linkBodies) {
    if (!link.valid()) continue;  // LinkConnection
    ++links;
    mass += dwc->body(link).mass.mass;
  }
  EXPECT_EQ(links, 8);
  EXPECT_NEAR(mass, 0.22, 1e-12);
  EXPECT_EQ(rwsim::dynamics::loopClosures(*dwc, device).size(), 2u);
  const auto* pd = dwc->findController("GraspController");
  ASSERT_NE(pd, nullptr);
  EXPECT_VECTOR_NEAR(pd->p, Eigen::VectorXd::Constant(3, 5.0), 0.0);

  const std::string saved = data.string();
  ASSERT_EQ(unsetenv("RW_COMPAT_DATA"), 0);
  try {
    rwsim::loaders::loadDynamicWorkCell(file);
    ADD_FAILURE() << "loaded without RW_COMPAT_DATA";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("the environment variable RW_COMPAT_DATA is not set"),
              std::string::npos)
        << e.what();
  }
  ASSERT_EQ(setenv("RW_COMPAT_DATA", saved.c_str(), 1), 0);
}

}  // namespace
