// Loads RobWorkSim's own dynamic workcell files (RW_COMPAT_DATA) and checks them against the
// numbers of the RobWork reference (§2, §6.1, §6.3).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <string>
#include <vector>

#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::common::Diagnostic;
using rwsim::dynamics::Body;
using rwsim::dynamics::BodyId;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DynamicWorkCell;

std::unique_ptr<DynamicWorkCell> loadCompat(const std::filesystem::path& file,
                                            std::vector<Diagnostic>* warnings = nullptr) {
  try {
    return rwsim::loaders::loadDynamicWorkCell(file, warnings);
  } catch (const rw::common::LoadError& e) {
    ADD_FAILURE() << e.what();
    return nullptr;
  }
}

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Lines of the closing-tag repairs reported in files whose name ends with `file`.
std::vector<int> repairLines(const std::vector<Diagnostic>& warnings, const std::string& file) {
  std::vector<int> lines;
  for (const Diagnostic& w : warnings) {
    if (w.message.find("as RobWork does") != std::string::npos &&
        w.message.find("closes <") != std::string::npos && endsWith(w.file, file)) {
      lines.push_back(w.line);
    }
  }
  return lines;
}

std::size_t repairCount(const std::vector<Diagnostic>& warnings) {
  return static_cast<std::size_t>(std::count_if(warnings.begin(), warnings.end(), [](auto& w) {
    return w.message.find("closes <") != std::string::npos;
  }));
}

const Body& bodyNamed(const DynamicWorkCell& dwc, const std::string& name) {
  const auto index = dwc.findBody(name);
  EXPECT_TRUE(index.valid()) << "no body " << name;
  return dwc.bodies().at(index.valid() ? index.index() : 0);
}

/// Expects a mass, a COG and a symmetric positive definite inertia about it.
void expectRigidLink(const Body& body, double mass, const rw::math::Vector3D& cog,
                     const std::string& material) {
  SCOPED_TRACE(body.name);
  EXPECT_EQ(body.kind, BodyKind::kRigid);
  EXPECT_DOUBLE_EQ(body.mass.mass, mass);
  EXPECT_VECTOR_NEAR(body.mass.cog, cog, 1e-12);
  EXPECT_EQ(body.material, material);
  EXPECT_TRUE(body.mass.inertia.isApprox(body.mass.inertia.transpose()));
  EXPECT_GT(
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(body.mass.inertia).eigenvalues().minCoeff(),
      0.0);
}

