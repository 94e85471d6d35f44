#include "rwsim/simulator/simulator.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/simulator/detail/ode_model.hpp"
#include "rwsim/simulator/detail/ode_runtime.hpp"

namespace rwsim::simulator {

namespace {

using detail::SimBody;
using detail::SimJoint;
using dynamics::BodyId;
using dynamics::BodyKind;
using dynamics::DeviceId;
using rw::math::Transform3D;
using rw::math::Vector3D;

// Below this tangential slip speed (m/s) a contact counts as sticking when choosing its first
// friction direction.
constexpr double kStickSpeed = 1e-4;
// Relative normal speed (m/s) above which restitution applies (RobWork: 1e-5).
constexpr double kBounceVelocity = 1e-5;

Vector3D toVector(const dReal* v) { return Vector3D(v[0], v[1], v[2]); }

bool finite3(const dReal* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// Velocity of the material point at `p` (world) of an ODE body; zero for static bodies.
Vector3D pointVelocity(dBodyID id, const Vector3D& p) {
  if (id == nullptr) return Vector3D::Zero();
  dVector3 v;
  dBodyGetPointVel(id, p.x(), p.y(), p.z(), v);
  return toVector(v);
}

}  // namespace

struct Simulator::Impl {
  const dynamics::DynamicWorkCell* dwc = nullptr;
  SimulatorOptions options;
  trial::PhysicsVariation variation;
  std::shared_ptr<const contacts::ContactDetector> detector;
  std::unique_ptr<detail::OdeWorld> ode;
  rw::kinematics::State state;
  double time = 0.0;
  StepStatus status = StepStatus::kOk;
  std::string failureDetail;
  std::string odeMessages;
  // Per body pair (row-major, bodies x bodies): friction and restitution.
  std::vector<double> mu;
  std::vector<double> restitution;
  // Bodies with Movable frames in frame order (parents before children).
  std::vector<BodyId> movableOrder;
  std::vector<Transform3D> poses;
  std::vector<contacts::BodyContact> geometric;
  std::vector<dJointFeedback> feedback;
  std::vector<dJointID> contactJoints;
  std::vector<SolvedBodyContact> solved;
  // Body pairs joined by a device joint (sorted), and whether the detector checks any of them
  // (one made by the Simulator excludes them up front; a caller's detector may not).
  std::vector<std::pair<BodyId, BodyId>> connected;
  bool filterConnected = false;
  // Rows of the last step (see lastStepRows()).
  std::size_t rows = 0;
  // options.stepMethod decided once.
  bool quickStep = false;
  // Last step's tangential contact force per body pair, to orient friction pyramids.
  std::map<std::pair<BodyId, BodyId>, Vector3D> lastTangentialForce;

  void init(const dynamics::DynamicWorkCell& cell);
  double pairValue(const std::vector<double>& table, BodyId a, BodyId b) const {
    return table[a.index() * dwc->bodies().size() + b.index()];
  }
  const SimBody& body(BodyId id) const;
  detail::SimDevice& device(DeviceId id) const;
  bool commandsFinite();
  void stepOnce();
  void createContactJoints();
  Vector3D frictionDirection(const SimBody& a, const SimBody& b, const contacts::ContactPoint& p,
                             const Vector3D& lastForce) const;
  void driveMotors();
  void driveKinematicBodies();
  void collectForces();
  void checkBodies();
  void updateState();
  void fail(StepStatus s, std::string detail) {
    status = s;
    failureDetail = std::move(detail);
  }
};

void Simulator::Impl::init(const dynamics::DynamicWorkCell& cell) {
  dwc = &cell;
  const auto& bodies = cell.bodies();
  const std::size_t n = bodies.size();
  mu.assign(n * n, 0.0);
  restitution.assign(n * n, 0.0);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      mu[a * n + b] = cell.materials().mu(bodies[a].material, bodies[b].material);
      // Only a real scale touches the value: the identity keeps the dwc's mu bit for bit.
      if (variation.frictionScale != 1.0) mu[a * n + b] *= variation.frictionScale;
      restitution[a * n + b] =
          cell.materials().restitution(bodies[a].objectType, bodies[b].objectType);
    }
  }
  const auto& tree = cell.workcell().frames();
  for (std::size_t b = 0; b < n; ++b) {
    if (tree.frame(bodies[b].frame).type() == rw::kinematics::FrameType::kMovable &&
        bodies[b].kind != BodyKind::kFixed) {
      movableOrder.push_back(BodyId(b));
    }
  }
  std::sort(movableOrder.begin(), movableOrder.end(),
            [&](BodyId x, BodyId y) { return cell.body(x).frame < cell.body(y).frame; });
}

