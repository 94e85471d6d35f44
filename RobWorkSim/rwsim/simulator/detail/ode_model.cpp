#include "rwsim/simulator/detail/ode_model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/trial/physics_variation.hpp"

namespace rwsim::simulator::detail {

namespace {

using rw::kinematics::FrameId;
using rw::kinematics::FrameType;
using rw::math::Transform3D;
using rw::math::Vector3D;

constexpr double kPi = std::numbers::pi;
// How far past a stop (rad or m) a joint may be for the stop to be released when its motor
// drives it back.
constexpr double kStopRelease = 1e-3;

void checkMass(const dynamics::Body& body) {
  const auto& m = body.mass;
  if (!std::isfinite(m.mass) || m.mass <= 0.0) {
    throw std::invalid_argument("body " + body.name + ": mass must be > 0 to simulate it");
  }
  const Eigen::Matrix3d& I = m.inertia;
  const bool finite = I.allFinite() && m.cog.allFinite();
  const bool symmetric = finite && (I - I.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * I.norm();
  bool valid = symmetric;
  if (valid) {
    const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
    const double tol = 1e-9 * e.cwiseAbs().maxCoeff();
    valid = e.minCoeff() > 0.0 && e[0] + e[1] >= e[2] - tol;
  }
  if (!valid) {
    throw std::invalid_argument("body " + body.name +
                                ": inertia must be symmetric and positive definite with "
                                "principal moments obeying the triangle inequality");
  }
}

void setOdePose(dBodyID id, const Transform3D& X_W_cog) {
  const Vector3D& p = X_W_cog.translation();
  dBodySetPosition(id, p.x(), p.y(), p.z());
  const Eigen::Quaterniond q(X_W_cog.linear());
  const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
  dBodySetQuaternion(id, dq);
  dBodySetLinearVel(id, 0, 0, 0);
  dBodySetAngularVel(id, 0, 0, 0);
}

void setDamping(dBodyID id, const dynamics::Body& body) {
  const auto read = [&](const char* key) -> double {
    const auto it = body.properties.find(key);
    if (it == body.properties.end()) return -1.0;
    if (const auto* v = std::get_if<double>(&it->second.value)) return *v;
    if (const auto* s = std::get_if<std::string>(&it->second.value)) {
      try {
        return std::stod(*s);
      } catch (const std::exception&) {
      }
    }
    throw std::invalid_argument("body " + body.name + ": property " + key + " is not a number");
  };
  const double linear = read("LinearDamping");
  const double angular = read("AngularDamping");
  if (linear >= 0.0) dBodySetLinearDamping(id, linear);
  if (angular >= 0.0) dBodySetAngularDamping(id, angular);
}

// Stop of a hinge measured from q0: ODE stops work within (-pi, pi); beyond that, no stop.
double hingeStop(double limit, double q0, bool lower) {
  const double s = limit - q0;
  if (!std::isfinite(s)) return lower ? -dInfinity : dInfinity;
  if (lower) return s > -kPi ? s : -dInfinity;
  return s < kPi ? s : dInfinity;
}

double sliderStop(double limit, double q0, bool lower) {
  const double s = limit - q0;
  if (!std::isfinite(s)) return lower ? -dInfinity : dInfinity;
  return s;
}

// A device joint's description: its DOF index or coupling, force limit, value and stops.
SimJoint describeJoint(const rw::kinematics::FrameTree& tree, const dynamics::RigidDevice& rd,
                       std::size_t j, const rw::kinematics::State& state) {
  const auto& joints = rd.device->joints();
  const auto& frame = tree.frame(joints[j]);
  SimJoint sj;
  sj.frame = joints[j];
  sj.revolute = frame.type() == FrameType::kRevolute;
  sj.q0 = frame.jointValue(state);
  sj.forceLimit = rd.forceLimits[j];
  if (frame.isActiveJoint()) {
    const auto& active = rd.device->activeJoints();
    sj.activeIndex =
        static_cast<int>(std::find(active.begin(), active.end(), joints[j]) - active.begin());
  }
  if (frame.isDependent()) {
    const auto& dep = *frame.dependency();
    sj.gain = dep.gain;
    sj.offset = dep.offset;
    const auto owner = std::find(joints.begin(), joints.end(), dep.owner);
    if (owner == joints.end()) {
      throw std::invalid_argument("joint " + frame.name() + " depends on a joint outside " +
                                  rd.device->name());
    }
    sj.owner = static_cast<std::size_t>(owner - joints.begin());
  } else {
    const auto& limits = frame.limits();
    sj.loStop =
        sj.revolute ? hingeStop(limits.lower, sj.q0, true) : sliderStop(limits.lower, sj.q0, true);
    sj.hiStop = sj.revolute ? hingeStop(limits.upper, sj.q0, false)
                            : sliderStop(limits.upper, sj.q0, false);
  }
  return sj;
}

/// How one free DOF of a constraint maps onto its ODE joint: the parameter setter, the
/// position getter and the parameter group (dParamLoStop + group * dParamGroup).
struct OdeAxis {
  void (*setParam)(dJointID, int, dReal);
  dReal (*position)(dJointID);
  int group;
};

/// The ODE axes of a constraint type's free DOF, in dynamics::Constraint::limits order (linear
/// first). RobWorkSim's ODE engine (ODEConstraint::setLoStop) sets stops for DOF 0 and 1 only,
/// in ODE's groups 0 and 1; for a PrismaticUniversal those are the universal axes, while here
/// its first DOF is the translation (ODE's group 2) and all three get stops.
std::vector<OdeAxis> odeAxes(dynamics::ConstraintType type) {
  using T = dynamics::ConstraintType;
  switch (type) {
    case T::kPrismatic:
      return {{dJointSetSliderParam, dJointGetSliderPosition, 0}};
    case T::kRevolute:
      return {{dJointSetHingeParam, dJointGetHingeAngle, 0}};
    case T::kUniversal:
      return {{dJointSetUniversalParam, dJointGetUniversalAngle1, 0},
              {dJointSetUniversalParam, dJointGetUniversalAngle2, 1}};
    case T::kPiston:
      return {{dJointSetPistonParam, dJointGetPistonPosition, 0},
              {dJointSetPistonParam, dJointGetPistonAngle, 1}};
    case T::kPrismaticRotoid:
      return {{dJointSetPRParam, dJointGetPRPosition, 0}, {dJointSetPRParam, dJointGetPRAngle, 1}};
    case T::kPrismaticUniversal:
      return {{dJointSetPUParam, dJointGetPUPosition, 2},
              {dJointSetPUParam, dJointGetPUAngle1, 0},
              {dJointSetPUParam, dJointGetPUAngle2, 1}};
    case T::kFixed:
    case T::kSpherical:
    case T::kFree:
      break;
  }
  return {};
}

/// Rows of a constraint's ODE joint without stops.
std::size_t baseRows(dynamics::ConstraintType type) {
  using T = dynamics::ConstraintType;
  switch (type) {
    case T::kFixed:
      return 6;
    case T::kPrismatic:
    case T::kRevolute:
      return 5;
    case T::kUniversal:
    case T::kPiston:
    case T::kPrismaticRotoid:
      return 4;
    case T::kSpherical:
    case T::kPrismaticUniversal:
      return 3;
    case T::kFree:
      break;
  }
  return 0;
}

/// Creates the ODE joint of a constraint between ODE bodies `first` and `second` (either may be
/// null, not both), with the axes of the constraint frame X_W_c (RobWorkSim's
/// ODEConstraint::createJoint).
dJointID createConstraintJoint(dWorldID world, dynamics::ConstraintType type, dBodyID first,
                               dBodyID second, const Transform3D& X_W_c) {
  using T = dynamics::ConstraintType;
  const Vector3D p = X_W_c.translation();
  const Vector3D x = X_W_c.linear().col(0);
  const Vector3D y = X_W_c.linear().col(1);
  const Vector3D z = X_W_c.linear().col(2);
  dJointID j = nullptr;
  switch (type) {
    case T::kFixed:
      j = dJointCreateFixed(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetFixed(j);
      break;
    case T::kPrismatic:
      j = dJointCreateSlider(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetSliderAxis(j, z.x(), z.y(), z.z());
      break;
    case T::kRevolute:
      j = dJointCreateHinge(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetHingeAnchor(j, p.x(), p.y(), p.z());
      dJointSetHingeAxis(j, z.x(), z.y(), z.z());
      break;
    case T::kUniversal:
      j = dJointCreateUniversal(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetUniversalAnchor(j, p.x(), p.y(), p.z());
      dJointSetUniversalAxis1(j, x.x(), x.y(), x.z());
      dJointSetUniversalAxis2(j, y.x(), y.y(), y.z());
      break;
    case T::kSpherical:
      j = dJointCreateBall(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetBallAnchor(j, p.x(), p.y(), p.z());
      break;
    case T::kPiston:
      j = dJointCreatePiston(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetPistonAnchor(j, p.x(), p.y(), p.z());
      dJointSetPistonAxis(j, z.x(), z.y(), z.z());
      break;
    case T::kPrismaticRotoid:
      j = dJointCreatePR(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetPRAnchor(j, p.x(), p.y(), p.z());
      dJointSetPRAxis1(j, z.x(), z.y(), z.z());
      dJointSetPRAxis2(j, x.x(), x.y(), x.z());
      break;
    case T::kPrismaticUniversal:
      j = dJointCreatePU(world, nullptr);
      dJointAttach(j, first, second);
      dJointSetPUAnchor(j, p.x(), p.y(), p.z());
      dJointSetPUAxis1(j, x.x(), x.y(), x.z());
      dJointSetPUAxis2(j, y.x(), y.y(), y.z());
      dJointSetPUAxis3(j, z.x(), z.y(), z.z());
      break;
    case T::kFree:
      break;
  }
  return j;
}

}  // namespace

Transform3D odePose(dBodyID body) {
  const dReal* p = dBodyGetPosition(body);
  const dReal* q = dBodyGetQuaternion(body);
  Transform3D X = Transform3D::Identity();
  X.linear() = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  X.translation() = Vector3D(p[0], p[1], p[2]);
  return X;
}

OdeWorld::OdeWorld(const dynamics::DynamicWorkCell& dwc, const rw::kinematics::State& state,
                   const SimulatorOptions& options, double objectMassScale, bool gravity) {
  world_ = dWorldCreate();
  // ODE's default threading implementation is one global object; worlds stepped in parallel
  // threads must each have their own, or their islands get mixed up.
  threading_ = dThreadingAllocateSelfThreadedImplementation();
  dWorldSetStepThreadingImplementation(world_, dThreadingImplementationGetFunctions(threading_),
                                       threading_);
  contactGroup_ = dJointGroupCreate(0);
  const Vector3D g = gravity ? dwc.gravity() : Vector3D::Zero();
  dWorldSetGravity(world_, g.x(), g.y(), g.z());
  dWorldSetCFM(world_, options.worldCfm);
  dWorldSetERP(world_, options.worldErp);
  dWorldSetContactSurfaceLayer(world_, options.contactSurfaceLayer);
  dWorldSetContactMaxCorrectingVel(world_, options.maxCorrectingVelocity);
  dWorldSetAutoDisableFlag(world_, 0);
  try {
    createBodies(dwc, state, objectMassScale);
    createDevices(dwc, state);
    createConstraints(dwc, state);
  } catch (...) {
    destroy();
    throw;
  }
}

OdeWorld::~OdeWorld() { destroy(); }

void OdeWorld::destroy() {
  if (poisoned_) return;
  dJointGroupDestroy(contactGroup_);
  dWorldSetStepThreadingImplementation(world_, nullptr, nullptr);
  dWorldDestroy(world_);  // also destroys the bodies and the device joints
  dThreadingFreeImplementation(threading_);
}

void OdeWorld::createBodies(const dynamics::DynamicWorkCell& dwc,
                            const rw::kinematics::State& state, double objectMassScale) {
  const auto& tree = dwc.workcell().frames();
  const rw::kinematics::FKTable fk(tree, state);
  bodies_.resize(dwc.bodies().size());
  for (std::size_t i = 0; i < dwc.bodies().size(); ++i) {
    const dynamics::Body& body = dwc.bodies()[i];
    SimBody& sim = bodies_[i];
    sim.bodyId = dynamics::BodyId(i);
    sim.kind = body.kind;
    sim.movableFrame = tree.frame(body.frame).type() == FrameType::kMovable;
    const Transform3D& X_W_frame = fk.worldTransform(body.frame);
    sim.startPosition = X_W_frame.translation();
    if (body.kind == dynamics::BodyKind::kFixed) {
      sim.X_W_fixed = X_W_frame;
      continue;
    }
    sim.id = dBodyCreate(world_);
    if (body.kind == dynamics::BodyKind::kRigid) {
      checkMass(body);
      sim.cog = body.mass.cog;
      double mass = body.mass.mass;
      Eigen::Matrix3d I = body.mass.inertia;
      // Only a real scale touches the values: the identity gives ODE the dwc's bit for bit.
      if (objectMassScale != 1.0 && trial::isVariedObject(body)) {
        mass *= objectMassScale;
        I *= objectMassScale;
      }
      dMass m;
      dMassSetParameters(&m, mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
      dBodySetMass(sim.id, &m);
      setDamping(sim.id, body);
    } else {
      dBodySetKinematic(sim.id);
    }
    setOdePose(sim.id, X_W_frame * Eigen::Translation3d(sim.cog));
  }
}

void OdeWorld::createDevices(const dynamics::DynamicWorkCell& dwc,
                             const rw::kinematics::State& state) {
  const auto& tree = dwc.workcell().frames();
  const rw::kinematics::FKTable fk(tree, state);
  devices_.resize(dwc.devices().size());
  for (std::size_t d = 0; d < dwc.devices().size(); ++d) {
    const dynamics::RigidDevice& rd = dwc.devices()[d];
    const auto& joints = rd.device->joints();
    if (rd.linkBodies.size() != joints.size() || rd.forceLimits.size() != joints.size()) {
      throw std::invalid_argument("rigid device " + rd.device->name() +
                                  ": link bodies or force limits do not match its joints");
    }
    SimDevice& sim = devices_[d];
    sim.active.assign(static_cast<std::size_t>(rd.device->dof()), 0);
    for (std::size_t j = 0; j < joints.size(); ++j) {
      sim.joints.push_back(describeJoint(tree, rd, j, state));
      const SimJoint& sj = sim.joints.back();
      if (sj.activeIndex >= 0) sim.active[static_cast<std::size_t>(sj.activeIndex)] = j;
      const dynamics::BodyId link = rd.linkBodies[j];
      if (!link.valid()) continue;  // no link body: the joint is held at its current value
      if (bodies_[link.index()].kind != dynamics::BodyKind::kRigid) {
        throw std::invalid_argument("joint " + tree.frame(joints[j]).name() +
                                    ": its link body must be rigid");
      }
      const dynamics::BodyId parent = dwc.bodyAbove(joints[j]);
      attachJoint(sim.joints.back(), link, parent, fk.worldTransform(joints[j]),
                  tree.frame(joints[j]).isPassive());
    }
    for (const SimJoint& sj : sim.joints) {
      if (sj.owner) sim.joints[*sj.owner].leads = true;
    }
    closeLoops(dwc, rd, fk, sim);
  }
}

void OdeWorld::createConstraints(const dynamics::DynamicWorkCell& dwc,
                                 const rw::kinematics::State& state) {
  const rw::kinematics::FKTable fk(dwc.workcell().frames(), state);
  constraints_.reserve(dwc.constraints().size());
  for (std::size_t i = 0; i < dwc.constraints().size(); ++i) {
    const dynamics::Constraint& c = dwc.constraints()[i];
    if (c.spring) {
      throw std::invalid_argument("constraint " + c.name +
                                  ": springs on constraints are not simulated yet");
    }
    SimConstraint sim;
    sim.index = i;
    sim.type = c.type;
    const dBodyID parent = bodies_[c.parent.index()].id;
    const dBodyID child = bodies_[c.child.index()].id;
    const Transform3D X_W_c = fk.worldTransform(dwc.body(c.parent).frame) * c.X_parent_constraint;
    dBodyID first = parent;
    if (first == nullptr && c.type != dynamics::ConstraintType::kFree) {
      if (staticAnchor_ == nullptr) {
        staticAnchor_ = dBodyCreate(world_);
        dBodySetKinematic(staticAnchor_);
      }
      first = staticAnchor_;
    }
    sim.id = createConstraintJoint(world_, c.type, first, child, X_W_c);
    const std::vector<OdeAxis> axes = odeAxes(c.type);
    if (!c.limits.empty() && c.limits.size() != axes.size()) {
      throw std::invalid_argument("constraint " + c.name + ": limits do not match its free DOF");
    }
    for (std::size_t k = 0; k < c.limits.size(); ++k) {
      // ODE's coordinate is minus the child's motion relative to the parent.
      const double lo = -c.limits[k].high;
      const double hi = -c.limits[k].low;
      const int group = axes[k].group * dParamGroup;
      axes[k].setParam(sim.id, dParamLoStop + group, std::isfinite(lo) ? lo : -dInfinity);
      axes[k].setParam(sim.id, dParamHiStop + group, std::isfinite(hi) ? hi : dInfinity);
      sim.odeStops.emplace_back(lo, hi);
    }
    constraints_.push_back(std::move(sim));
  }
}

std::size_t OdeWorld::constraintRows(const SimConstraint& c) const {
  std::size_t rows = baseRows(c.type);
  if (c.odeStops.empty()) return rows;
  const std::vector<OdeAxis> axes = odeAxes(c.type);
  for (std::size_t k = 0; k < axes.size(); ++k) {
    const double pos = axes[k].position(c.id);
    if (pos <= c.odeStops[k].first || pos >= c.odeStops[k].second) ++rows;
  }
  return rows;
}

void OdeWorld::closeLoops(const dynamics::DynamicWorkCell& dwc, const dynamics::RigidDevice& rd,
                          const rw::kinematics::FKTable& fk, SimDevice& sim) {
  const auto& tree = dwc.workcell().frames();
  const auto& joints = rd.device->joints();
  for (const dynamics::LoopClosure& c : rd.loopClosures) {
    if (bodies_[c.child.index()].kind != dynamics::BodyKind::kRigid) {
      throw std::invalid_argument("rigid device " + rd.device->name() + ": junction " +
                                  std::to_string(c.junction) + " closes on body " +
                                  dwc.body(c.child).name + ", which is not rigid");
    }
    if (c.joint.valid()) {
      const auto j = static_cast<std::size_t>(std::find(joints.begin(), joints.end(), c.joint) -
                                              joints.begin());
      attachJoint(sim.joints[j], c.child, c.parent, fk.worldTransform(c.joint),
                  tree.frame(c.joint).isPassive());
      continue;
    }
    const dJointID weld = dJointCreateFixed(world_, nullptr);
    dJointAttach(weld, bodies_[c.child.index()].id, bodies_[c.parent.index()].id);
    dJointSetFixed(weld);
    sim.welds.push_back(weld);
  }
}

void OdeWorld::attachJoint(SimJoint& sj, dynamics::BodyId link, dynamics::BodyId parent,
                           const Transform3D& X_W_joint, bool passive) {
  const dBodyID linkId = bodies_[link.index()].id;
  const dBodyID parentId = parent.valid() ? bodies_[parent.index()].id : nullptr;
  const Vector3D p = X_W_joint.translation();
  const Vector3D z = X_W_joint.linear().col(2);
  if (sj.revolute) {
    sj.id = dJointCreateHinge(world_, nullptr);
    dJointAttach(sj.id, linkId, parentId);
    dJointSetHingeAnchor(sj.id, p.x(), p.y(), p.z());
    dJointSetHingeAxis(sj.id, z.x(), z.y(), z.z());
  } else {
    sj.id = dJointCreateSlider(world_, nullptr);
    dJointAttach(sj.id, linkId, parentId);
    dJointSetSliderAxis(sj.id, z.x(), z.y(), z.z());
  }
  setMotor(sj, 0.0, passive ? 0.0 : sj.forceLimit);
}

Transform3D OdeWorld::framePose(const SimBody& body) const {
  if (body.id == nullptr) return body.X_W_fixed;
  return odePose(body.id) * Eigen::Translation3d(-body.cog);
}

double OdeWorld::jointPosition(const SimJoint& joint) const {
  if (joint.id == nullptr) return joint.q0;
  if (!joint.revolute) return joint.q0 + dJointGetSliderPosition(joint.id);
  const double raw = dJointGetHingeAngle(joint.id);
  const double turns = std::round((joint.lastRelative - raw) / (2.0 * kPi));
  return joint.q0 + raw + 2.0 * kPi * turns;
}

void OdeWorld::trackJoints() {
  for (auto& device : devices_) {
    for (auto& joint : device.joints) {
      joint.lastRelative = jointPosition(joint) - joint.q0;
      if (!joint.leads) continue;  // only a dependent joint's owner needs its speeds
      const double v = jointVelocity(joint);
      joint.meanVelocity = 0.5 * (joint.lastVelocity + v);
      joint.lastVelocity = v;
    }
  }
}

double OdeWorld::jointVelocity(const SimJoint& joint) const {
  if (joint.id == nullptr) return 0.0;
  return joint.revolute ? dJointGetHingeAngleRate(joint.id) : dJointGetSliderPositionRate(joint.id);
}

std::size_t OdeWorld::setMotor(const SimJoint& joint, double velocity, double forceLimit) const {
  if (joint.id == nullptr) return 0;
  // ODE's own (wrapped) joint coordinate, which its stops refer to.
  const double pos =
      joint.revolute ? dJointGetHingeAngle(joint.id) : dJointGetSliderPosition(joint.id);
  // Release a stop for this step when the motor drives the joint away from it (unless the
  // joint has sunk clearly past the stop, which the stop must then correct).
  const bool leaveLow = velocity > 0.0 && forceLimit > 0.0 && pos <= joint.loStop &&
                        pos >= joint.loStop - kStopRelease;
  const bool leaveHigh = velocity < 0.0 && forceLimit > 0.0 && pos >= joint.hiStop &&
                         pos <= joint.hiStop + kStopRelease;
  const double lo = leaveLow ? -dInfinity : joint.loStop;
  const double hi = leaveHigh ? dInfinity : joint.hiStop;
  if (joint.revolute) {
    dJointSetHingeParam(joint.id, dParamLoStop, lo);
    dJointSetHingeParam(joint.id, dParamHiStop, hi);
    dJointSetHingeParam(joint.id, dParamVel, velocity);
    dJointSetHingeParam(joint.id, dParamFMax, forceLimit);
  } else {
    dJointSetSliderParam(joint.id, dParamLoStop, lo);
    dJointSetSliderParam(joint.id, dParamHiStop, hi);
    dJointSetSliderParam(joint.id, dParamVel, velocity);
    dJointSetSliderParam(joint.id, dParamFMax, forceLimit);
  }
  const bool onStop = lo <= hi && (pos <= lo || pos >= hi);
  return 5 + (forceLimit > 0.0 || onStop ? 1 : 0);
}

std::size_t OdeWorld::constraintRows(const SimJoint& joint) const {
  if (joint.id == nullptr) return 0;
  const auto param = [&](int which) {
    return joint.revolute ? dJointGetHingeParam(joint.id, which)
                          : dJointGetSliderParam(joint.id, which);
  };
  const double pos =
      joint.revolute ? dJointGetHingeAngle(joint.id) : dJointGetSliderPosition(joint.id);
  const double lo = param(dParamLoStop);
  const double hi = param(dParamHiStop);
  const bool onStop = lo <= hi && (pos <= lo || pos >= hi);
  return 5 + (param(dParamFMax) > 0.0 || onStop ? 1 : 0);
}

}  // namespace rwsim::simulator::detail