TEST(DynamicWorkCellCompat, SdhTestSceneLoadsWithRepairedClosingTags) {
  REQUIRE_COMPAT_DATA(data);
  std::vector<Diagnostic> warnings;
  const auto dwc = loadCompat(data / "devices/SDH2/test_scene.dwc.xml", &warnings);
  ASSERT_TRUE(dwc);
  // Two </RigidBody> closing a <RigidJoint> and </PDParam> closing <PDParams>.
  EXPECT_EQ(repairLines(warnings, "SDH2/SchunkHandTactile0.dwc.xml"),
            (std::vector<int>{39, 67, 95}));
  EXPECT_EQ(repairCount(warnings), 3u);
  const auto repair =
      std::find_if(warnings.begin(), warnings.end(), [](auto& w) { return w.line == 39; });
  ASSERT_NE(repair, warnings.end());
  EXPECT_EQ(repair->message,
            "</RigidBody> closes <RigidJoint>; read as </RigidJoint>, as RobWork does");
  EXPECT_EQ(repair->column, 2);
  ASSERT_EQ(repair->includedFrom.size(), 1u);
  EXPECT_TRUE(endsWith(repair->includedFrom[0], "SDH2/test_scene.dwc.xml:7"));

  EXPECT_VECTOR_NEAR(dwc->gravity(), rw::math::Vector3D(0, 0, -9.8), 0.0);
  const auto& materials = dwc->materials();
  EXPECT_EQ(materials.materials().size(), 44u);  // 45 declarations, Bronze twice
  EXPECT_EQ(materials.defaultMaterial(), "Plastic");
  EXPECT_DOUBLE_EQ(materials.mu("Plastic", "Rubber"), 0.7);
  EXPECT_DOUBLE_EQ(materials.mu("Rubber", "Plastic"), 0.7);
  EXPECT_DOUBLE_EQ(materials.mu("Aluminum", "Aluminum"), 1.05);      // Mu, not Mud
  EXPECT_DOUBLE_EQ(materials.mu("BrakeMaterial", "CastIron"), 0.4);  // the first of two entries
  EXPECT_DOUBLE_EQ(materials.mu("Glass", "Rubber"), 0.4);            // not in the map
  EXPECT_EQ(materials.frictionPairCount(), 49u);  // 50 active entries, one pair twice
  EXPECT_EQ(materials.defaultObjectType(), "hardObj");
  EXPECT_DOUBLE_EQ(materials.restitution("softObj", "hardObj"), 0.0);

  const auto deviceIndex = dwc->findDevice("SchunkHand");
  ASSERT_TRUE(deviceIndex.valid());
  const auto& device = dwc->device(deviceIndex);
  const Body& base = dwc->body(device.baseBody);
  EXPECT_EQ(base.name, "SchunkHand.Base");
  EXPECT_EQ(base.kind, BodyKind::kKinematic);
  EXPECT_EQ(base.material, "Plastic");
  ASSERT_EQ(device.linkBodies.size(), 8u);
  EXPECT_TRUE(std::none_of(device.linkBodies.begin(), device.linkBodies.end(),
                           [](BodyId b) { return !b.valid(); }));
  EXPECT_EQ(device.forceLimits, (std::vector<double>{2.1, 1.4, 2.1, 2.1, 1.4, 2.1, 2.1, 1.4}));

  const rw::math::Vector3D proximal(-3.4639e-5, 0.0440533, 0.000589354);
  const rw::math::Vector3D distal(-0.000216234, 0.0308393, 0.0014567);
  const rw::math::Vector3D spread(1.28577e-6, -0.00291929, -0.00562509);
  for (const std::string f : {"f1", "f2", "f3"}) {
    expectRigidLink(bodyNamed(*dwc, "SchunkHand." + f + ".Joint2"), 0.1, proximal, "Plastic");
    expectRigidLink(bodyNamed(*dwc, "SchunkHand." + f + ".Joint3"), 0.1, distal, "Rubber");
  }
  expectRigidLink(bodyNamed(*dwc, "SchunkHand.F2Joint1"), 0.1, spread, "Plastic");
  expectRigidLink(bodyNamed(*dwc, "SchunkHand.F3Joint1"), 0.1, spread, "Plastic");
  // The spread link carries its fixed "Rev" frame.
  const Body& f2 = bodyNamed(*dwc, "SchunkHand.F2Joint1");
  EXPECT_EQ(dwc->bodyOfFrame(dwc->workcell().findFrame("SchunkHand.F2Joint1Rev")),
            dwc->findBody(f2.name));

  const auto* controller = dwc->findController("GraspController");
  ASSERT_NE(controller, nullptr);
  EXPECT_EQ(controller->device, deviceIndex);
  EXPECT_EQ(controller->type, "Position");
  EXPECT_DOUBLE_EQ(controller->timeStep, 0.01);
  EXPECT_VECTOR_NEAR(controller->p, Eigen::VectorXd::Constant(7, 10.0), 0.0);
  EXPECT_VECTOR_NEAR(controller->d, Eigen::VectorXd::Constant(7, 0.003), 0.0);
}

