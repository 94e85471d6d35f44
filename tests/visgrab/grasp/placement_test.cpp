// The collision-aware placement of contact grasps (visgrab/grasp/placement.hpp) in small scenes
// built in code: the project's SDH over a table with a standing can, a standing box or a lying
// bottle. Each case's contacts are worked by hand; the contact IK's own placement of them
// collides, and the search must find a collision-free one within the contact slack, or report
// the penetration when none exists.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "grasp_test_support.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/placement.hpp"

namespace {

using rw::math::Vector3D;
using rwsim::simulator::GraspParameters;
using rwsim::simulator::GraspTrial;
using rwsim::trial::GraspOutcome;
using visgrab::grasp::DesiredContact;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;
using visgrab::grasp::ResolveStatus;
using visgrab::test::grasp::sdh;

// A table top at z = 0 and one object given as workcell geometry (its frame's pose and
// geometry element), the SDH hanging above.
struct Scene {
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc;
  std::unique_ptr<GraspTrial> trial;

  Scene(const std::string& objectPose, const std::string& geometry, double mass) {
    const std::string wc =
        "<WorkCell name=\"PlacementScene\">\n"
        "  <Frame name=\"Table\" refframe=\"WORLD\"><RPY>0 0 0</RPY><Pos>0 0 -0.025</Pos>\n"
        "    <Drawable name=\"TableGeo\"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x=\"0.8\" y=\"0.8\" "
        "z=\"0.05\"/></Drawable>\n"
        "  </Frame>\n"
        "  <Frame name=\"Object\" refframe=\"WORLD\" type=\"Movable\">" +
        objectPose + "\n    <Drawable name=\"ObjectGeo\"><RPY>0 0 0</RPY><Pos>0 0 0</Pos>" +
        geometry +
        "</Drawable>\n  </Frame>\n"
        "  <Frame name=\"HandMount\" refframe=\"WORLD\"><RPY>0 180 0</RPY><Pos>0 0 0.5</Pos>"
        "</Frame>\n"
        "  <Include file=\"../../../../scenes/hands/sdh/sdh.wc.xml\"/>\n"
        "</WorkCell>\n";
    const std::string dwcXml =
        "<DynamicWorkcell workcell=\"placement.wc.xml\">\n"
        "  <Gravity>0 0 -9.81</Gravity>\n"
        "  <Include file=\"../../../../scenes/materials.xml\"/>\n"
        "  <FixedBody frame=\"Table\"><MaterialID>Table</MaterialID></FixedBody>\n"
        "  <RigidBody frame=\"Object\"><Mass>" +
        std::to_string(mass) +
        "</Mass><EstimateInertia/><Integrator>Euler</Integrator>"
        "<MaterialID>Object</MaterialID></RigidBody>\n"
        "  <Include file=\"../../../../scenes/hands/sdh/sdh_dynamics.dwc.xml\"/>\n"
        "</DynamicWorkcell>\n";
    dwc = rwsim::loaders::loadDynamicWorkCellFromStrings(
        dwcXml, wc, visgrab::test::sourceDir() / "tests/rwsim/simulator/data/placement.dwc.xml");
    rwsim::simulator::GraspTrialSetup setup;
    setup.hand = sdh().deviceName();
    setup.controller = sdh().controllerName();
    setup.tcpFrame = sdh().tcpFrameName();
    setup.simulator = rwsim::simulator::optionsFromEngineProperties(*dwc);
    trial = std::make_unique<GraspTrial>(*dwc, setup);
  }

  visgrab::grasp::PlacementTest test() const {
    return [this](const GraspParameters& g) {
      return trial->checkPlacement(g, dwc->workcell().defaultState());
    };
  }
};

GraspRequest contactGrasp(std::vector<DesiredContact> contacts, const Vector3D& approach) {
  GraspRequest r;
  r.id = "g";
  r.kind = GraspKind::kContacts;
  r.contacts = std::move(contacts);
  r.approach = approach;
  return r;
}

// The largest distance of a fingertip pad from its contact with the hand at q_contact, measured
// in the scene's own kinematics (the trial's placement of the base, the scene's frames).
double fingertipDeviation(const Scene& scene, const visgrab::grasp::ResolvedGrasp& g,
                          const std::vector<DesiredContact>& contacts) {
  GraspParameters atContact = g.parameters;
  atContact.qOpen = g.ik->qContact;
  const rw::kinematics::State state =
      scene.trial->placedState(atContact, scene.dwc->workcell().defaultState());
  const auto& tips = sdh().contactIk()->fingertips;
  double worst = 0.0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const auto& tip = tips[static_cast<std::size_t>(g.ik->fingerOfContact[k])];
    const auto frame =
        scene.dwc->workcell().findFrame(sdh().workcell().frames().frame(tip.frame).name());
    EXPECT_TRUE(frame.valid());
    const rw::math::Transform3D X =
        rw::kinematics::worldTransform(scene.dwc->workcell().frames(), state, frame);
    worst = std::max(worst, (X * tip.point - contacts[k].position).norm());
  }
  return worst;
}

