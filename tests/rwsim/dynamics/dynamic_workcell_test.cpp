// DynamicWorkCell built in code: body geometry frames and the validations of addBody,
// addDevice and addController.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "support/test_support.hpp"

namespace {

using rw::kinematics::FrameId;
using rw::kinematics::FrameSpec;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rwsim::dynamics::Body;
using rwsim::dynamics::BodyId;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DeviceId;
using rwsim::dynamics::DynamicWorkCell;
using rwsim::dynamics::PDController;
using rwsim::dynamics::RigidDevice;

FrameId addFrame(rw::models::WorkCell& wc, const std::string& name, FrameId parent,
                 FrameType type = FrameType::kFixed, bool daf = false) {
  FrameSpec spec;
  spec.name = name;
  spec.parent = parent;
  spec.type = type;
  spec.daf = daf;
  return wc.frames().add(std::move(spec));
}

/// A gripper "G" (movable base, revolute J1 with a fixed J1Tip below it, prismatic J2 that
/// follows J1) plus a table and a movable object with a fixed marker frame and a DAF.
class DynamicWorkCellTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto wc = std::make_unique<rw::models::WorkCell>("test");
    table_ = addFrame(*wc, "Table", FrameTree::kWorld);
    object_ = addFrame(*wc, "Object", FrameTree::kWorld, FrameType::kMovable);
    marker_ = addFrame(*wc, "Object.Marker", object_);
    daf_ = addFrame(*wc, "Object.Daf", object_, FrameType::kFixed, true);
    base_ = addFrame(*wc, "G.Base", FrameTree::kWorld, FrameType::kMovable);
    palm_ = addFrame(*wc, "G.Palm", base_);
    j1_ = addFrame(*wc, "G.J1", palm_, FrameType::kRevolute);
    tip_ = addFrame(*wc, "G.J1Tip", j1_, FrameType::kFixed);
    FrameSpec j2;
    j2.name = "G.J2";
    j2.parent = base_;
    j2.type = FrameType::kPrismatic;
    j2.dependency = rw::kinematics::JointDependency{j1_, -1.0, 0.0};
    j2_ = wc->frames().add(std::move(j2));
    rw::models::Device::Spec device;
    device.name = "G";
    device.kind = rw::models::Device::Kind::kTree;
    device.base = base_;
    device.ends = {tip_, j2_};
    wc->addDevice(std::move(device));
    dwc_ = std::make_unique<DynamicWorkCell>(std::move(wc));
    dwc_->materials().addMaterial("Plastic");
    dwc_->materials().addMaterial("Rubber");
    dwc_->materials().setDefaultMaterial("Plastic");
  }

  Body body(const std::string& name, FrameId frame, BodyKind kind) const {
    Body b;
    b.name = name;
    b.frame = frame;
    b.kind = kind;
    b.material = "Plastic";
    if (kind == BodyKind::kRigid) {
      b.mass.mass = 0.1;
      b.mass.inertia = Eigen::Matrix3d::Identity() * 1e-4;
    }
    return b;
  }

  /// Adds the gripper's bodies and device; returns the device.
  DeviceId addGripper() {
    const BodyId base = dwc_->addBody(body("G.Base", base_, BodyKind::kKinematic));
    const BodyId l1 = dwc_->addBody(body("G.J1", j1_, BodyKind::kRigid));
    const BodyId l2 = dwc_->addBody(body("G.J2", j2_, BodyKind::kRigid));
    RigidDevice device;
    device.device = dwc_->workcell().findDevice("G");
    device.baseBody = base;
    device.linkBodies = {l1, l2};
    device.forceLimits = {2.0, 3.0};
    return dwc_->addDevice(std::move(device));
  }

  std::unique_ptr<DynamicWorkCell> dwc_;
  FrameId table_, object_, marker_, daf_, base_, palm_, j1_, tip_, j2_;
};