TEST(DynamicWorkCellCompat, Pg70TestSceneLoads) {
  REQUIRE_COMPAT_DATA(data);
  std::vector<Diagnostic> warnings;
  const auto dwc = loadCompat(data / "devices/PG70/test_scene.dwc.xml", &warnings);
  ASSERT_TRUE(dwc);
  EXPECT_EQ(repairLines(warnings, "PG70/PG70.dwc.xml"), (std::vector<int>{24, 29}));
  const auto deviceIndex = dwc->findDevice("PG70");
  ASSERT_TRUE(deviceIndex.valid());
  const auto& device = dwc->device(deviceIndex);
  EXPECT_EQ(device.forceLimits, (std::vector<double>{40.0, 50.0}));
  EXPECT_EQ(dwc->body(device.baseBody).kind, BodyKind::kKinematic);
  for (const char* link : {"PG70.RightFinger", "PG70.LeftFinger"}) {
    const Body& body = bodyNamed(*dwc, link);
    EXPECT_DOUBLE_EQ(body.mass.mass, 0.1);
    EXPECT_EQ(body.material, "Plastic");
  }
  const auto* controller = dwc->findController("GraspController");
  ASSERT_NE(controller, nullptr);
  EXPECT_VECTOR_NEAR(controller->p, Eigen::VectorXd::Constant(1, 10.0), 0.0);
  EXPECT_VECTOR_NEAR(controller->d, Eigen::VectorXd::Constant(1, 0.003), 0.0);
}

TEST(DynamicWorkCellCompat, Pg70BoxSceneHasAnalyticBoxInertia) {
  REQUIRE_COMPAT_DATA(data);
  const auto dwc = loadCompat(data / "scene/grasping/pg70_box.dwc.xml");
  ASSERT_TRUE(dwc);
  const Body& floor = bodyNamed(*dwc, "Floor");
  EXPECT_EQ(floor.kind, BodyKind::kFixed);
  EXPECT_EQ(floor.material, "Plastic");
  const Body& object = bodyNamed(*dwc, "object");
  EXPECT_EQ(object.kind, BodyKind::kRigid);
  EXPECT_DOUBLE_EQ(object.mass.mass, 0.1);
  EXPECT_VECTOR_NEAR(object.mass.cog, rw::math::Vector3D::Zero(), 1e-12);
  // Box 0.06 x 0.06 x 0.1 about its centre: m/12 (b^2 + c^2) = 0.1/12 * (0.0036 + 0.01) etc.
  const Eigen::Vector3d diagonal(0.1 / 12 * 0.0136, 0.1 / 12 * 0.0136, 0.1 / 12 * 0.0072);
  EXPECT_VECTOR_NEAR(object.mass.inertia.diagonal(), diagonal, 1e-15);
  EXPECT_NEAR(object.mass.inertia(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(diagonal.x(), 1.1333333e-4, 1e-10);
  EXPECT_NEAR(diagonal.z(), 6.0e-5, 1e-12);
  EXPECT_TRUE(dwc->findDevice("PG70").valid());
  EXPECT_EQ(bodyNamed(*dwc, "PG70.Base").kind, BodyKind::kKinematic);
}

TEST(DynamicWorkCellCompat, TactileSdhWarnsAboutSensorsItDoesNotSimulate) {
  REQUIRE_COMPAT_DATA(data);
  const std::string scene = R"(<DynamicWorkcell workcell="test_scene.wc.xml">
  <Include file="../../scene/DynamicMaterialDataBase.xml"/>
  <Include file="SchunkHandTactile6.dwc.xml"/>
</DynamicWorkcell>)";
  std::vector<Diagnostic> warnings;
  std::unique_ptr<DynamicWorkCell> dwc;
  try {
    dwc = rwsim::loaders::loadDynamicWorkCellFromString(
        scene, data / "devices/SDH2/tactile6.dwc.xml", &warnings);
  } catch (const rw::common::LoadError& e) {
    FAIL() << e.what();
  }
  ASSERT_TRUE(dwc);
  const auto sensors = std::count_if(warnings.begin(), warnings.end(), [](auto& w) {
    return w.message.find("<TactileArraySensor") == 0 &&
           w.message.find("not simulated by this project") != std::string::npos;
  });
  EXPECT_EQ(sensors, 6);
  // <Name>...</Sensor> six times, plus the two </RigidBody>.
  EXPECT_EQ(repairLines(warnings, "SchunkHandTactile6.dwc.xml"),
            (std::vector<int>{47, 75, 93, 114, 135, 157, 179, 200}));
  EXPECT_EQ(dwc->devices().size(), 1u);
}

}  // namespace
