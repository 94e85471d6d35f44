// A linked finger (its distal joint a Depend on the proximal one, as a claw's or the SDH's
// phalanges are coupled) closing on a fixed cylinder under the PD law: the closing phase ends by
// the rest test, long before the closing cap. Before the fix the dependent joint's motor fed the
// owner's latest speed forward, and against the cylinder the two joints locked into a period-2
// oscillation (the proximal joint jumping between 0.125 and 0.154 rad every 5 ms step at
// +-6 rad/s): the rest test never held and every closing ran into the 5 s cap.
#include <gtest/gtest.h>

#include <string>

#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Q;

// Base at the world origin (kinematic), the proximal joint about world +y through it (its frame
// turned -90 deg about x: joint z = world y), the proximal link 6 cm along +x, the distal joint
// at its end with q_d = q_p, the distal link 4 cm; both links 2 cm square. Positive q turns the
// finger down. The cylinder (r 2 cm, axis along y, fixed) lies under the distal link: its top is
// 2.5 cm below the links' axis, 1.5 cm below their lower faces. The distal link meets it at
// q_p of about 0.12 rad, where the proximal link is still clear: the coupled pair is blocked by
// the distal link alone.
constexpr const char* kWorkcell = R"(<WorkCell name="LinkedFinger">
  <TreeDevice name="Finger">
    <Frame name="Base" type="Movable"><RPY>0 0 0</RPY><Pos>0 0 0</Pos>
      <Drawable name="Mount"><RPY>0 0 0</RPY><Pos>-0.02 0 0</Pos><Box x="0.02" y="0.02" z="0.02"/></Drawable>
    </Frame>
    <Joint name="Proximal" refframe="Base" type="Revolute"><RPY>0 0 -90</RPY><Pos>0 0 0</Pos>
      <PosLimit min="-30" max="120"/>
      <Drawable name="ProximalLink"><RPY>0 0 0</RPY><Pos>0.03 0 0</Pos><Box x="0.06" y="0.02" z="0.02"/></Drawable>
    </Joint>
    <Joint name="Distal" refframe="Proximal" type="Revolute"><RPY>0 0 0</RPY><Pos>0.06 0 0</Pos>
      <Depend on="Proximal" gain="1" offset="0"/>
      <Drawable name="DistalLink"><RPY>0 0 0</RPY><Pos>0.02 0 0</Pos><Box x="0.04" y="0.02" z="0.02"/></Drawable>
    </Joint>
    <Frame name="Tip" refframe="Distal" type="EndEffector"><RPY>0 0 0</RPY><Pos>0.04 0 0</Pos></Frame>
    <Frame name="TCP" refframe="Base"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Frame>
    <CollisionSetup file="finger.prox.xml"/>
  </TreeDevice>
  <Frame name="Cylinder" refframe="WORLD"><RPY>0 0 90</RPY><Pos>0.08 0 -0.045</Pos>
    <Drawable name="Rod"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Cylinder radius="0.02" z="0.1"/></Drawable>
  </Frame>
</WorkCell>
)";

constexpr const char* kCollisionSetup = R"(<CollisionSetup><Exclude>
  <FramePair first="Base" second="Proximal"/><FramePair first="Proximal" second="Distal"/>
</Exclude></CollisionSetup>
)";

// Torque limits 1 N m (proximal) and 2 N m (the dependent joint, larger than its owner's as
// docs/adding-a-hand.md advises), the paper's PD gains.
std::string dynamics(const std::string& materials) {
  return R"(<DynamicWorkcell workcell="finger.wc.xml">
  <Gravity>0 0 -9.81</Gravity>
  <Include file=")" +
         materials + R"("/>
  <FixedBody frame="Cylinder"><MaterialID>Object</MaterialID></FixedBody>
  <RigidDevice device="Finger">
    <ForceLimit joint="Proximal">1</ForceLimit>
    <ForceLimit joint="Distal">2</ForceLimit>
    <KinematicBase frame="Base"><MaterialID>Finger</MaterialID></KinematicBase>
    <RigidJoint joint="Proximal"><Mass>0.05</Mass><EstimateInertia/><MaterialID>Finger</MaterialID></RigidJoint>
    <RigidJoint joint="Distal"><Mass>0.03</Mass><EstimateInertia/><MaterialID>Finger</MaterialID></RigidJoint>
  </RigidDevice>
  <PDDeviceController name="GraspController" device="Finger" type="Position">
    <Sync>false</Sync><PDParams>10 0.003</PDParams><TimeStep>0.01</TimeStep>
  </PDDeviceController>
</DynamicWorkcell>
)";
}