const SimBody& Simulator::Impl::body(BodyId id) const {
  if (!id.valid() || id.index() >= ode->bodies().size()) {
    throw std::out_of_range("Simulator: no body " + dynamics::toString(id));
  }
  return ode->bodies()[id.index()];
}

detail::SimDevice& Simulator::Impl::device(DeviceId id) const {
  if (!id.valid() || id.index() >= ode->devices().size()) {
    throw std::out_of_range("Simulator: no device " + dynamics::toString(id));
  }
  return ode->devices()[id.index()];
}

bool Simulator::Impl::commandsFinite() {
  for (const SimBody& b : ode->bodies()) {
    if (!b.commandLinear.allFinite() || !b.commandAngular.allFinite()) {
      fail(StepStatus::kNumericalFailure,
           "body " + dwc->body(b.bodyId).name + ": commanded velocity is not finite");
      return false;
    }
  }
  for (const auto& dev : ode->devices()) {
    for (const SimJoint& j : dev.joints) {
      if (!std::isfinite(j.velocityTarget) || !std::isfinite(j.forceLimit)) {
        fail(StepStatus::kNumericalFailure, "joint " +
                                                dwc->workcell().frames().frame(j.frame).name() +
                                                ": motor target or force limit is not finite");
        return false;
      }
    }
  }
  return true;
}

void Simulator::Impl::stepOnce() {
  // Non-finite commands would trip ODE's own assertions inside the step; stop before.
  if (!commandsFinite()) return;
  const auto& sims = ode->bodies();
  poses.resize(sims.size());
  for (std::size_t i = 0; i < sims.size(); ++i) poses[i] = ode->framePose(sims[i]);
  detector->detect(poses, geometric);
  // Bodies joined by a device joint never touch each other: model geometry overlaps at joints
  // (RobWork's SDH2 hulls by 2.7 cm), as MuJoCo filters parent-child pairs.
  if (filterConnected) {
    std::erase_if(geometric, [&](const contacts::BodyContact& bc) {
      const std::pair<BodyId, BodyId> key(std::min(bc.bodyA, bc.bodyB),
                                          std::max(bc.bodyA, bc.bodyB));
      return std::binary_search(connected.begin(), connected.end(), key);
    });
  }
  createContactJoints();
  driveMotors();
  driveKinematicBodies();
  if (quickStep) {
    dWorldQuickStep(ode->world(), options.timeStep);
  } else {
    dWorldStep(ode->world(), options.timeStep);
  }
  collectForces();
  checkBodies();
  time += options.timeStep;
  if (status == StepStatus::kOk) updateState();
}

Vector3D Simulator::Impl::frictionDirection(const SimBody& a, const SimBody& b,
                                            const contacts::ContactPoint& p,
                                            const Vector3D& lastForce) const {
  // ODE's Approx1 friction is a pyramid; aligning its first axis with the slip (or, when
  // sticking, with last step's friction force) makes it exact where it matters.
  const Vector3D& n = p.normal;
  Vector3D slip = pointVelocity(b.id, p.position) - pointVelocity(a.id, p.position);
  slip -= n * n.dot(slip);
  if (slip.norm() > kStickSpeed) return slip.normalized();
  Vector3D f = lastForce - n * n.dot(lastForce);
  if (f.norm() > 1e-9) return f.normalized();
  return Vector3D::Zero();
}