TEST_F(DynamicWorkCellTest, RigidlyAttachedFramesStopAtJointsMovablesDafsAndBodies) {
  const auto& tree = dwc_->workcell().frames();
  EXPECT_EQ(rwsim::dynamics::rigidlyAttachedFrames(tree, base_, {}),
            (std::vector<FrameId>{base_, palm_}));
  EXPECT_EQ(rwsim::dynamics::rigidlyAttachedFrames(tree, j1_, {}),
            (std::vector<FrameId>{j1_, tip_}));
  EXPECT_EQ(rwsim::dynamics::rigidlyAttachedFrames(tree, object_, {}),
            (std::vector<FrameId>{object_, marker_}));
  EXPECT_EQ(rwsim::dynamics::rigidlyAttachedFrames(tree, base_, {palm_}),
            (std::vector<FrameId>{base_}));
  // WORLD reaches the table only: Object and G.Base are Movable.
  EXPECT_EQ(rwsim::dynamics::rigidlyAttachedFrames(tree, FrameTree::kWorld, {}),
            (std::vector<FrameId>{FrameTree::kWorld, table_}));
}

TEST_F(DynamicWorkCellTest, BodiesDevicesAndControllersAreFoundByName) {
  const BodyId object = dwc_->addBody(body("Object", object_, BodyKind::kRigid));
  EXPECT_EQ(dwc_->bodies()[0].geometryFrames, (std::vector<FrameId>{object_, marker_}));
  EXPECT_EQ(dwc_->bodyOfFrame(marker_), object);
  EXPECT_EQ(dwc_->bodyOfFrame(daf_), BodyId::none());
  const DeviceId device = addGripper();
  EXPECT_EQ(dwc_->findDevice("G"), device);
  EXPECT_EQ(dwc_->findDevice("H"), DeviceId::none());
  EXPECT_EQ(dwc_->body(dwc_->findBody("G.J1")).device, device);
  EXPECT_EQ(dwc_->bodyOfFrame(tip_), dwc_->findBody("G.J1"));
  EXPECT_EQ(dwc_->body(dwc_->findBody("G.Base")).device, device);
  PDController pd;
  pd.name = "GraspController";
  pd.device = device;
  pd.p = Eigen::VectorXd::Constant(1, 10.0);
  pd.d = Eigen::VectorXd::Constant(1, 0.003);
  dwc_->addController(pd);
  ASSERT_NE(dwc_->findController("GraspController"), nullptr);
  EXPECT_EQ(dwc_->findController("Other"), nullptr);
  EXPECT_EQ(dwc_->findBody("Nothing"), BodyId::none());
}

TEST_F(DynamicWorkCellTest, AddBodyRejectsWhatCannotBeSimulated) {
  Body b = body("Object", object_, BodyKind::kRigid);
  b.mass.mass = -1;
  EXPECT_THROW(dwc_->addBody(b), std::invalid_argument);
  b = body("Object", object_, BodyKind::kRigid);
  b.mass.inertia(0, 0) = -1e-4;  // not positive definite
  EXPECT_THROW(dwc_->addBody(b), std::invalid_argument);
  b = body("Object", object_, BodyKind::kRigid);
  b.mass.inertia(0, 1) = 1e-5;  // not symmetric
  EXPECT_THROW(dwc_->addBody(b), std::invalid_argument);
  b = body("Object", object_, BodyKind::kRigid);
  b.material = "Steel";
  EXPECT_THROW(dwc_->addBody(b), std::invalid_argument);
  b.material.clear();
  EXPECT_THROW(dwc_->addBody(b), std::invalid_argument);
  b = body("Object", object_, BodyKind::kRigid);
  b.objectType = "soft";
  EXPECT_THROW(dwc_->addBody(b), std::invalid_argument);
  EXPECT_THROW(dwc_->addBody(body("Table", table_, BodyKind::kRigid)), std::invalid_argument);
  EXPECT_THROW(dwc_->addBody(body("Table", table_, BodyKind::kKinematic)), std::invalid_argument);
  EXPECT_THROW(dwc_->addBody(body("Ghost", FrameId{99}, BodyKind::kFixed)), std::invalid_argument);
  b = body("Object", object_, BodyKind::kRigid);
  b.device = DeviceId(0);
  EXPECT_THROW(dwc_->addBody(b), std::invalid_argument);

  dwc_->addBody(body("Object", object_, BodyKind::kRigid));
  EXPECT_THROW(dwc_->addBody(body("Object", table_, BodyKind::kFixed)), std::invalid_argument);
  // The marker's geometry already belongs to the object.
  EXPECT_THROW(dwc_->addBody(body("Marker", marker_, BodyKind::kFixed)), std::invalid_argument);
  EXPECT_NO_THROW(dwc_->addBody(body("Table", table_, BodyKind::kFixed)));
  EXPECT_EQ(dwc_->bodies().size(), 2u);
}

