// Loads RobWork's own workcell files (RW_COMPAT_DATA) and checks them against the numbers of
// the RobWork reference (§1, §6.1, §6.3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::kinematics::FKTable;
using rw::kinematics::FrameId;
using rw::kinematics::FrameType;
using rw::models::Device;
using rw::models::WorkCell;

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

std::vector<std::string> namesOf(const WorkCell& wc, const std::vector<FrameId>& ids) {
  std::vector<std::string> names;
  for (const FrameId id : ids) names.push_back(wc.frames().frame(id).name());
  return names;
}

const rw::kinematics::Frame& frameNamed(const WorkCell& wc, const std::string& name) {
  const FrameId id = wc.findFrame(name);
  EXPECT_TRUE(id.valid()) << "no frame " << name;
  return wc.frames().frame(id.valid() ? id : rw::kinematics::FrameTree::kWorld);
}

bool hasPair(const rw::models::CollisionSetup& setup, const std::string& a, const std::string& b) {
  return std::any_of(setup.excludePairs.begin(), setup.excludePairs.end(), [&](const auto& p) {
    return (p.first == a && p.second == b) || (p.first == b && p.second == a);
  });
}

bool hasGeometryNamed(const std::vector<rw::models::GeometryInstance>& list,
                      const std::string& name) {
  return std::any_of(list.begin(), list.end(), [&](const auto& g) { return g.name == name; });
}

std::unique_ptr<WorkCell> loadCompat(const std::filesystem::path& file,
                                     std::vector<rw::common::Diagnostic>* warnings = nullptr) {
  try {
    return rw::loaders::loadWorkCell(file, warnings);
  } catch (const rw::common::LoadError& e) {
    ADD_FAILURE() << e.what();
    return nullptr;
  }
}