void Simulator::Impl::createContactJoints() {
  dJointGroupEmpty(ode->contactGroup());
  rows = 0;
  std::size_t total = 0;
  for (const auto& bc : geometric) total += bc.points.size();
  feedback.assign(total, dJointFeedback{});
  contactJoints.assign(total, nullptr);
  std::size_t slot = 0;
  for (const auto& bc : geometric) {
    const SimBody& a = body(bc.bodyA);
    const SimBody& b = body(bc.bodyB);
    const bool dynamic = a.kind == BodyKind::kRigid || b.kind == BodyKind::kRigid;
    const double pairMu = pairValue(mu, bc.bodyA, bc.bodyB);
    const double cr = pairValue(restitution, bc.bodyA, bc.bodyB);
    const auto last = lastTangentialForce.find({bc.bodyA, bc.bodyB});
    const Vector3D lastForce =
        last == lastTangentialForce.end() ? Vector3D::Zero() : Vector3D(last->second);
    for (const auto& p : bc.points) {
      const std::size_t k = slot++;
      if (!dynamic) continue;
      dContact c{};
      c.surface.mode = dContactApprox1 | dContactSoftCFM | dContactSoftERP;
      c.surface.mu = pairMu;
      c.surface.soft_cfm = options.contactCfm;
      c.surface.soft_erp = options.contactErp;
      double depth = p.depth;
      if (depth < 0.0) {
        // Speculative contact: the gap may close within this step, no further.
        c.surface.mode |= dContactMotionN;
        c.surface.motionN = depth / options.timeStep;
        depth = 0.0;
      }
      if (cr > 0.0) {
        c.surface.mode |= dContactBounce;
        c.surface.bounce = cr;
        c.surface.bounce_vel = kBounceVelocity;
      }
      const Vector3D dir = frictionDirection(a, b, p, lastForce);
      if (dir.squaredNorm() > 0.0) {
        c.surface.mode |= dContactFDir1;
        c.fdir1[0] = dir.x();
        c.fdir1[1] = dir.y();
        c.fdir1[2] = dir.z();
      }
      for (int i = 0; i < 3; ++i) {
        c.geom.pos[i] = p.position[i];
        c.geom.normal[i] = p.normal[i];  // ODE pushes its first body along the normal: B
      }
      c.geom.depth = depth;
      rows += pairMu > 0.0 ? 3 : 1;
      const dJointID j = dJointCreateContact(ode->world(), ode->contactGroup(), &c);
      dJointAttach(j, b.id, a.id);
      dJointSetFeedback(j, &feedback[k]);
      contactJoints[k] = j;
    }
  }
}

void Simulator::Impl::driveMotors() {
  for (const detail::SimConstraint& c : ode->constraints()) rows += ode->constraintRows(c);
  for (auto& dev : ode->devices()) {
    rows += 6 * dev.welds.size();
    for (const SimJoint& j : dev.joints) {
      if (j.id == nullptr) continue;
      if (j.owner) {
        const SimJoint& o = dev.joints[*j.owner];
        // Follow the owner: its motion over the step (feed-forward) plus this joint's whole
        // error. The feed-forward is the owner's mean speed over the last two steps, not its
        // latest speed: the motor's torque also acts on the owner's link, and when the owner's
        // link or this one presses on something (a linked finger closing on an object) feeding
        // the latest speed forward locks the two joints into a period-2 oscillation (the owner
        // moving +-0.03 rad every step, +-6 rad/s) that never lets the fingers come to rest
        // (issue 20; tests/rwsim/simulator/linked_finger_test.cpp). The mean over two steps has
        // no component at that period, and lags smooth motion by only its change over a step.
        const double err = j.gain * ode->jointPosition(o) + j.offset - ode->jointPosition(j);
        const double v = j.gain * o.meanVelocity + err / options.timeStep;
        rows += ode->setMotor(j, v, j.forceLimit);
      } else if (j.activeIndex >= 0) {
        rows += ode->setMotor(j, j.velocityTarget, j.forceLimit);
      } else {
        rows += ode->constraintRows(j);  // passive: as created
      }
    }
  }
}

void Simulator::Impl::driveKinematicBodies() {
  for (const SimBody& b : ode->bodies()) {
    if (b.kind != BodyKind::kKinematic) continue;
    const Transform3D X = detail::odePose(b.id);
    const Vector3D v = b.commandLinear + b.commandAngular.cross(X.linear() * b.cog);
    dBodySetLinearVel(b.id, v.x(), v.y(), v.z());
    dBodySetAngularVel(b.id, b.commandAngular.x(), b.commandAngular.y(), b.commandAngular.z());
  }
}

