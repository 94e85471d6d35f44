// The Franka Hand (scenes/hands/franka): its collision geometry against ACRONYM's collision mesh
// of the hand, and a jaw grasp of a standing box that holds through the lift.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "grasp_test_support.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/contact_ik.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"

namespace {

using rw::geometry::Aabb;
using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;
using visgrab::grasp::HandGraspSetup;
using visgrab::test::sourceDir;

const HandGraspSetup& frankaHand() {
  static const auto setup = visgrab::grasp::loadHandGraspSetup(sourceDir() / "scenes/hands/franka");
  return *setup;
}

// The world bounding box of the collision geometry of one frame of the hand at q (the base at
// the world's origin), or of the named geometries only.
Aabb collisionBounds(const HandGraspSetup& hand, double q, const std::string& frame,
                     const std::vector<std::string>& names = {}) {
  rw::kinematics::State state = hand.defaultState();
  hand.device().setQ(visgrab::test::grasp::makeQ({q}), state);
  const auto& wc = hand.workcell();
  const auto id = wc.findFrame("Franka." + frame);
  EXPECT_TRUE(id.valid()) << frame;
  const auto* object = wc.findObject(id);
  EXPECT_NE(object, nullptr) << frame;
  Aabb box;
  if (object == nullptr) return box;
  const Transform3D X_W_f = rw::kinematics::worldTransform(wc.frames(), state, id);
  for (const auto& g : object->collision) {
    if (!names.empty() && std::find(names.begin(), names.end(), g.name) == names.end()) continue;
    for (const Vector3D& v : g.geometry->triangles().vertices) {
      box.extend(X_W_f * (g.X_frame_geometry * v));
    }
  }
  return box;
}

void expectBoundsNear(const Aabb& model, const Aabb& mesh, double tol, const char* what) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(model.min[i], mesh.min[i], tol) << what << ", axis " << i;
    EXPECT_NEAR(model.max[i], mesh.max[i], tol) << what << ", axis " << i;
  }
}

// ACRONYM's mesh is in the hand's base frame (+z approach, +x closing) with the fingers fully
// open (0.04 each). Its 138 vertices fall in three groups: the two fingers (above the finger
// joints' plane z = 0.0584, within 0.07 of the centre along x and 0.011 across) and the palm
// (all the others). Per finger, the pad is the part above z = 0.09 (the diagonal finger below it
// reaches up to 0.09 only further out). The model's pads (their grip faces at x = +/-0.04, their
// z extent) and its palm (the union of the base's boxes) agree with these within 1 mm.
TEST(FrankaHand, AgreesWithAcronymsCollisionMesh) {
  const auto data = visgrab::test::acronymDataDir();
  if (!data) {
    GTEST_SKIP() << "ACRONYM's data is absent: set VISGRAB_ACRONYM_DATA to the folder holding "
                    "franka_gripper_collision_mesh.stl (or RW_COMPAT_DATA with ../acronym beside "
                    "it)";
  }
  const auto mesh = rw::geometry::loadMesh(*data / "franka_gripper_collision_mesh.stl");
  Aabb palm, leftPad, rightPad;
  double leftInner = 1.0, rightInner = -1.0;
  for (const Vector3D& v : mesh->vertices) {
    const bool finger = v.z() > 0.0584 && std::abs(v.x()) < 0.07 && std::abs(v.y()) < 0.011;
    if (!finger) {
      palm.extend(v);
    } else if (v.z() > 0.09) {
      (v.x() > 0 ? leftPad : rightPad).extend(v);
      if (v.x() > 0) leftInner = std::min(leftInner, v.x());
      if (v.x() < 0) rightInner = std::max(rightInner, v.x());
    }
  }
  ASSERT_FALSE(palm.empty());
  ASSERT_FALSE(leftPad.empty());
  ASSERT_FALSE(rightPad.empty());
  const HandGraspSetup& hand = frankaHand();
  const Aabb left = collisionBounds(hand, 0.04, "LeftFinger", {"LeftPadGeo"});
  const Aabb right = collisionBounds(hand, 0.04, "RightFinger", {"RightPadGeo"});
  // Grip faces along x at full opening.
  EXPECT_NEAR(left.min.x(), leftInner, 1e-3);
  EXPECT_NEAR(right.max.x(), rightInner, 1e-3);
  EXPECT_NEAR(left.min.x(), 0.04, 1e-12);
  EXPECT_NEAR(right.max.x(), -0.04, 1e-12);
  // The pads' extent along the approach.
  EXPECT_NEAR(left.min.z(), leftPad.min.z(), 1e-3);
  EXPECT_NEAR(left.max.z(), leftPad.max.z(), 1e-3);
  EXPECT_NEAR(right.min.z(), rightPad.min.z(), 1e-3);
  EXPECT_NEAR(right.max.z(), rightPad.max.z(), 1e-3);
  // The palm: every bound.
  expectBoundsNear(collisionBounds(hand, 0.04, "Base"), palm, 1e-3, "palm");
  // The whole finger: its outer edge and its foot.
  const Aabb leftFinger = collisionBounds(hand, 0.04, "LeftFinger");
  Aabb meshLeftFinger;
  for (const Vector3D& v : mesh->vertices) {
    if (v.z() > 0.0584 && v.x() > 0 && v.x() < 0.07 && std::abs(v.y()) < 0.011) {
      meshLeftFinger.extend(v);
    }
  }
  EXPECT_NEAR(leftFinger.max.x(), meshLeftFinger.max.x(), 1e-3);
  EXPECT_NEAR(leftFinger.min.z(), meshLeftFinger.min.z(), 1e-3);
  EXPECT_NEAR(leftFinger.max.z(), meshLeftFinger.max.z(), 1e-3);
}