void checkSchunkHand(const WorkCell& wc) {
  ASSERT_EQ(wc.devices().size(), 1u);
  const Device& hand = *wc.devices().front();
  EXPECT_EQ(hand.name(), "SchunkHand");
  EXPECT_EQ(hand.kind(), Device::Kind::kTree);
  EXPECT_EQ(hand.dof(), 7);
  const std::vector<std::string> active = {
      "SchunkHand.f1.Joint2", "SchunkHand.f1.Joint3", "SchunkHand.F2Joint1", "SchunkHand.f2.Joint2",
      "SchunkHand.f2.Joint3", "SchunkHand.f3.Joint2", "SchunkHand.f3.Joint3"};
  EXPECT_EQ(namesOf(wc, hand.activeJoints()), active);
  std::vector<std::string> all = active;
  all.insert(all.begin() + 5, "SchunkHand.F3Joint1");
  EXPECT_EQ(namesOf(wc, hand.joints()), all);
  EXPECT_EQ(
      namesOf(wc, hand.ends()),
      (std::vector<std::string>{"SchunkHand.f1.TCP", "SchunkHand.f2.TCP", "SchunkHand.f3.TCP"}));

  const auto& spread3 = frameNamed(wc, "SchunkHand.F3Joint1");
  ASSERT_TRUE(spread3.isDependent());
  EXPECT_EQ(spread3.dependency()->owner, wc.findFrame("SchunkHand.F2Joint1"));
  EXPECT_DOUBLE_EQ(spread3.dependency()->gain, -1.0);
  EXPECT_DOUBLE_EQ(spread3.dependency()->offset, 0.0);
  // Reference §1.9: device-level limits of a dependent joint stay unconverted.
  EXPECT_DOUBLE_EQ(spread3.limits().lower, -90.0);
  EXPECT_DOUBLE_EQ(spread3.limits().upper, 90.0);

  Eigen::VectorXd lower(7), upper(7), velocity(7), acceleration(7);
  lower << -90, -90, 0, -90, -90, -90, -90;
  upper << 90, 90, 90, 90, 90, 90, 90;
  velocity << 100, 100, 28, 100, 100, 100, 100;
  acceleration << 1000, 1000, 100, 1000, 1000, 1000, 1000;
  EXPECT_VECTOR_NEAR(hand.lowerLimits(), lower * kDeg, 1e-12);
  EXPECT_VECTOR_NEAR(hand.upperLimits(), upper * kDeg, 1e-12);
  EXPECT_VECTOR_NEAR(hand.velocityLimits(), velocity * kDeg, 1e-12);
  EXPECT_VECTOR_NEAR(hand.accelerationLimits(), acceleration * kDeg, 1e-12);
  EXPECT_NEAR(hand.upperLimits()[2], kPi / 2, 1e-12);
  EXPECT_NEAR(hand.velocityLimits()[0], 100 * kPi / 180, 1e-12);

  ASSERT_EQ(hand.configurations().count("Home"), 1u);
  EXPECT_VECTOR_NEAR(hand.configurations().at("Home"), Eigen::VectorXd::Zero(7), 0.0);
  EXPECT_EQ(frameNamed(wc, "SchunkHand.Base").type(), FrameType::kMovable);
  EXPECT_TRUE(frameNamed(wc, "SchunkHand.f1.TCP").isEndEffector());

  // The old-format CollisionSetup file, scoped with "SchunkHand.".
  const auto& setup = wc.collisionSetup();
  EXPECT_EQ(setup.excludePairs.size(), 18u);
  for (const auto& [a, b] : setup.excludePairs) {
    EXPECT_EQ(a.rfind("SchunkHand.", 0), 0u) << a;
    EXPECT_EQ(b.rfind("SchunkHand.", 0), 0u) << b;
    EXPECT_TRUE(wc.findFrame(a).valid()) << a;
    EXPECT_TRUE(wc.findFrame(b).valid()) << b;
  }
  EXPECT_TRUE(hasPair(setup, "SchunkHand.Base", "SchunkHand.F1Base"));
  EXPECT_TRUE(hasPair(setup, "SchunkHand.F2Joint1Rev", "SchunkHand.F3Joint1"));
  EXPECT_TRUE(hasPair(setup, "SchunkHand.f3.Joint2", "SchunkHand.f3.Joint3"));
  EXPECT_FALSE(setup.excludeStaticPairs);
  const auto& proximity = wc.proximitySetup();
  EXPECT_TRUE(proximity.useIncludeAll);
  EXPECT_FALSE(proximity.useExcludeStaticPairs);
  ASSERT_EQ(proximity.rules.size(), 18u);
  EXPECT_FALSE(proximity.rules.front().include);
  EXPECT_EQ(proximity.rules.front().patternA, "SchunkHand.Base");
  EXPECT_EQ(proximity.rules.front().patternB, "SchunkHand.F1Base");

  // F1BaseGeo has colmodel="Disabled": drawn, never collided.
  const auto* f1Base = wc.findObject(wc.findFrame("SchunkHand.F1Base"));
  ASSERT_NE(f1Base, nullptr);
  EXPECT_TRUE(hasGeometryNamed(f1Base->visual, "F1BaseGeo"));
  EXPECT_FALSE(hasGeometryNamed(f1Base->collision, "F1BaseGeo"));
  const auto* base = wc.findObject(wc.findFrame("SchunkHand.Base"));
  ASSERT_NE(base, nullptr);
  EXPECT_TRUE(hasGeometryNamed(base->collision, "schunkFlance"));
  EXPECT_TRUE(hasGeometryNamed(base->collision, "BaseGeo"));
  const auto* tip = wc.findObject(wc.findFrame("SchunkHand.f2.Joint3"));
  ASSERT_NE(tip, nullptr);
  ASSERT_EQ(tip->collision.size(), 1u);
  EXPECT_EQ(tip->collision.front().name, "Joint3Geo");
  EXPECT_EQ(tip->collision.front().geometry->type(), rw::geometry::GeometryType::kMesh);
  // The three fingers share one mesh object (read once per load).
  const auto* tip1 = wc.findObject(wc.findFrame("SchunkHand.f1.Joint3"));
  ASSERT_NE(tip1, nullptr);
  EXPECT_EQ(tip1->collision.front().geometry, tip->collision.front().geometry);
}

