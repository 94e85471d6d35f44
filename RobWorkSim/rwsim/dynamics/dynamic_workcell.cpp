#include "rwsim/dynamics/dynamic_workcell.hpp"

#include "rwsim/dynamics/loop_closure.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace rwsim::dynamics {

namespace {

using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;

/// Controller types RobWork's PDDeviceController knows.
constexpr std::array<std::string_view, 5> kControllerTypes = {"Position", "CntPosition", "Velocity",
                                                              "Force", "Current"};

/// Relative tolerance of the symmetry check of an inertia tensor.
constexpr double kSymmetryTolerance = 1e-9;

[[noreturn]] void fail(const std::string& message) { throw std::invalid_argument(message); }

bool contains(const std::vector<FrameId>& frames, FrameId id) {
  return std::find(frames.begin(), frames.end(), id) != frames.end();
}

bool validFrame(const FrameTree& tree, FrameId id) {
  return id.valid() && static_cast<std::size_t>(id.index) < tree.size();
}

void checkMassProperties(const Body& body) {
  const MassProperties& m = body.mass;
  const std::string what = "body \"" + body.name + "\": ";
  if (!std::isfinite(m.mass) || !(m.mass > 0.0)) fail(what + "mass must be finite and > 0");
  if (!m.cog.allFinite()) fail(what + "the centre of mass is not finite");
  if (!m.inertia.allFinite()) fail(what + "the inertia is not finite");
  const double scale = m.inertia.cwiseAbs().maxCoeff();
  if ((m.inertia - m.inertia.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * scale) {
    fail(what + "the inertia is not symmetric");
  }
  if (!(scale > 0.0) || Eigen::LLT<Eigen::Matrix3d>(m.inertia).info() != Eigen::Success) {
    fail(what + "the inertia is not positive definite");
  }
}

}  // namespace

std::vector<FrameId> rigidlyAttachedFrames(const FrameTree& tree, FrameId frame,
                                           const std::vector<FrameId>& stopAt) {
  std::vector<FrameId> result;
  std::vector<FrameId> pending{frame};
  while (!pending.empty()) {
    const FrameId id = pending.back();
    pending.pop_back();
    result.push_back(id);
    // Reverse iterators, not std::views::reverse: clang 14 (the fuzz build) cannot compile
    // libstdc++ 12's views.
    const std::vector<FrameId>& children = tree.children(id);
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      const FrameId c = *it;
      const rw::kinematics::Frame& child = tree.frame(c);
      if (child.type() != FrameType::kFixed || child.isDaf() || contains(stopAt, c)) continue;
      pending.push_back(c);
    }
  }
  return result;
}

DynamicWorkCell::DynamicWorkCell(std::unique_ptr<rw::models::WorkCell> workcell)
    : workcell_(std::move(workcell)) {
  if (!workcell_) fail("DynamicWorkCell: the workcell is null");
  bodyOfFrame_.assign(workcell_->frames().size(), BodyId::none());
}

BodyId DynamicWorkCell::findBody(std::string_view name) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].name == name) return BodyId(i);
  }
  return BodyId::none();
}

BodyId DynamicWorkCell::bodyOfFrame(FrameId frame) const {
  if (!frame.valid() || static_cast<std::size_t>(frame.index) >= bodyOfFrame_.size()) {
    return BodyId::none();
  }
  return bodyOfFrame_[static_cast<std::size_t>(frame.index)];
}

BodyId DynamicWorkCell::bodyAbove(FrameId frame) const {
  const auto& tree = workcell_->frames();
  if (!validFrame(tree, frame)) return BodyId::none();
  for (FrameId f = tree.frame(frame).parent(); f.valid(); f = tree.frame(f).parent()) {
    const BodyId b = bodyOfFrame(f);
    if (b.valid()) return b;
    if (f == rw::kinematics::FrameTree::kWorld) break;
  }
  return BodyId::none();
}

DeviceId DynamicWorkCell::findDevice(std::string_view name) const {
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    if (devices_[i].device->name() == name) return DeviceId(i);
  }
  return DeviceId::none();
}