TEST_F(DynamicWorkCellTest, AddDeviceChecksLimitsAndLinks) {
  const BodyId base = dwc_->addBody(body("G.Base", base_, BodyKind::kKinematic));
  const BodyId l1 = dwc_->addBody(body("G.J1", j1_, BodyKind::kRigid));
  const BodyId object = dwc_->addBody(body("Object", object_, BodyKind::kRigid));
  RigidDevice d;
  d.device = dwc_->workcell().findDevice("G");
  d.baseBody = base;
  d.linkBodies = {l1, BodyId::none()};
  d.forceLimits = {2.0};  // J2 (dependent) needs one too
  EXPECT_THROW(dwc_->addDevice(d), std::invalid_argument);
  d.forceLimits = {2.0, -1.0};
  EXPECT_THROW(dwc_->addDevice(d), std::invalid_argument);
  d.forceLimits = {2.0, 3.0};
  d.linkBodies = {l1};
  EXPECT_THROW(dwc_->addDevice(d), std::invalid_argument);
  d.linkBodies = {object, BodyId::none()};  // not on J1's frame
  EXPECT_THROW(dwc_->addDevice(d), std::invalid_argument);
  d.linkBodies = {BodyId::none(), l1};
  EXPECT_THROW(dwc_->addDevice(d), std::invalid_argument);
  d.linkBodies = {l1, BodyId::none()};
  d.baseBody = BodyId(7);
  EXPECT_THROW(dwc_->addDevice(d), std::invalid_argument);
  d.baseBody = base;
  RigidDevice foreign = d;
  foreign.device = nullptr;
  EXPECT_THROW(dwc_->addDevice(foreign), std::invalid_argument);
  EXPECT_EQ(dwc_->addDevice(d), DeviceId(0));
  EXPECT_THROW(dwc_->addDevice(d), std::invalid_argument);  // added twice
}

TEST_F(DynamicWorkCellTest, AddControllerChecksGainsAgainstTheDof) {
  const DeviceId device = addGripper();
  PDController pd;
  pd.name = "pd";
  pd.device = device;
  pd.p = Eigen::VectorXd::Constant(2, 10.0);  // the DOF is 1 (J2 is dependent)
  pd.d = Eigen::VectorXd::Constant(2, 0.003);
  EXPECT_THROW(dwc_->addController(pd), std::invalid_argument);
  pd.p = Eigen::VectorXd::Constant(1, 10.0);
  EXPECT_THROW(dwc_->addController(pd), std::invalid_argument);
  pd.d = Eigen::VectorXd::Constant(1, 0.003);
  pd.type = "Torque";
  EXPECT_THROW(dwc_->addController(pd), std::invalid_argument);
  pd.type = "Position";
  pd.timeStep = 0.0;
  EXPECT_THROW(dwc_->addController(pd), std::invalid_argument);
  pd.timeStep = 0.01;
  pd.device = DeviceId(3);
  EXPECT_THROW(dwc_->addController(pd), std::invalid_argument);
  pd.device = device;
  EXPECT_NO_THROW(dwc_->addController(pd));
  EXPECT_THROW(dwc_->addController(pd), std::invalid_argument);  // same name
}

TEST(DynamicWorkCell, NeedsAWorkCell) {
  EXPECT_THROW(DynamicWorkCell(nullptr), std::invalid_argument);
}

}  // namespace