void checkSchunkHandKinematics(const WorkCell& wc) {
  const auto state = wc.defaultState();
  const FKTable fk(wc.frames(), state);
  auto world = [&](const std::string& name) -> Eigen::Vector3d {
    return fk.worldTransform(wc.findFrame(name)).translation();
  };
  // Reference §6.1, derived forward kinematics at q = 0 (base at world z 0.056).
  EXPECT_VECTOR_NEAR(world("SchunkHand.Base"), Eigen::Vector3d(0, 0, 0.056), 1e-12);
  EXPECT_VECTOR_NEAR(world("SchunkHand.f1.Joint2"), Eigen::Vector3d(0.0381, 0, 0.0985), 1e-4);
  EXPECT_VECTOR_NEAR(world("SchunkHand.f2.Joint2"), Eigen::Vector3d(-0.0191, 0.0330, 0.0985), 1e-4);
  EXPECT_VECTOR_NEAR(world("SchunkHand.f3.Joint2"), Eigen::Vector3d(-0.0191, -0.0330, 0.0985),
                     1e-4);
  EXPECT_VECTOR_NEAR(world("SchunkHand.f1.Joint3"), Eigen::Vector3d(0.0381, 0, 0.1850), 1e-4);
  EXPECT_VECTOR_NEAR(world("SchunkHand.f1.TCP"), Eigen::Vector3d(0.0281, 0, 0.2350), 1e-4);
  EXPECT_VECTOR_NEAR(world("SchunkHand.f2.TCP"), Eigen::Vector3d(-0.0091, 0.0330, 0.2350), 1e-4);
  EXPECT_VECTOR_NEAR(world("SchunkHand.f3.TCP"), Eigen::Vector3d(-0.0091, -0.0330, 0.2350), 1e-4);
}

TEST(WorkCellLoaderCompat, SchunkHandTestScene) {
  REQUIRE_COMPAT_DATA(data);
  std::vector<rw::common::Diagnostic> warnings;
  const auto wc = loadCompat(data / "devices/SDH2/test_scene.wc.xml", &warnings);
  ASSERT_NE(wc, nullptr);
  EXPECT_TRUE(warnings.empty()) << warnings.front().format();
  EXPECT_EQ(wc->name(), "SDHTestScene");
  EXPECT_TRUE(std::filesystem::path(wc->fileName()).is_absolute());
  EXPECT_EQ(std::filesystem::path(wc->fileName()).filename(), "test_scene.wc.xml");
  checkSchunkHand(*wc);
  checkSchunkHandKinematics(*wc);
  // No workcell frame precedes the device: its base hangs on WORLD.
  EXPECT_EQ(frameNamed(*wc, "SchunkHand.Base").parent(), rw::kinematics::FrameTree::kWorld);
}

TEST(WorkCellLoaderCompat, SchunkHandBareDeviceFile) {
  REQUIRE_COMPAT_DATA(data);
  const auto wc = loadCompat(data / "devices/SDH2/SchunkHand.wc.xml");
  ASSERT_NE(wc, nullptr);
  EXPECT_EQ(wc->name(), "");
  checkSchunkHand(*wc);
  checkSchunkHandKinematics(*wc);
}

TEST(WorkCellLoaderCompat, SchunkHandSpreadMovesFingersTwoAndThreeOppositely) {
  REQUIRE_COMPAT_DATA(data);
  const auto wc = loadCompat(data / "devices/SDH2/test_scene.wc.xml");
  ASSERT_NE(wc, nullptr);
  const Device& hand = *wc->devices().front();
  auto state = wc->defaultState();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(7);
  q[2] = 0.3;
  hand.setQ(q, state);
  const auto& f3 = frameNamed(*wc, "SchunkHand.F3Joint1");
  EXPECT_DOUBLE_EQ(f3.jointValue(state), -0.3);
}