const PDController* DynamicWorkCell::findController(std::string_view name) const {
  for (const PDController& c : controllers_) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

const Constraint* DynamicWorkCell::findConstraint(std::string_view name) const {
  for (const Constraint& c : constraints_) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

BodyId DynamicWorkCell::addBody(Body body) {
  const FrameTree& tree = workcell_->frames();
  const std::string what = "body \"" + body.name + "\": ";
  if (body.name.empty()) fail("a body needs a name");
  if (findBody(body.name).valid()) fail(what + "a body of this name exists");
  if (!validFrame(tree, body.frame)) fail(what + "unknown frame");
  if (body.device.valid()) fail(what + "Body::device is set by addDevice and must be none");
  const rw::kinematics::Frame& frame = tree.frame(body.frame);
  if (body.kind == BodyKind::kRigid) {
    if (frame.type() != FrameType::kMovable && !frame.isJoint()) {
      fail(what + "a rigid body needs a Movable frame or a joint, \"" + frame.name() + "\" is not");
    }
    checkMassProperties(body);
  } else if (body.kind == BodyKind::kKinematic && frame.type() != FrameType::kMovable) {
    fail(what + "a kinematic body needs a Movable frame, \"" + frame.name() + "\" is not");
  }
  if (body.material.empty() || !materials_.hasMaterial(body.material)) {
    fail(what + "undeclared material \"" + body.material + "\"");
  }
  if (!body.objectType.empty() && !materials_.hasObjectType(body.objectType)) {
    fail(what + "undeclared object type \"" + body.objectType + "\"");
  }
  if (body.geometryFrames.empty()) {
    std::vector<FrameId> stopAt;
    for (const Body& b : bodies_) stopAt.push_back(b.frame);
    body.geometryFrames = rigidlyAttachedFrames(tree, body.frame, stopAt);
  } else if (!contains(body.geometryFrames, body.frame)) {
    fail(what + "geometryFrames must contain the body frame");
  }
  for (const FrameId id : body.geometryFrames) {
    if (!validFrame(tree, id)) fail(what + "unknown geometry frame");
    const BodyId owner = bodyOfFrame(id);
    if (owner.valid() ||
        std::count(body.geometryFrames.begin(), body.geometryFrames.end(), id) > 1) {
      fail(what + "frame \"" + tree.frame(id).name() + "\" already belongs to body \"" +
           (owner.valid() ? this->body(owner).name : body.name) + "\"");
    }
  }
  const BodyId id(bodies_.size());
  for (const FrameId f : body.geometryFrames) {
    bodyOfFrame_[static_cast<std::size_t>(f.index)] = id;
  }
  bodies_.push_back(std::move(body));
  return id;
}

DeviceId DynamicWorkCell::addDevice(RigidDevice device) {
  const auto& known = workcell_->devices();
  if (device.device == nullptr || std::none_of(known.begin(), known.end(), [&](const auto& d) {
        return d.get() == device.device;
      })) {
    fail("rigid device: the device is not one of this workcell's devices");
  }
  const std::string what = "rigid device \"" + device.device->name() + "\": ";
  if (findDevice(device.device->name()).valid()) fail(what + "already added");
  const auto& joints = device.device->joints();
  if (device.forceLimits.size() != joints.size()) {
    fail(what + "expected " + std::to_string(joints.size()) +
         " force limits (one per joint), got " + std::to_string(device.forceLimits.size()));
  }
  for (const double limit : device.forceLimits) {
    if (!std::isfinite(limit) || limit < 0.0) fail(what + "force limits must be finite and >= 0");
  }
  if (device.linkBodies.size() != joints.size()) {
    fail(what + "expected " + std::to_string(joints.size()) + " link bodies (one per joint, -1 " +
         "for none), got " + std::to_string(device.linkBodies.size()));
  }
  const auto validBody = [&](BodyId b) { return b.valid() && b.index() < bodies_.size(); };
  if (!validBody(device.baseBody)) fail(what + "invalid base body");
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const BodyId link = device.linkBodies[j];
    if (!link.valid()) continue;
    if (!validBody(link)) fail(what + "invalid link body index");
    const Body& body = this->body(link);
    if (body.kind != BodyKind::kRigid || body.frame != joints[j] || body.device.valid() ||
        link == device.baseBody ||
        std::count(device.linkBodies.begin(), device.linkBodies.end(), link) > 1) {
      fail(what + "body \"" + body.name + "\" cannot be the link of joint \"" +
           workcell_->frames().frame(joints[j]).name() +
           "\" (it must be an unused rigid body on that joint's frame)");
    }
  }
  device.loopClosures = loopClosures(*this, device);  // throws if they cannot be closed
  const DeviceId id(devices_.size());
  Body& base = bodies_[device.baseBody.index()];
  if (!base.device.valid()) base.device = id;
  for (const BodyId link : device.linkBodies) {
    if (link.valid()) bodies_[link.index()].device = id;
  }
  devices_.push_back(std::move(device));
  return id;
}

void DynamicWorkCell::addController(PDController controller) {
  const std::string what = "controller \"" + controller.name + "\": ";
  if (controller.name.empty()) fail("a controller needs a name");
  if (findController(controller.name) != nullptr) fail(what + "a controller of this name exists");
  if (!controller.device.valid() || controller.device.index() >= devices_.size()) {
    fail(what + "invalid device index");
  }
  const int dof = device(controller.device).device->dof();
  if (controller.p.size() != dof || controller.d.size() != dof) {
    fail(what + "expected " + std::to_string(dof) + " P and D gains (one per DOF), got " +
         std::to_string(controller.p.size()) + " and " + std::to_string(controller.d.size()));
  }
  if (!controller.p.allFinite() || !controller.d.allFinite()) fail(what + "gains must be finite");
  if (std::find(kControllerTypes.begin(), kControllerTypes.end(), controller.type) ==
      kControllerTypes.end()) {
    fail(what + "unknown type \"" + controller.type +
         "\" (expected Position, CntPosition, Velocity, Force or Current)");
  }
  if (!std::isfinite(controller.timeStep) || !(controller.timeStep > 0.0)) {
    fail(what + "the time step must be > 0");
  }
  controllers_.push_back(std::move(controller));
}

void DynamicWorkCell::addConstraint(Constraint constraint) {
  const Constraint& c = constraint;
  const std::string what = "constraint \"" + c.name + "\": ";
  if (c.name.empty()) fail("a constraint needs a name");
  if (findConstraint(c.name) != nullptr) fail(what + "a constraint of this name exists");
  for (const BodyId id : {c.parent, c.child}) {
    if (!id.valid() || id.index() >= bodies_.size()) fail(what + "invalid body index");
  }
  if (c.parent == c.child) fail(what + "parent and child are the same body");
  if (body(c.parent).kind != BodyKind::kRigid && body(c.child).kind != BodyKind::kRigid) {
    fail(what + "neither body is rigid (" + body(c.parent).name + " and " + body(c.child).name +
         " are fixed or kinematic), so nothing can move");
  }
  const Eigen::Matrix3d& R = c.X_parent_constraint.linear();
  if (!c.X_parent_constraint.matrix().allFinite() ||
      !(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || !(R.determinant() > 0)) {
    fail(what + "the transform is not finite or its rotation is not a rotation matrix");
  }
  const ConstraintDof dof = constraintDof(c.type);
  const std::string typeName(constraintTypeName(c.type));
  if (!c.limits.empty()) {
    if (c.type == ConstraintType::kSpherical || c.type == ConstraintType::kFree) {
      fail(what + "a " + typeName + " constraint takes no limits");
    }
    if (c.limits.size() != dof.total()) {
      fail(what + "expected " + std::to_string(dof.total()) + " limits (one per free DOF of a " +
           typeName + " constraint), got " + std::to_string(c.limits.size()));
    }
    for (std::size_t i = 0; i < c.limits.size(); ++i) {
      const ConstraintLimit& l = c.limits[i];
      if (std::isnan(l.low) || std::isnan(l.high) || l.low > l.high) {
        fail(what + "limit " + std::to_string(i) + ": low must be <= high");
      }
      const bool angular = i >= dof.linear;
      const bool beyondPi = (std::isfinite(l.low) && l.low < -std::numbers::pi) ||
                            (std::isfinite(l.high) && l.high > std::numbers::pi);
      if (angular && beyondPi) {
        fail(what + "limit " + std::to_string(i) + ": an angular limit must lie in [-pi, pi]");
      }
    }
  }
  if (c.spring) {
    const auto n = static_cast<Eigen::Index>(dof.total());
    for (const Eigen::MatrixXd* m : {&c.spring->compliance, &c.spring->damping}) {
      if (m->rows() != n || m->cols() != n || !m->allFinite()) {
        fail(what + "spring matrices must be finite and " + std::to_string(n) + " x " +
             std::to_string(n));
      }
    }
  }
  constraints_.push_back(std::move(constraint));
}

std::vector<std::pair<BodyId, BodyId>> jointConnectedBodyPairs(const DynamicWorkCell& dwc) {
  std::vector<std::pair<BodyId, BodyId>> pairs;
  for (const RigidDevice& rd : dwc.devices()) {
    const auto& joints = rd.device->joints();
    for (std::size_t j = 0; j < joints.size() && j < rd.linkBodies.size(); ++j) {
      const BodyId link = rd.linkBodies[j];
      const BodyId above = link.valid() ? dwc.bodyAbove(joints[j]) : BodyId::none();
      if (above.valid() && above != link)
        pairs.emplace_back(std::min(link, above), std::max(link, above));
    }
    for (const LoopClosure& c : rd.loopClosures) {
      pairs.emplace_back(std::min(c.parent, c.child), std::max(c.parent, c.child));
    }
  }
  for (const Constraint& c : dwc.constraints()) {
    if (c.type == ConstraintType::kFree) continue;
    pairs.emplace_back(std::min(c.parent, c.child), std::max(c.parent, c.child));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace rwsim::dynamics
