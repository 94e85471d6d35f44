#include "sim_test_scenes.hpp"

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/rpy.hpp"

namespace visgrab::test::sim {

using rw::kinematics::FrameId;
using rw::kinematics::FrameSpec;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::Body;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DynamicWorkCell;

// Bodies and devices to add once the DynamicWorkCell exists.
struct SceneBuilder::Pending {
  std::vector<std::function<void(DynamicWorkCell&)>> steps;
};

namespace {

FrameId addFrame(rw::models::WorkCell& wc, const std::string& name, FrameId parent, FrameType type,
                 const Transform3D& X) {
  FrameSpec spec;
  spec.name = name;
  spec.parent = parent;
  spec.type = type;
  spec.transform = X;
  return wc.frames().add(spec);
}

void addGeometry(rw::models::WorkCell& wc, FrameId frame, const std::string& name,
                 const Transform3D& X, std::shared_ptr<const rw::geometry::Geometry> g) {
  rw::models::GeometryInstance gi;
  gi.name = name;
  gi.X_frame_geometry = X;
  gi.geometry = std::move(g);
  wc.objectOf(frame).collision.push_back(gi);
}

Body makeBody(const std::string& name, FrameId frame, BodyKind kind, const std::string& material) {
  Body b;
  b.name = name;
  b.frame = frame;
  b.kind = kind;
  b.material = material;
  return b;
}

}  // namespace

Eigen::Matrix3d boxInertia(double mass, const Vector3D& s) {
  return (mass / 12.0 *
          Vector3D(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                   s.x() * s.x() + s.y() * s.y()))
      .asDiagonal();
}

SceneBuilder::SceneBuilder(std::string name, double tableMu)
    : wc_(std::make_unique<rw::models::WorkCell>(std::move(name))),
      pending_(std::make_shared<Pending>()),
      tableMu_(tableMu) {}

void SceneBuilder::addTable(const std::string& name, const Transform3D& X_W, const Vector3D& size) {
  const FrameId f = addFrame(*wc_, name, FrameTree::kWorld, FrameType::kFixed, X_W);
  addGeometry(*wc_, f, name + "Geo", Transform3D::Identity(),
              rw::geometry::Geometry::box(size.x(), size.y(), size.z()));
  pending_->steps.push_back([name, f](DynamicWorkCell& dwc) {
    dwc.addBody(makeBody(name, f, BodyKind::kFixed, "Table"));
  });
}

void SceneBuilder::addBox(const std::string& name, const Transform3D& X_W, const Vector3D& size,
                          double mass) {
  const FrameId f = addFrame(*wc_, name, FrameTree::kWorld, FrameType::kMovable, X_W);
  addGeometry(*wc_, f, name + "Geo", Transform3D::Identity(),
              rw::geometry::Geometry::box(size.x(), size.y(), size.z()));
  pending_->steps.push_back([=](DynamicWorkCell& dwc) {
    Body b = makeBody(name, f, BodyKind::kRigid, "Object");
    b.mass.mass = mass;
    b.mass.inertia = boxInertia(mass, size);
    dwc.addBody(b);
  });
}

void SceneBuilder::addBody(const std::string& name, const Transform3D& X_W,
                           std::shared_ptr<const rw::geometry::Geometry> geometry, double mass,
                           const Eigen::Matrix3d& inertia, const Vector3D& cog) {
  const FrameId f = addFrame(*wc_, name, FrameTree::kWorld, FrameType::kMovable, X_W);
  addGeometry(*wc_, f, name + "Geo", Transform3D::Identity(), std::move(geometry));
  pending_->steps.push_back([=](DynamicWorkCell& dwc) {
    Body b = makeBody(name, f, BodyKind::kRigid, "Object");
    b.mass.mass = mass;
    b.mass.inertia = inertia;
    b.mass.cog = cog;
    dwc.addBody(b);
  });
}

void SceneBuilder::addGripper(const Transform3D& X_W, double gap, double force, double velocity) {
  auto& wc = *wc_;
  const FrameId base = addFrame(wc, "Gripper.Base", FrameTree::kWorld, FrameType::kMovable, X_W);
  addGeometry(wc, base, "Housing", rw::math::makeTranslation(Vector3D(0, 0, 0.1)),
              rw::geometry::Geometry::box(0.05, 0.05, 0.02));
  // Local z of a jaw frame points to the centre: Rx(-90 deg) maps z to +y, Rx(90 deg) to -y.
  const double q90 = std::numbers::pi / 2;
  FrameSpec left;
  left.name = "Gripper.Left";
  left.parent = base;
  left.type = FrameType::kPrismatic;
  left.transform = rw::math::rpyTransform(Vector3D(0, 0, -q90), Vector3D(0, -gap, 0));
  left.limits.lower = 0.0;
  left.limits.upper = gap;
  left.limits.velocity = velocity;
  const FrameId l = wc.frames().add(left);
  FrameSpec right = left;
  right.name = "Gripper.Right";
  right.transform = rw::math::rpyTransform(Vector3D(0, 0, q90), Vector3D(0, gap, 0));
  const FrameId r = wc.frames().add(right);
  const Vector3D plate(0.1, 0.1, 0.02);  // x, y (vertical after the turn), z (thickness)
  for (const FrameId jaw : {l, r}) {
    addGeometry(wc, jaw, "Plate", Transform3D::Identity(),
                rw::geometry::Geometry::box(plate.x(), plate.y(), plate.z()));
  }
  rw::models::Device::Spec spec;
  spec.name = "Gripper";
  spec.kind = rw::models::Device::Kind::kTree;
  spec.base = base;
  spec.ends = {l, r};
  const rw::models::Device& device = wc.addDevice(spec);
  const rw::models::Device* dev = &device;
  pending_->steps.push_back([=](DynamicWorkCell& dwc) {
    const auto b = dwc.addBody(makeBody("Gripper.Base", base, BodyKind::kKinematic, "Finger"));
    rwsim::dynamics::RigidDevice rd;
    rd.device = dev;
    rd.baseBody = b;
    for (const auto& [name, frame] :
         {std::pair{"Gripper.Left", l}, std::pair{"Gripper.Right", r}}) {
      Body link = makeBody(name, frame, BodyKind::kRigid, "Finger");
      link.mass.mass = 0.1;
      link.mass.inertia = boxInertia(0.1, plate);
      rd.linkBodies.push_back(dwc.addBody(link));
      rd.forceLimits.push_back(force);
    }
    const auto d = dwc.addDevice(rd);
    rwsim::dynamics::PDController pd;
    pd.name = "GraspController";
    pd.device = d;
    pd.p = Eigen::Vector2d(10.0, 10.0);
    pd.d = Eigen::Vector2d(0.003, 0.003);
    dwc.addController(pd);
  });
}

void SceneBuilder::addFinger(const Transform3D& X_W, double lever, double torque, bool limited) {
  auto& wc = *wc_;
  const FrameId base = addFrame(wc, "Finger.Base", FrameTree::kWorld, FrameType::kFixed, X_W);
  addGeometry(wc, base, "Mount", rw::math::makeTranslation(Vector3D(-0.03, 0, 0)),
              rw::geometry::Geometry::box(0.02, 0.02, 0.02));
  // Joint z along world +y: Rx(-90 deg); the joint frame's y then points down.
  FrameSpec joint;
  joint.name = "Finger.Joint";
  joint.parent = base;
  joint.type = FrameType::kRevolute;
  joint.transform = rw::math::rpyTransform(Vector3D(0, 0, -std::numbers::pi / 2), Vector3D::Zero());
  if (limited) {
    joint.limits.lower = -1.0;
    joint.limits.upper = 1.0;
  }
  const FrameId j = wc.frames().add(joint);
  // The rod stops short of the tip; the tip sphere sits on top of the rod's axis line so that
  // its lowest point is level with the joint axis (friction at the tip then has no lever).
  const double rod = lever - 0.012;
  addGeometry(wc, j, "Rod", rw::math::makeTranslation(Vector3D(rod / 2, 0, 0)),
              rw::geometry::Geometry::box(rod, 0.01, 0.01));
  addGeometry(wc, j, "Tip", rw::math::makeTranslation(Vector3D(lever, -0.01, 0)),
              rw::geometry::Geometry::sphere(0.01));
  rw::models::Device::Spec spec;
  spec.name = "Finger";
  spec.kind = rw::models::Device::Kind::kSerial;
  spec.base = base;
  spec.ends = {j};
  const rw::models::Device* dev = &wc.addDevice(spec);
  pending_->steps.push_back([=](DynamicWorkCell& dwc) {
    const auto b = dwc.addBody(makeBody("Finger.Base", base, BodyKind::kFixed, "Finger"));
    Body link = makeBody("Finger.Joint", j, BodyKind::kRigid, "Finger");
    link.mass.mass = 0.1;
    link.mass.cog = Vector3D(lever / 2, 0, 0);
    link.mass.inertia = boxInertia(0.1, Vector3D(lever, 0.01, 0.01));
    rwsim::dynamics::RigidDevice rd;
    rd.device = dev;
    rd.baseBody = b;
    rd.linkBodies = {dwc.addBody(link)};
    rd.forceLimits = {torque};
    dwc.addDevice(rd);
  });
}

std::unique_ptr<DynamicWorkCell> SceneBuilder::build(double gravity) {
  auto dwc = std::make_unique<DynamicWorkCell>(std::move(wc_));
  auto& m = dwc->materials();
  for (const char* name : {"Table", "Object", "Finger"}) m.addMaterial(name);
  m.setDefaultMaterial("Object");
  const auto coulomb = [](double mu) {
    rwsim::dynamics::FrictionData f;
    f.parameters = {{"Mu", {mu}}};
    return f;
  };
  m.setFriction("Object", "Table", coulomb(tableMu_));
  m.setFriction("Finger", "Object", coulomb(0.6));
  m.setFriction("Finger", "Finger", coulomb(0.8));
  m.setFriction("Finger", "Table", coulomb(0.4));
  m.setFriction("Object", "Object", coulomb(0.4));
  dwc->setGravity(Vector3D(0, 0, -gravity));
  for (const auto& step : pending_->steps) step(*dwc);
  return dwc;
}

std::unique_ptr<DynamicWorkCell> boxUnderTiltedGravity(double angle, double mu) {
  SceneBuilder scene("tilted", mu);
  scene.addTable("Table", rw::math::makeTranslation(Vector3D(0, 0, -0.05)), Vector3D(2, 1, 0.1));
  scene.addBox("Block", rw::math::makeTranslation(Vector3D(-0.5, 0, 0.025)),
               Vector3D(0.1, 0.1, 0.05), 0.5);
  auto dwc = scene.build();
  dwc->setGravity(kG * Vector3D(std::sin(angle), 0, -std::cos(angle)));
  return dwc;
}

std::unique_ptr<DynamicWorkCell> weighingScene(double boxMass, double jawForce) {
  SceneBuilder scene("weighing");
  scene.addTable("Table", rw::math::makeTranslation(Vector3D(0, 0, -0.05)), Vector3D(1, 1, 0.1));
  scene.addBox("Box", rw::math::makeTranslation(Vector3D(0, 0, 0.05)), Vector3D(0.1, 0.1, 0.1),
               boxMass);
  scene.addGripper(rw::math::makeTranslation(Vector3D(0.5, 0, 0.5)), 0.05, jawForce);
  return scene.build();
}

}  // namespace visgrab::test::sim