// The Franka's published dimensions (franka_description): one DOF 0..0.04 driving both fingers,
// the TCP 0.1034 along the approach, the finger joints at 0.0584.
TEST(FrankaHand, KinematicsAreFrankaDescriptions) {
  const HandGraspSetup& hand = frankaHand();
  EXPECT_EQ(hand.dof(), 1);
  EXPECT_EQ(hand.device().lowerLimits()[0], 0.0);
  EXPECT_EQ(hand.device().upperLimits()[0], 0.04);
  EXPECT_TRANSFORM_NEAR(hand.X_base_tcp(), rw::math::makeTranslation(Vector3D(0, 0, 0.1034)),
                        1e-15);
  rw::kinematics::State state = hand.defaultState();
  const auto& wc = hand.workcell();
  for (const double q : {0.0, 0.02, 0.04}) {
    hand.device().setQ(visgrab::test::grasp::makeQ({q}), state);
    const auto at = [&](const char* f) {
      return rw::kinematics::worldTransform(wc.frames(), state, wc.findFrame(f)).translation();
    };
    EXPECT_VECTOR_NEAR(at("Franka.LeftFinger"), Vector3D(q, 0, 0.0584), 1e-15);
    EXPECT_VECTOR_NEAR(at("Franka.RightFinger"), Vector3D(-q, 0, 0.0584), 1e-15);
    EXPECT_VECTOR_NEAR(at("Franka.LeftPad"), Vector3D(q, 0, 0.1034), 1e-15);
    EXPECT_VECTOR_NEAR(at("Franka.RightPad"), Vector3D(-q, 0, 0.1034), 1e-15);
  }
}

// Contact IK with the two pads: contacts 50 mm apart on a horizontal line, pushing towards each
// other, approached from above. The pads' grip faces are 2 q apart, so the contact configuration
// is q = 0.025; both pads back off 1 cm (q_open 0.035); the TCP (the pads' centre) lands on the
// contacts' midpoint with z down; the closing rule gives q_closed = q_open - 0.02.
TEST(FrankaHand, ContactIkPutsThePadsOnTwoContacts) {
  const std::vector<visgrab::grasp::DesiredContact> contacts{
      {Vector3D(0.375, 0.1, 0.3), Vector3D(1, 0, 0)},
      {Vector3D(0.425, 0.1, 0.3), Vector3D(-1, 0, 0)}};
  const auto r = visgrab::grasp::solveContactIk(frankaHand(), contacts, -Vector3D::UnitZ());
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_NEAR(r.qContact[0], 0.025, 1e-4);
  EXPECT_NEAR(r.qOpen[0], 0.035, 1e-4);
  EXPECT_NEAR(r.qClosed[0], r.qOpen[0] - 0.02, 1e-9);
  EXPECT_LT((r.X_W_tcp.translation() - Vector3D(0.4, 0.1, 0.3)).norm(), 1e-3);
  EXPECT_GT(r.X_W_tcp.linear().col(2).dot(-Vector3D::UnitZ()),
            std::cos(1.0 * std::numbers::pi / 180));
}

