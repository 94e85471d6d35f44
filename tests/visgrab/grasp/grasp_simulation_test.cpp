// Grasps resolved by the grasp utilities and simulated by rwsim's GraspTrial on the SDH box scene
// (tests/rwsim/simulator/data/sdh_box.dwc.xml: a 6 x 6 x 10 cm box standing at the origin).
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "grasp_test_support.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"

namespace {

using rw::math::Vector3D;
using rwsim::simulator::GraspTrial;
using rwsim::simulator::GraspTrialResult;
using rwsim::trial::GraspOutcome;
using visgrab::grasp::DesiredContact;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;
using visgrab::grasp::resolve;
using visgrab::test::grasp::sdh;

std::string describe(const GraspTrialResult& r) {
  return std::string(rwsim::trial::outcomeName(r.outcome)) + " (" + r.detail + "), Q_lift " +
         std::to_string(r.qLift);
}

class SdhBoxGrasp : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dwc_ = rwsim::loaders::loadDynamicWorkCell(visgrab::test::sourceDir() /
                                               "tests/rwsim/simulator/data/sdh_box.dwc.xml")
               .release();
  }
  static void TearDownTestSuite() {
    delete dwc_;
    dwc_ = nullptr;
  }

  // A trial set up from the hand's grasp description.
  static GraspTrialResult run(const rwsim::simulator::GraspParameters& g) {
    rwsim::simulator::GraspTrialSetup setup;
    setup.hand = sdh().deviceName();
    setup.controller = sdh().controllerName();
    setup.tcpFrame = sdh().tcpFrameName();
    setup.simulator = rwsim::simulator::optionsFromEngineProperties(*dwc_);
    return GraspTrial(*dwc_, setup).run(g, dwc_->workcell().defaultState());
  }

  static rwsim::dynamics::DynamicWorkCell* dwc_;
};

rwsim::dynamics::DynamicWorkCell* SdhBoxGrasp::dwc_ = nullptr;

TEST_F(SdhBoxGrasp, CylinderPreshapeOverTheBoxIsStable) {
  GraspRequest r;
  r.id = "cyl";
  r.kind = GraspKind::kPreshape;
  r.preshape = "SDH_CYL";
  // Hand pointing down, TCP at the box's centre (the box top is at z = 0.1).
  r.X_W_tcp = rw::math::rpyTransform(Vector3D(0, std::numbers::pi, 0), Vector3D(0, 0, 0.05));
  const auto g = resolve(r, sdh());
  ASSERT_TRUE(g.ok()) << g.message;
  const auto result = run(g.parameters);
  EXPECT_EQ(result.outcome, GraspOutcome::kStable) << describe(result);
}

TEST_F(SdhBoxGrasp, TwoFingerContactGraspOnOppositeFacesHolds) {
  GraspRequest r;
  r.id = "pinch";
  r.kind = GraspKind::kContacts;
  r.contacts = {DesiredContact{{-0.03, 0.0, 0.06}, {1, 0, 0}},
                DesiredContact{{0.03, 0.0, 0.06}, {-1, 0, 0}}};
  r.approach = -Vector3D::UnitZ();
  const auto g = resolve(r, sdh());
  ASSERT_TRUE(g.ok()) << g.message;
  const auto result = run(g.parameters);
  EXPECT_TRUE(result.outcome == GraspOutcome::kStable || result.outcome == GraspOutcome::kSlipped)
      << describe(result);
}

TEST_F(SdhBoxGrasp, ThreeFingerContactGraspHolds) {
  GraspRequest r;
  r.id = "tripod";
  r.kind = GraspKind::kContacts;
  r.contacts = {DesiredContact{{-0.03, 0.02, 0.06}, {1, 0, 0}},
                DesiredContact{{0.03, 0.0, 0.06}, {-1, 0, 0}},
                DesiredContact{{-0.03, -0.02, 0.06}, {1, 0, 0}}};
  r.approach = -Vector3D::UnitZ();
  const auto g = resolve(r, sdh());
  ASSERT_TRUE(g.ok()) << g.message;
  const auto result = run(g.parameters);
  EXPECT_TRUE(result.outcome == GraspOutcome::kStable || result.outcome == GraspOutcome::kSlipped)
      << describe(result);
}

}  // namespace