void Simulator::Impl::collectForces() {
  solved.clear();
  lastTangentialForce.clear();
  std::size_t slot = 0;
  for (const auto& bc : geometric) {
    SolvedBodyContact out;
    out.bodyA = bc.bodyA;
    out.bodyB = bc.bodyB;
    const bool bIsFirst = body(bc.bodyB).id != nullptr;
    Vector3D tangential = Vector3D::Zero();
    for (const auto& p : bc.points) {
      const std::size_t k = slot++;
      SolvedContact sc;
      sc.point = p;
      if (contactJoints[k] != nullptr) {
        // feedback.f1 is the force on ODE's first body: B, or A when B is static.
        const Vector3D f1 = toVector(feedback[k].f1);
        sc.force = bIsFirst ? f1 : Vector3D(-f1);
        tangential += sc.force - p.normal * p.normal.dot(sc.force);
      }
      out.points.push_back(sc);
    }
    lastTangentialForce[{bc.bodyA, bc.bodyB}] = tangential;
    solved.push_back(std::move(out));
  }
}

void Simulator::Impl::checkBodies() {
  const auto& cells = dwc->bodies();
  for (const SimBody& b : ode->bodies()) {
    if (b.id == nullptr) continue;
    const std::string& name = cells[b.bodyId.index()].name;
    const dReal* q = dBodyGetQuaternion(b.id);
    if (!finite3(dBodyGetPosition(b.id)) || !finite3(q) || !std::isfinite(q[3]) ||
        !finite3(dBodyGetLinearVel(b.id)) || !finite3(dBodyGetAngularVel(b.id))) {
      fail(StepStatus::kNumericalFailure, "body " + name + ": pose or velocity is not finite");
      return;
    }
    if (b.kind != BodyKind::kRigid) continue;
    const double speed = toVector(dBodyGetLinearVel(b.id)).norm();
    if (speed > options.maxSpeed) {
      fail(StepStatus::kRunaway,
           "body " + name + ": speed " + std::to_string(speed) + " m/s exceeds maxSpeed");
      return;
    }
    const double moved = (ode->framePose(b).translation() - b.startPosition).norm();
    if (moved > options.escapeDistance) {
      fail(StepStatus::kRunaway,
           "body " + name + ": moved " + std::to_string(moved) + " m, beyond escapeDistance");
      return;
    }
  }
}

void Simulator::Impl::updateState() {
  ode->trackJoints();
  const auto& tree = dwc->workcell().frames();
  for (const auto& dev : ode->devices()) {
    for (const SimJoint& j : dev.joints) {
      if (j.owner || j.id == nullptr) continue;
      tree.frame(j.frame).setJointValue(state, ode->jointPosition(j));
    }
  }
  for (const BodyId id : movableOrder) {
    const auto& frame = tree.frame(dwc->body(id).frame);
    const Transform3D X_W_frame = ode->framePose(body(id));
    const Transform3D X_W_parent =
        rw::kinematics::worldTransform(tree, state, state.parentOf(frame.id()));
    frame.setMovableTransform(state, X_W_parent.inverse() * X_W_frame);
  }
}

Simulator::Simulator(const dynamics::DynamicWorkCell& dwc, SimulatorOptions options,
                     const trial::PhysicsVariation& variation)
    : Simulator(dwc,
                std::make_shared<contacts::ContactDetector>(dwc, options.contacts,
                                                            dynamics::jointConnectedBodyPairs(dwc)),
                options, variation) {}