// A jaw grasp from above on a 5 x 5 x 10 cm box of 0.2 kg standing on a table: the jaw frame at
// the box's axis 2.5 cm below its top (the pads span 8.9 mm either side of it, the palm's top is
// 37.4 mm above it, 12.4 mm clear of the box), the jaws closing along the world's x. The hand
// closes on the box's faces and holds it through the lift. A 9 cm box is wider than the
// stroke: the grasp is an input error, not a trial.
class FrankaBox : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new visgrab::test::TempDir();
    const std::string hands = (sourceDir() / "scenes/hands/franka").string();
    visgrab::test::writeFile(
        dir_->path() / "box.wc.xml",
        "<WorkCell name=\"FrankaBox\">\n"
        "  <Frame name=\"Table\" refframe=\"WORLD\"><RPY>0 0 0</RPY><Pos>0 0 -0.025</Pos>\n"
        "    <Drawable name=\"TableGeo\"><RPY>0 0 0</RPY><Pos>0 0 0</Pos>"
        "<Box x=\"0.8\" y=\"0.8\" z=\"0.05\"/></Drawable></Frame>\n"
        "  <Frame name=\"Box\" refframe=\"WORLD\" type=\"Movable\"><RPY>0 0 0</RPY>"
        "<Pos>0 0 0.05</Pos>\n"
        "    <Drawable name=\"BoxGeo\"><RPY>0 0 0</RPY><Pos>0 0 0</Pos>"
        "<Box x=\"0.05\" y=\"0.05\" z=\"0.1\"/></Drawable></Frame>\n"
        "  <Frame name=\"HandMount\" refframe=\"WORLD\"><RPY>0 180 0</RPY><Pos>0 0 0.4</Pos>"
        "</Frame>\n"
        "  <Include file=\"" +
            hands + "/franka.wc.xml\"/>\n</WorkCell>\n");
    visgrab::test::writeFile(
        dir_->path() / "box.dwc.xml",
        "<DynamicWorkcell workcell=\"box.wc.xml\">\n"
        "  <Gravity>0 0 -9.81</Gravity>\n"
        "  <Include file=\"" +
            (sourceDir() / "scenes/materials.xml").string() +
            "\"/>\n"
            "  <FixedBody frame=\"Table\"><MaterialID>Table</MaterialID></FixedBody>\n"
            "  <RigidBody frame=\"Box\"><Mass>0.2</Mass><EstimateInertia/>"
            "<Integrator>Euler</Integrator><MaterialID>Object</MaterialID></RigidBody>\n"
            "  <Include file=\"" +
            hands + "/franka_dynamics.dwc.xml\"/>\n</DynamicWorkcell>\n");
    dwc_ = rwsim::loaders::loadDynamicWorkCell(dir_->path() / "box.dwc.xml").release();
  }
  static void TearDownTestSuite() {
    delete dwc_;
    dwc_ = nullptr;
    delete dir_;
    dir_ = nullptr;
  }

  static rwsim::simulator::GraspTrialResult run(const rwsim::simulator::GraspParameters& g) {
    rwsim::simulator::GraspTrialSetup setup;
    setup.hand = frankaHand().deviceName();
    setup.controller = frankaHand().controllerName();
    setup.tcpFrame = frankaHand().tcpFrameName();
    setup.simulator = rwsim::simulator::optionsFromEngineProperties(*dwc_);
    return rwsim::simulator::GraspTrial(*dwc_, setup).run(g, dwc_->workcell().defaultState());
  }

  static GraspRequest topDown(double width) {
    GraspRequest r;
    r.id = "top";
    r.kind = GraspKind::kJaw;
    r.X_W_jaw =
        rw::math::rpyTransform(Vector3D(0, std::numbers::pi, 0), Vector3D(0, 0, 0.1 - 0.025));
    r.width = width;
    return r;
  }

  static visgrab::test::TempDir* dir_;
  static rwsim::dynamics::DynamicWorkCell* dwc_;
};

visgrab::test::TempDir* FrankaBox::dir_ = nullptr;
rwsim::dynamics::DynamicWorkCell* FrankaBox::dwc_ = nullptr;

TEST_F(FrankaBox, AJawGraspFromAboveHoldsAStandingBox) {
  const auto g = visgrab::grasp::resolve(topDown(0.05), frankaHand());
  ASSERT_TRUE(g.ok()) << g.message;
  const auto result = run(g.parameters);
  EXPECT_EQ(result.outcome, rwsim::trial::GraspOutcome::kStable)
      << rwsim::trial::outcomeName(result.outcome) << " (" << result.detail << ")";
  // The jaws stopped on the box's faces, 0.025 from its axis (q = the half width; the contact
  // solver lets the pads sink up to a millimetre), and the box rose with the hand.
  ASSERT_EQ(result.qGrasp.size(), 1);
  EXPECT_NEAR(result.qGrasp[0], 0.025, 1e-3);
  EXPECT_GE(result.contacts.size(), 2u);
  EXPECT_NEAR(result.objectLift.z(), result.handLift.z(), 0.01);
  EXPECT_GT(result.handLift.z(), 0.05);
}

TEST_F(FrankaBox, ABoxWiderThanTheStrokeIsAnInputError) {
  const auto g = visgrab::grasp::resolve(topDown(0.09), frankaHand());
  EXPECT_EQ(g.status, visgrab::grasp::ResolveStatus::kInputError);
  EXPECT_NE(g.message.find("width 0.09 m is outside what hand \"Franka\" opens to"),
            std::string::npos)
      << g.message;
}

}  // namespace