class LinkedFinger : public ::testing::Test {
 protected:
  void SetUp() override {
    visgrab::test::writeFile(tmp_.path() / "finger.wc.xml", kWorkcell);
    visgrab::test::writeFile(tmp_.path() / "finger.prox.xml", kCollisionSetup);
    visgrab::test::writeFile(
        tmp_.path() / "finger.dwc.xml",
        dynamics((visgrab::test::sourceDir() / "scenes/materials.xml").generic_string()));
    dwc_ = rwsim::loaders::loadDynamicWorkCell(tmp_.path() / "finger.dwc.xml");
    setup_.hand = "Finger";
    setup_.tcpFrame = "Finger.TCP";
  }

  // Closes from straight (q 0) towards 1.5 rad, far past the cylinder; returns the trial and
  // sets closeEnd_ to the simulated time of the last closing step.
  rwsim::simulator::GraspTrialResult close() {
    setup_.observer = [this](const rwsim::trial::PhysicsEngine& sim, std::string_view phase) {
      if (phase != "close") return;
      closeEnd_ = sim.time();
      proximal_ = sim.jointPositions(dwc_->findDevice("Finger"))[0];
    };
    const rwsim::simulator::GraspTrial trial(*dwc_, setup_);
    rwsim::simulator::GraspParameters grasp;
    grasp.qOpen = Q::Zero(1);
    grasp.qClosed = Q::Constant(1, 1.5);
    return trial.run(grasp, dwc_->workcell().defaultState());
  }

  visgrab::test::TempDir tmp_;
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc_;
  rwsim::simulator::GraspTrialSetup setup_;
  double closeEnd_ = -1.0;
  double proximal_ = 0.0;
};

TEST_F(LinkedFinger, ClosingOnAFixedCylinderEndsByTheRestTest) {
  const auto r = close();
  EXPECT_LT(closeEnd_, 1.0) << r.detail;
  EXPECT_FALSE(r.closingCapped) << r.detail;
  EXPECT_FALSE(rwsim::trial::closingHitCap(r.detail)) << r.detail;
  // Blocked by the cylinder: touching it, far from the 1.5 rad it was closing towards.
  EXPECT_GT(proximal_, 0.08);
  EXPECT_LT(proximal_, 0.2);
  // The cylinder is fixed, not an object to lift: nothing to hold.
  EXPECT_EQ(r.outcome, rwsim::trial::GraspOutcome::kMissed) << r.detail;
}

// A closing that runs into the cap says so in the trial's detail (here the rest test is made
// unreachable: no speed counts as at rest).
TEST_F(LinkedFinger, AClosingStoppedByTheCapSaysSo) {
  setup_.restSpeedRevolute = 0.0;
  setup_.closeTimeLimit = 0.5;
  const auto r = close();
  EXPECT_TRUE(r.closingCapped);
  EXPECT_NEAR(closeEnd_, 0.5, 0.006);
  EXPECT_TRUE(rwsim::trial::closingHitCap(r.detail)) << r.detail;
  EXPECT_NE(r.detail.find("[closing hit the cap: 0.5 s simulated with Finger.Proximal still at "),
            std::string::npos)
      << r.detail;
  EXPECT_NE(r.detail.find("rad/s (at rest below 0)]"), std::string::npos) << r.detail;
}

}  // namespace