Simulator::Simulator(const dynamics::DynamicWorkCell& dwc,
                     std::shared_ptr<const contacts::ContactDetector> detector,
                     SimulatorOptions options, const trial::PhysicsVariation& variation)
    : impl_(std::make_unique<Impl>()) {
  if (!detector) throw std::invalid_argument("Simulator: the contact detector is null");
  variation.check();
  impl_->variation = variation;
  if (!(options.timeStep > 0.0) || !std::isfinite(options.timeStep)) {
    throw std::invalid_argument("Simulator: the time step must be > 0");
  }
  detail::prepareOdeForThisThread();
  options.contacts = detector->options();
  impl_->options = std::move(options);
  impl_->quickStep = impl_->options.stepMethod == "WorldQuickStep";
  impl_->connected = dynamics::jointConnectedBodyPairs(dwc);
  for (const auto& pair : detector->candidatePairs()) {
    const std::pair<BodyId, BodyId> key(std::min(pair.first, pair.second),
                                        std::max(pair.first, pair.second));
    if (std::binary_search(impl_->connected.begin(), impl_->connected.end(), key)) {
      impl_->filterConnected = true;
    }
  }
  impl_->detector = std::move(detector);
  impl_->init(dwc);
  reset(dwc.workcell().defaultState());
}

Simulator::~Simulator() = default;

void Simulator::reset(const rw::kinematics::State& state) {
  detail::prepareOdeForThisThread();
  impl_->ode.reset();
  impl_->ode = std::make_unique<detail::OdeWorld>(*impl_->dwc, state, impl_->options,
                                                  impl_->variation.objectMassScale,
                                                  impl_->variation.gravity);
  impl_->state = state;
  impl_->time = 0.0;
  impl_->status = StepStatus::kOk;
  impl_->failureDetail.clear();
  impl_->odeMessages.clear();
  impl_->geometric.clear();
  impl_->solved.clear();
  impl_->lastTangentialForce.clear();
  impl_->rows = 0;
  detail::takeOdeMessages();
}

StepStatus Simulator::step() {
  if (impl_->status != StepStatus::kOk) return impl_->status;
  detail::prepareOdeForThisThread();
  try {
    impl_->stepOnce();
  } catch (const detail::OdeFatalError& e) {
    impl_->ode->poison();
    impl_->fail(StepStatus::kNumericalFailure, e.what());
  }
  const std::string messages = detail::takeOdeMessages();
  if (!messages.empty() && impl_->odeMessages.size() < 4096) {
    impl_->odeMessages += (impl_->odeMessages.empty() ? "" : "; ") + messages;
  }
  return impl_->status;
}

const std::string& Simulator::engineMessages() const { return impl_->odeMessages; }

const std::string& Simulator::failureDetail() const { return impl_->failureDetail; }

double Simulator::time() const { return impl_->time; }

double Simulator::timeStep() const { return impl_->options.timeStep; }

const rw::kinematics::State& Simulator::state() const { return impl_->state; }

Transform3D Simulator::bodyPose(BodyId body) const {
  return impl_->ode->framePose(impl_->body(body));
}

Vector3D Simulator::bodyLinearVelocity(BodyId body) const {
  const SimBody& b = impl_->body(body);
  if (b.id == nullptr) return Vector3D::Zero();
  return pointVelocity(b.id, bodyPose(body).translation());
}

Vector3D Simulator::bodyAngularVelocity(BodyId body) const {
  const SimBody& b = impl_->body(body);
  if (b.id == nullptr) return Vector3D::Zero();
  return toVector(dBodyGetAngularVel(b.id));
}

void Simulator::setKinematicVelocity(BodyId body, const Vector3D& linear, const Vector3D& angular) {
  const SimBody& b = impl_->body(body);
  if (b.kind != BodyKind::kKinematic) {
    throw std::invalid_argument("Simulator: body " + impl_->dwc->body(body).name +
                                " is not kinematic");
  }
  auto& sim = impl_->ode->bodies()[body.index()];
  sim.commandLinear = linear;
  sim.commandAngular = angular;
}

rw::math::Q Simulator::jointPositions(DeviceId device) const {
  const auto& dev = impl_->device(device);
  rw::math::Q q(static_cast<Eigen::Index>(dev.active.size()));
  for (std::size_t i = 0; i < dev.active.size(); ++i) {
    q[static_cast<Eigen::Index>(i)] = impl_->ode->jointPosition(dev.joints[dev.active[i]]);
  }
  return q;
}

rw::math::Q Simulator::jointVelocities(DeviceId device) const {
  const auto& dev = impl_->device(device);
  rw::math::Q v(static_cast<Eigen::Index>(dev.active.size()));
  for (std::size_t i = 0; i < dev.active.size(); ++i) {
    v[static_cast<Eigen::Index>(i)] = impl_->ode->jointVelocity(dev.joints[dev.active[i]]);
  }
  return v;
}