void checkPg70(const WorkCell& wc) {
  const Device* pg70 = wc.findDevice("PG70");
  ASSERT_NE(pg70, nullptr);
  EXPECT_EQ(pg70->dof(), 1);
  EXPECT_EQ(namesOf(wc, pg70->activeJoints()), (std::vector<std::string>{"PG70.RightFinger"}));
  EXPECT_EQ(namesOf(wc, pg70->joints()),
            (std::vector<std::string>{"PG70.RightFinger", "PG70.LeftFinger"}));
  const auto& left = frameNamed(wc, "PG70.LeftFinger");
  ASSERT_TRUE(left.isDependent());
  EXPECT_EQ(left.type(), FrameType::kPrismatic);
  EXPECT_DOUBLE_EQ(left.dependency()->gain, -1.0);
  EXPECT_EQ(left.dependency()->owner, wc.findFrame("PG70.RightFinger"));
  EXPECT_VECTOR_NEAR(pg70->lowerLimits(), Eigen::VectorXd::Zero(1), 0.0);
  EXPECT_VECTOR_NEAR(pg70->upperLimits(), Eigen::VectorXd::Constant(1, 0.035), 1e-15);
  EXPECT_VECTOR_NEAR(pg70->velocityLimits(), Eigen::VectorXd::Constant(1, 0.06), 1e-15);
  const auto& tcp = frameNamed(wc, "PG70.TCPPG70");
  ASSERT_EQ(tcp.properties().count("minJawWidth"), 1u);
  ASSERT_EQ(tcp.properties().count("maxJawWidth"), 1u);
  EXPECT_EQ(std::get<double>(tcp.properties().at("minJawWidth").value), 0.01);
  EXPECT_EQ(std::get<double>(tcp.properties().at("maxJawWidth").value), 0.09);
  EXPECT_EQ(wc.collisionSetup().excludePairs.size(), 3u);
  EXPECT_TRUE(hasPair(wc.collisionSetup(), "PG70.LeftFinger", "PG70.RightFinger"));
  const auto* right = wc.findObject(wc.findFrame("PG70.RightFinger"));
  ASSERT_NE(right, nullptr);
  EXPECT_TRUE(hasGeometryNamed(right->collision, "RightGeo"));
}

TEST(WorkCellLoaderCompat, Pg70TestScene) {
  REQUIRE_COMPAT_DATA(data);
  const auto wc = loadCompat(data / "devices/PG70/test_scene.wc.xml");
  ASSERT_NE(wc, nullptr);
  EXPECT_EQ(wc->name(), "PG70TestScene");
  checkPg70(*wc);
  const auto bare = loadCompat(data / "devices/PG70/PG70.wc.xml");
  ASSERT_NE(bare, nullptr);
  checkPg70(*bare);
}

TEST(WorkCellLoaderCompat, Pg70BoxGraspScene) {
  REQUIRE_COMPAT_DATA(data);
  const auto wc = loadCompat(data / "scene/grasping/pg70_box.wc.xml");
  ASSERT_NE(wc, nullptr);
  EXPECT_EQ(wc->name(), "PG70BoxGraspScene");
  checkPg70(*wc);
  // The device base mounts on the last workcell frame before the Include.
  EXPECT_EQ(frameNamed(*wc, "PG70.Base").parent(), wc->findFrame("GripperOffset"));
  const auto state = wc->defaultState();
  const FKTable fk(wc->frames(), state);
  EXPECT_VECTOR_NEAR(fk.worldTransform(wc->findFrame("PG70.Base")).translation(),
                     Eigen::Vector3d(0, 0, 0.2), 1e-12);

  const auto* floor = wc->findObject(wc->findFrame("Floor"));
  ASSERT_NE(floor, nullptr);
  ASSERT_EQ(floor->collision.size(), 1u);
  EXPECT_EQ(floor->collision.front().name, "PlaneGeo");
  EXPECT_EQ(floor->collision.front().geometry->type(), rw::geometry::GeometryType::kMesh);
  EXPECT_EQ(std::filesystem::path(floor->collision.front().geometry->sourceFile()).filename(),
            "plane_5x5.stl");

  const auto& object = frameNamed(*wc, "object");
  EXPECT_EQ(object.type(), FrameType::kMovable);
  EXPECT_EQ(object.parent(), rw::kinematics::FrameTree::kWorld);
  EXPECT_TRANSFORM_NEAR(fk.worldTransform(object.id()),
                        rw::math::makeTranslation(Eigen::Vector3d(0, 0, 0.06)), 1e-15);
  const auto* box = wc->findObject(object.id());
  ASSERT_NE(box, nullptr);
  ASSERT_EQ(box->collision.size(), 1u);
  ASSERT_EQ(box->visual.size(), 1u);
  EXPECT_EQ(box->collision.front().geometry->type(), rw::geometry::GeometryType::kBox);
  EXPECT_EQ(box->collision.front().geometry->parameters(), (std::vector<double>{0.06, 0.06, 0.1}));
  EXPECT_EQ(box->collision.front().geometry, box->visual.front().geometry);
}

}  // namespace