// Checks a case whose naive placement collides and whose search must find a free one.
void expectPlacedFree(const Scene& scene, const GraspRequest& r) {
  const auto naive = visgrab::grasp::resolve(r, sdh());
  ASSERT_TRUE(naive.ok()) << naive.message;
  const auto naiveCheck = scene.test()(naive.parameters);
  ASSERT_TRUE(naiveCheck.collides) << "the case must collide when placed naively";
  EXPECT_GT(naiveCheck.penetration, 0.0) << naiveCheck.detail;

  const auto placed = visgrab::grasp::resolve(r, sdh(), scene.test());
  ASSERT_TRUE(placed.ok()) << placed.message;
  ASSERT_TRUE(placed.placement.has_value());
  EXPECT_TRUE(placed.placement->found);
  EXPECT_GT(placed.placement->tests, 1);
  const auto check = scene.test()(placed.parameters);
  EXPECT_FALSE(check.collides) << check.detail;
  EXPECT_EQ(check.penetration, 0.0);
  // Within the contact slack of the IK's own solution (5 mm by default), measured independently.
  const double slack = visgrab::grasp::PlacementOptions{}.contactSlack;
  EXPECT_LE(fingertipDeviation(scene, placed, r.contacts),
            fingertipDeviation(scene, naive, r.contacts) + slack + 1e-6)
      << placed.placement->describe();
  // The trial starts from it: whatever the grasp does, it is not in collision.
  const auto result = scene.trial->run(placed.parameters, scene.dwc->workcell().defaultState());
  EXPECT_NE(result.outcome, GraspOutcome::kInCollision) << result.detail;
  // Deterministic.
  const auto again = visgrab::grasp::resolve(r, sdh(), scene.test());
  EXPECT_TRUE(again.parameters.X_W_tcp.isApprox(placed.parameters.X_W_tcp, 0.0));
  EXPECT_EQ(again.parameters.qOpen, placed.parameters.qOpen);
}

// A standing 0.33 l can (r 33 mm, h 115 mm), grasped from above by two fingers 2 cm above the
// table: the contact IK's posture puts finger 2's middle link 3 mm into the can.
TEST(Placement, CanFromAboveLowOnItsSidesIsPlacedFree) {
  const Scene can("<RPY>0 0 0</RPY><Pos>0 0 0.0575</Pos>",
                  "<Cylinder radius=\"0.033\" z=\"0.115\"/>", 0.35);
  expectPlacedFree(can, contactGrasp({DesiredContact{{-0.033, 0, 0.02}, {1, 0, 0}},
                                      DesiredContact{{0.033, 0, 0.02}, {-1, 0, 0}}},
                                     -Vector3D::UnitZ()));
}

// A standing 6 x 6 x 10 cm box, three fingers from above at mid-height (thumb on +x, fingers
// 2 cm either side on -x): the thumb's proximal link touches the box 0.7 mm deep.
TEST(Placement, BoxThreeFingersAtMidHeightIsPlacedFree) {
  const Scene box("<RPY>0 0 0</RPY><Pos>0 0 0.05</Pos>", "<Box x=\"0.06\" y=\"0.06\" z=\"0.1\"/>",
                  0.2);
  expectPlacedFree(box, contactGrasp({DesiredContact{{-0.03, 0.02, 0.05}, {1, 0, 0}},
                                      DesiredContact{{0.03, 0.0, 0.05}, {-1, 0, 0}},
                                      DesiredContact{{-0.03, -0.02, 0.05}, {1, 0, 0}}},
                                     -Vector3D::UnitZ()));
}