void Simulator::setMotorVelocityTargets(DeviceId device, const rw::math::Q& velocities) {
  auto& dev = impl_->device(device);
  if (static_cast<std::size_t>(velocities.size()) != dev.active.size()) {
    throw std::invalid_argument("Simulator: " + std::to_string(velocities.size()) +
                                " velocity targets for " + std::to_string(dev.active.size()) +
                                " DOF");
  }
  for (std::size_t i = 0; i < dev.active.size(); ++i) {
    dev.joints[dev.active[i]].velocityTarget = velocities[static_cast<Eigen::Index>(i)];
  }
}

void Simulator::setMotorForceLimits(DeviceId device, const rw::math::Q& limits) {
  auto& dev = impl_->device(device);
  if (static_cast<std::size_t>(limits.size()) != dev.active.size()) {
    throw std::invalid_argument("Simulator: " + std::to_string(limits.size()) +
                                " force limits for " + std::to_string(dev.active.size()) + " DOF");
  }
  for (Eigen::Index i = 0; i < limits.size(); ++i) {
    if (!std::isfinite(limits[i]) || limits[i] < 0.0) {
      throw std::invalid_argument("Simulator: force limit " + std::to_string(i) +
                                  " must be finite and >= 0");
    }
  }
  for (SimJoint& j : dev.joints) {
    if (j.activeIndex >= 0) j.forceLimit = limits[j.activeIndex];
  }
  for (SimJoint& j : dev.joints) {
    if (!j.owner) continue;
    const int ownerDof = dev.joints[*j.owner].activeIndex;
    if (ownerDof >= 0) j.forceLimit = limits[ownerDof];
  }
}

const std::vector<SolvedBodyContact>& Simulator::contacts() const { return impl_->solved; }

std::size_t Simulator::lastStepRows() const { return impl_->rows; }

const SimulatorOptions& Simulator::options() const { return impl_->options; }

const trial::PhysicsVariation& Simulator::variation() const { return impl_->variation; }

namespace {

class OdeEngineFactory final : public trial::EngineFactory {
 public:
  OdeEngineFactory(const dynamics::DynamicWorkCell& dwc, SimulatorOptions options,
                   std::shared_ptr<const contacts::ContactDetector> detector)
      : dwc_(dwc), options_(std::move(options)), detector_(std::move(detector)) {}

  std::string name() const override { return "ode"; }

  std::string settings() const override {
    char text[512];
    std::snprintf(text, sizeof(text),
                  "ODE %s; step %.9g s %s; cfm %.9g erp %.9g; contact cfm %.9g erp %.9g, "
                  "surface layer %.9g m, max correcting velocity %.9g m/s, margin %.9g m, "
                  "%d points per manifold",
                  VISGRAB_ODE_VERSION, options_.timeStep, options_.stepMethod.c_str(),
                  options_.worldCfm, options_.worldErp, options_.contactCfm, options_.contactErp,
                  options_.contactSurfaceLayer, options_.maxCorrectingVelocity,
                  options_.contacts.margin, options_.contacts.maxPointsPerManifold);
    return text;
  }

  using trial::EngineFactory::create;
  std::unique_ptr<trial::PhysicsEngine> create(
      const trial::PhysicsVariation& variation) const override {
    if (detector_) return std::make_unique<Simulator>(dwc_, detector_, options_, variation);
    return std::make_unique<Simulator>(dwc_, options_, variation);
  }

 private:
  const dynamics::DynamicWorkCell& dwc_;
  SimulatorOptions options_;
  std::shared_ptr<const contacts::ContactDetector> detector_;
};

}  // namespace

std::shared_ptr<const trial::EngineFactory> odeEngineFactory(
    const dynamics::DynamicWorkCell& dwc, SimulatorOptions options,
    std::shared_ptr<const contacts::ContactDetector> detector) {
  return std::make_shared<OdeEngineFactory>(dwc, std::move(options), std::move(detector));
}

}  // namespace rwsim::simulator