// A bottle (r 34 mm, 235 mm long) lying along x, grasped across its widest line (z = 34 mm)
// from its end (approach +x): the IK's posture puts finger 2 12 mm into the bottle.
TEST(Placement, LyingBottleFromItsEndIsPlacedFree) {
  const Scene bottle("<RPY>0 90 0</RPY><Pos>0 0 0.034</Pos>",
                     "<Cylinder radius=\"0.034\" z=\"0.235\"/>", 0.55);
  expectPlacedFree(bottle, contactGrasp({DesiredContact{{0.0, -0.034, 0.034}, {0, 1, 0}},
                                         DesiredContact{{0.0, 0.034, 0.034}, {0, -1, 0}}},
                                        Vector3D::UnitX()));
}

// Three fingers from above on the box 2 cm above the table: the thumb's links cannot clear
// the box within the slack, so no collision-free placement exists; the grasp is in collision
// and the message gives the least penetration found.
TEST(Placement, NoFreePlacementIsInCollisionWithThePenetration) {
  const Scene box("<RPY>0 0 0</RPY><Pos>0 0 0.05</Pos>", "<Box x=\"0.06\" y=\"0.06\" z=\"0.1\"/>",
                  0.2);
  const GraspRequest r = contactGrasp({DesiredContact{{-0.03, 0.02, 0.02}, {1, 0, 0}},
                                       DesiredContact{{0.03, 0.0, 0.02}, {-1, 0, 0}},
                                       DesiredContact{{-0.03, -0.02, 0.02}, {1, 0, 0}}},
                                      -Vector3D::UnitZ());
  const auto placed = visgrab::grasp::resolve(r, sdh(), box.test());
  ASSERT_EQ(placed.status, ResolveStatus::kInCollision) << placed.message;
  ASSERT_TRUE(placed.placement.has_value());
  EXPECT_FALSE(placed.placement->found);
  EXPECT_EQ(placed.placement->tests, placed.placement->candidates);
  // The placement shown is the least penetrating one, and its test says so.
  const auto check = box.test()(placed.parameters);
  EXPECT_TRUE(check.collides);
  EXPECT_NEAR(check.penetration, placed.placement->check.penetration, 1e-12);
  EXPECT_GT(check.penetration, 0.001);
  char mm[32];
  std::snprintf(mm, sizeof(mm), "least penetration %.1f mm", check.penetration * 1e3);
  EXPECT_NE(placed.message.find("no collision-free placement among"), std::string::npos)
      << placed.message;
  EXPECT_NE(placed.message.find(mm), std::string::npos) << placed.message;
  EXPECT_NE(placed.message.find("penetrates object frame Object"), std::string::npos)
      << placed.message;
  // The trial agrees: it is in collision at once, with the same penetration in its detail.
  const auto result = box.trial->run(placed.parameters, box.dwc->workcell().defaultState());
  EXPECT_EQ(result.outcome, GraspOutcome::kInCollision);
  char by[32];
  std::snprintf(by, sizeof(by), "by %.1f mm", check.penetration * 1e3);
  EXPECT_NE(result.detail.find(by), std::string::npos) << result.detail;
}

// A grasp the IK places free is left as it is: the search tests it once.
TEST(Placement, FreeIkPlacementIsKept) {
  const Scene box("<RPY>0 0 0</RPY><Pos>0 0 0.05</Pos>", "<Box x=\"0.06\" y=\"0.06\" z=\"0.1\"/>",
                  0.2);
  const GraspRequest r = contactGrasp(
      {DesiredContact{{-0.03, 0, 0.09}, {1, 0, 0}}, DesiredContact{{0.03, 0, 0.09}, {-1, 0, 0}}},
      -Vector3D::UnitZ());
  const auto naive = visgrab::grasp::resolve(r, sdh());
  const auto placed = visgrab::grasp::resolve(r, sdh(), box.test());
  ASSERT_TRUE(placed.ok()) << placed.message;
  EXPECT_EQ(placed.placement->tests, 1);
  EXPECT_TRUE(placed.parameters.X_W_tcp.isApprox(naive.parameters.X_W_tcp, 0.0));
  EXPECT_EQ(placed.parameters.qOpen, naive.parameters.qOpen);
}

}  // namespace
