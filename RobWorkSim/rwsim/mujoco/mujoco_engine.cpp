#include "rwsim/mujoco/mujoco_engine.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/kinematics/frame_tree.hpp"

namespace rwsim::mujoco {

namespace detail {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

}  // namespace detail

using ModelPtr = std::unique_ptr<mjModel, detail::ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, detail::DataDeleter>;

namespace {

using dynamics::BodyId;
using dynamics::BodyKind;
using dynamics::DeviceId;
using rw::math::Transform3D;
using rw::math::Vector3D;
using trial::StepStatus;

// MuJoCo's warnings are counted in mjData::warning, which step() reads; without a handler MuJoCo
// would also print them and append them to MUJOCO_LOG.TXT in the working folder.
void countWarningOnly(const char* /*message*/) {}

ModelPtr compile(const std::string& xml, const std::string& dwcName) {
  static std::once_flag handler;
  std::call_once(handler, [] { mju_user_warning = countWarningOnly; });
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "exported.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error(dwcName + ": MuJoCo cannot make a virtual file for the model");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], xml.data(), xml.size());
  char error[1000] = "";
  ModelPtr m(mj_loadXML(name, vfs.get(), error, sizeof(error)));
  mj_deleteVFS(vfs.get());
  if (!m) {
    throw std::runtime_error(dwcName + ": MuJoCo cannot compile the exported MJCF: " + error);
  }
  return m;
}

int idOf(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::logic_error("the exported MJCF has no '" + name + "'");
  return id;
}

// What a warning is, and whether it makes the step's result unreliable.
struct WarningInfo {
  const char* what;
  bool fatal;
};

constexpr std::array<WarningInfo, mjNWARNING> kWarnings = {{
    {"near-singular inertia matrix", false},
    {"contact buffer full, contacts dropped", true},
    {"constraint buffer full, constraints dropped", true},
    {"visual geom buffer full", false},
    {"bad number in qpos", true},
    {"bad number in qvel", true},
    {"bad number in qacc", true},
    {"bad number in ctrl", true},
}};
static_assert(mjWARN_BADCTRL == 7 && mjNWARNING == 8, "kWarnings follows mjtWarning");

Transform3D poseOf(const mjData* d, int body) {
  Transform3D X = Transform3D::Identity();
  X.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->xmat + 9 * body);
  X.translation() = Vector3D(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]);
  return X;
}

void setPose(mjtNum* pos, mjtNum* quat, const Transform3D& X) {
  const Eigen::Quaterniond q(X.linear());
  for (int k = 0; k < 3; ++k) pos[k] = X.translation()[k];
  quat[0] = q.w();
  quat[1] = q.x();
  quat[2] = q.y();
  quat[3] = q.z();
}

}  // namespace

// The compiled model and the dwc's ids in it.
struct CompiledModel {
  ModelPtr model;
  MujocoOptions options;
  // Per dwc body: MuJoCo body id; qpos and dof address of its free joint or link joint (-1);
  // the six joints of a kinematic body (empty otherwise).
  std::vector<int> body;
  std::vector<int> freeJoint;
  std::vector<int> linkJoint;
  std::vector<std::vector<int>> kinematicJoints;
  // Per MuJoCo body: the dwc body index, or -1.
  std::vector<int> dwcBody;
  // Per device, per DOF: the joint and its servo.
  std::vector<std::vector<int>> activeJoints;
  std::vector<std::vector<int>> actuators;
};

struct MujocoEngine::Impl {
  const dynamics::DynamicWorkCell* dwc = nullptr;
  std::shared_ptr<const CompiledModel> compiled;
  ModelPtr m;
  DataPtr d;
  rw::kinematics::State state;
  StepStatus status = StepStatus::kOk;
  // Simulated time; kept by the engine, as MuJoCo resets mjData (and its time) on a bad qacc.
  double time = 0.0;
  std::string failureDetail;
  std::string messages;
  std::array<int, mjNWARNING> warningsSeen{};
  std::vector<Vector3D> commandLinear;
  std::vector<Vector3D> commandAngular;
  std::vector<Vector3D> startPosition;
  std::vector<BodyId> movableOrder;
  std::vector<trial::SolvedBodyContact> solved;

  int mjBody(BodyId id) const {
    if (!id.valid() || id.index() >= compiled->body.size()) {
      throw std::out_of_range("MujocoEngine: no body " + dynamics::toString(id));
    }
    return compiled->body[id.index()];
  }
  std::size_t deviceIndex(DeviceId id) const {
    if (!id.valid() || id.index() >= compiled->activeJoints.size()) {
      throw std::out_of_range("MujocoEngine: no device " + dynamics::toString(id));
    }
    return id.index();
  }
  void fail(StepStatus s, std::string detail) {
    status = s;
    failureDetail = std::move(detail);
  }
  void vary(const trial::PhysicsVariation& variation);
  bool commandsFinite();
  void driveKinematicBodies();
  bool readWarnings();
  void checkBodies();
  void collectContacts();
  void updateState();
};

void MujocoEngine::Impl::vary(const trial::PhysicsVariation& variation) {
  if (variation.frictionScale != 1.0) {
    for (int p = 0; p < m->npair; ++p) {
      m->pair_friction[5 * p] *= variation.frictionScale;
      m->pair_friction[5 * p + 1] *= variation.frictionScale;
    }
  }
  if (variation.objectMassScale != 1.0) {
    const auto& bodies = dwc->bodies();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (!trial::isVariedObject(bodies[b])) continue;
      const int id = compiled->body[b];
      m->body_mass[id] *= variation.objectMassScale;
      // The principal moments: a scaled tensor keeps its principal axes (body_iquat).
      for (int k = 0; k < 3; ++k) m->body_inertia[3 * id + k] *= variation.objectMassScale;
    }
  }
  if (!variation.gravity) {
    for (int k = 0; k < 3; ++k) m->opt.gravity[k] = 0.0;
  }
  // The compiler's constants at qpos0 from the scaled values (kinematic bodies are not yet
  // moved: this model copy is as compiled).
  mj_setConst(m.get(), d.get());
}

bool MujocoEngine::Impl::commandsFinite() {
  for (std::size_t b = 0; b < commandLinear.size(); ++b) {
    if (!commandLinear[b].allFinite() || !commandAngular[b].allFinite()) {
      fail(StepStatus::kNumericalFailure,
           "body " + dwc->bodies()[b].name + ": commanded velocity is not finite");
      return false;
    }
  }
  for (int a = 0; a < m->nu; ++a) {
    if (!std::isfinite(d->ctrl[a])) {
      fail(StepStatus::kNumericalFailure, std::string("joint ") +
                                              mj_id2name(m.get(), mjOBJ_ACTUATOR, a) +
                                              ": motor target is not finite");
      return false;
    }
  }
  return true;
}

// Writes each kinematic body's commanded twist into its joints' velocities: the slides' and the
// hinges' world axes (at the current pose) times the joint speeds give the frame origin's linear
// and the body's angular velocity.
void MujocoEngine::Impl::driveKinematicBodies() {
  for (std::size_t b = 0; b < commandLinear.size(); ++b) {
    const auto& joints = compiled->kinematicJoints[b];
    if (joints.empty()) continue;
    Eigen::Matrix3d slides;
    Eigen::Matrix3d hinges;
    for (int k = 0; k < 3; ++k) {
      slides.col(k) = Eigen::Map<const Vector3D>(d->xaxis + 3 * joints[k]);
      hinges.col(k) = Eigen::Map<const Vector3D>(d->xaxis + 3 * joints[k + 3]);
    }
    const Vector3D v = slides.partialPivLu().solve(commandLinear[b]);
    const Vector3D w = hinges.partialPivLu().solve(commandAngular[b]);
    for (int k = 0; k < 3; ++k) {
      d->qvel[m->jnt_dofadr[joints[k]]] = v[k];
      d->qvel[m->jnt_dofadr[joints[k + 3]]] = w[k];
    }
  }
}

// New warnings of the last step: the first fatal one fails it, the others become messages.
bool MujocoEngine::Impl::readWarnings() {
  for (int i = 0; i < mjNWARNING; ++i) {
    const int count = d->warning[i].number;
    if (count <= warningsSeen[static_cast<std::size_t>(i)]) continue;
    warningsSeen[static_cast<std::size_t>(i)] = count;
    const WarningInfo& info = kWarnings[static_cast<std::size_t>(i)];
    const std::string text = std::string("MuJoCo warning: ") + info.what + " (index " +
                             std::to_string(d->warning[i].lastinfo) + ")";
    if (info.fatal) {
      fail(StepStatus::kNumericalFailure, text);
      return false;
    }
    if (messages.size() < 4096) messages += (messages.empty() ? "" : "; ") + text;
  }
  return true;
}

void MujocoEngine::Impl::checkBodies() {
  for (int i = 0; i < m->nq; ++i) {
    if (!std::isfinite(d->qpos[i])) {
      fail(StepStatus::kNumericalFailure, "MuJoCo: qpos " + std::to_string(i) + " is not finite");
      return;
    }
  }
  for (int i = 0; i < m->nv; ++i) {
    if (!std::isfinite(d->qvel[i])) {
      fail(StepStatus::kNumericalFailure, "MuJoCo: qvel " + std::to_string(i) + " is not finite");
      return;
    }
  }
  const auto& bodies = dwc->bodies();
  const MujocoOptions& options = compiled->options;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].kind != BodyKind::kRigid) continue;
    mjtNum v[6];
    mj_objectVelocity(m.get(), d.get(), mjOBJ_BODY, compiled->body[b], v, 0);
    const double speed = Vector3D(v[3], v[4], v[5]).norm();
    if (speed > options.maxSpeed) {
      fail(StepStatus::kRunaway,
           "body " + bodies[b].name + ": speed " + std::to_string(speed) + " m/s exceeds maxSpeed");
      return;
    }
    const double moved =
        (poseOf(d.get(), compiled->body[b]).translation() - startPosition[b]).norm();
    if (moved > options.escapeDistance) {
      fail(StepStatus::kRunaway, "body " + bodies[b].name + ": moved " + std::to_string(moved) +
                                     " m, beyond escapeDistance");
      return;
    }
  }
}

void MujocoEngine::Impl::collectContacts() {
  solved.clear();
  std::map<std::pair<BodyId, BodyId>, std::size_t> slot;
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const int a = compiled->dwcBody[static_cast<std::size_t>(m->geom_bodyid[c.geom1])];
    const int b = compiled->dwcBody[static_cast<std::size_t>(m->geom_bodyid[c.geom2])];
    if (a < 0 || b < 0 || a == b) continue;
    mjtNum local[6];
    mj_contactForce(m.get(), d.get(), i, local);
    // The contact frame's rows: the normal (from geom1 towards geom2), then the tangents;
    // mj_contactForce gives the force geom1 exerts on geom2 in that frame.
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> frame(c.frame);
    trial::SolvedContact sc;
    sc.point.position = Vector3D(c.pos[0], c.pos[1], c.pos[2]);
    sc.point.normal = frame.row(0).transpose();
    sc.point.depth = -c.dist;
    sc.force = frame.transpose() * Vector3D(local[0], local[1], local[2]);
    BodyId bodyA(static_cast<std::size_t>(a));
    BodyId bodyB(static_cast<std::size_t>(b));
    if (bodyB < bodyA) {
      std::swap(bodyA, bodyB);
      sc.point.normal = -sc.point.normal;
      sc.force = -sc.force;
    }
    const auto [it, added] = slot.try_emplace({bodyA, bodyB}, solved.size());
    if (added) {
      trial::SolvedBodyContact pair;
      pair.bodyA = bodyA;
      pair.bodyB = bodyB;
      solved.push_back(std::move(pair));
    }
    solved[it->second].points.push_back(sc);
  }
}

void MujocoEngine::Impl::updateState() {
  const auto& tree = dwc->workcell().frames();
  for (std::size_t dev = 0; dev < dwc->devices().size(); ++dev) {
    const auto& joints = dwc->devices()[dev].device->joints();
    for (const auto joint : joints) {
      const auto& frame = tree.frame(joint);
      if (frame.isDependent()) continue;
      const BodyId link = dwc->bodyOfFrame(joint);
      if (!link.valid() || compiled->linkJoint[link.index()] < 0) continue;
      frame.setJointValue(state, d->qpos[m->jnt_qposadr[compiled->linkJoint[link.index()]]]);
    }
  }
  for (const BodyId id : movableOrder) {
    const auto& frame = tree.frame(dwc->body(id).frame);
    const Transform3D X_W_frame = poseOf(d.get(), compiled->body[id.index()]);
    const Transform3D X_W_parent =
        rw::kinematics::worldTransform(tree, state, state.parentOf(frame.id()));
    frame.setMovableTransform(state, X_W_parent.inverse() * X_W_frame);
  }
}

MujocoEngine::MujocoEngine(const dynamics::DynamicWorkCell& dwc,
                           std::shared_ptr<const CompiledModel> model,
                           const trial::PhysicsVariation& variation)
    : impl_(std::make_unique<Impl>()) {
  if (!model) throw std::invalid_argument("MujocoEngine: the compiled model is null");
  variation.check();
  impl_->dwc = &dwc;
  impl_->compiled = std::move(model);
  impl_->m.reset(mj_copyModel(nullptr, impl_->compiled->model.get()));
  impl_->d.reset(mj_makeData(impl_->m.get()));
  if (!impl_->m || !impl_->d) throw std::runtime_error("MujocoEngine: out of memory");
  if (!variation.isIdentity()) impl_->vary(variation);
  const auto& tree = dwc.workcell().frames();
  const auto& bodies = dwc.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (tree.frame(bodies[b].frame).type() == rw::kinematics::FrameType::kMovable &&
        bodies[b].kind != BodyKind::kFixed) {
      impl_->movableOrder.push_back(BodyId(b));
    }
  }
  std::sort(impl_->movableOrder.begin(), impl_->movableOrder.end(),
            [&](BodyId x, BodyId y) { return dwc.body(x).frame < dwc.body(y).frame; });
  reset(dwc.workcell().defaultState());
}

MujocoEngine::~MujocoEngine() = default;

void MujocoEngine::reset(const rw::kinematics::State& state) {
  Impl& s = *impl_;
  mjModel* m = s.m.get();
  mjData* d = s.d.get();
  const mjModel* base = s.compiled->model.get();
  std::copy(base->actuator_forcerange, base->actuator_forcerange + 2 * base->nu,
            m->actuator_forcerange);
  mj_resetData(m, d);
  const auto& tree = s.dwc->workcell().frames();
  const rw::kinematics::FKTable fk(tree, state);
  const auto& bodies = s.dwc->bodies();
  s.commandLinear.assign(bodies.size(), Vector3D::Zero());
  s.commandAngular.assign(bodies.size(), Vector3D::Zero());
  s.startPosition.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Transform3D& X = fk.worldTransform(bodies[b].frame);
    s.startPosition[b] = X.translation();
    const int id = s.compiled->body[b];
    if (const int free = s.compiled->freeJoint[b]; free >= 0) {
      mjtNum* q = d->qpos + m->jnt_qposadr[free];
      setPose(q, q + 3, X);
    } else if (const int link = s.compiled->linkJoint[b]; link >= 0) {
      d->qpos[m->jnt_qposadr[link]] = tree.frame(bodies[b].frame).jointValue(state);
    } else if (m->body_parentid[id] == 0) {
      // A kinematic or fixed body below the world: placed in this engine's model.
      setPose(m->body_pos + 3 * id, m->body_quat + 4 * id, X);
    }
  }
  mj_forward(m, d);
  s.state = state;
  s.status = StepStatus::kOk;
  s.failureDetail.clear();
  s.messages.clear();
  for (int i = 0; i < mjNWARNING; ++i) {
    s.warningsSeen[static_cast<std::size_t>(i)] = d->warning[i].number;
  }
  s.time = 0.0;
  s.solved.clear();
}

StepStatus MujocoEngine::step() {
  Impl& s = *impl_;
  if (s.status != StepStatus::kOk) return s.status;
  if (!s.commandsFinite()) return s.status;
  s.driveKinematicBodies();
  mjModel* m = s.m.get();
  mjData* d = s.d.get();
  mj_step(m, d);
  s.time += m->opt.timestep;
  if (!s.readWarnings()) return s.status;
  // mj_step leaves the poses of the step's start in mjData; bring them to the new positions.
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_comVel(m, d);
  s.checkBodies();
  if (s.status != StepStatus::kOk) return s.status;
  s.collectContacts();
  s.updateState();
  return s.status;
}

double MujocoEngine::timeStep() const { return impl_->m->opt.timestep; }

double MujocoEngine::time() const { return impl_->time; }

const std::string& MujocoEngine::failureDetail() const { return impl_->failureDetail; }

const std::string& MujocoEngine::engineMessages() const { return impl_->messages; }

const rw::kinematics::State& MujocoEngine::state() const { return impl_->state; }

Transform3D MujocoEngine::bodyPose(BodyId body) const {
  return poseOf(impl_->d.get(), impl_->mjBody(body));
}

Vector3D MujocoEngine::bodyLinearVelocity(BodyId body) const {
  mjtNum v[6];
  mj_objectVelocity(impl_->m.get(), impl_->d.get(), mjOBJ_BODY, impl_->mjBody(body), v, 0);
  return Vector3D(v[3], v[4], v[5]);
}

Vector3D MujocoEngine::bodyAngularVelocity(BodyId body) const {
  mjtNum v[6];
  mj_objectVelocity(impl_->m.get(), impl_->d.get(), mjOBJ_BODY, impl_->mjBody(body), v, 0);
  return Vector3D(v[0], v[1], v[2]);
}

void MujocoEngine::setKinematicVelocity(BodyId body, const Vector3D& linear,
                                        const Vector3D& angular) {
  impl_->mjBody(body);
  if (impl_->compiled->kinematicJoints[body.index()].empty()) {
    throw std::invalid_argument("MujocoEngine: body " + impl_->dwc->body(body).name +
                                " is not kinematic");
  }
  impl_->commandLinear[body.index()] = linear;
  impl_->commandAngular[body.index()] = angular;
}

rw::math::Q MujocoEngine::jointPositions(DeviceId device) const {
  const auto& joints = impl_->compiled->activeJoints[impl_->deviceIndex(device)];
  rw::math::Q q(static_cast<Eigen::Index>(joints.size()));
  for (std::size_t i = 0; i < joints.size(); ++i) {
    q[static_cast<Eigen::Index>(i)] = impl_->d->qpos[impl_->m->jnt_qposadr[joints[i]]];
  }
  return q;
}

rw::math::Q MujocoEngine::jointVelocities(DeviceId device) const {
  const auto& joints = impl_->compiled->activeJoints[impl_->deviceIndex(device)];
  rw::math::Q v(static_cast<Eigen::Index>(joints.size()));
  for (std::size_t i = 0; i < joints.size(); ++i) {
    v[static_cast<Eigen::Index>(i)] = impl_->d->qvel[impl_->m->jnt_dofadr[joints[i]]];
  }
  return v;
}

void MujocoEngine::setMotorVelocityTargets(DeviceId device, const rw::math::Q& velocities) {
  const auto& actuators = impl_->compiled->actuators[impl_->deviceIndex(device)];
  if (static_cast<std::size_t>(velocities.size()) != actuators.size()) {
    throw std::invalid_argument("MujocoEngine: " + std::to_string(velocities.size()) +
                                " velocity targets for " + std::to_string(actuators.size()) +
                                " DOF");
  }
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    impl_->d->ctrl[actuators[i]] = velocities[static_cast<Eigen::Index>(i)];
  }
}

void MujocoEngine::setMotorForceLimits(DeviceId device, const rw::math::Q& limits) {
  const auto& actuators = impl_->compiled->actuators[impl_->deviceIndex(device)];
  if (static_cast<std::size_t>(limits.size()) != actuators.size()) {
    throw std::invalid_argument("MujocoEngine: " + std::to_string(limits.size()) +
                                " force limits for " + std::to_string(actuators.size()) + " DOF");
  }
  for (Eigen::Index i = 0; i < limits.size(); ++i) {
    if (!std::isfinite(limits[i]) || limits[i] < 0.0) {
      throw std::invalid_argument("MujocoEngine: force limit " + std::to_string(i) +
                                  " must be finite and >= 0");
    }
  }
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    const double limit = limits[static_cast<Eigen::Index>(i)];
    impl_->m->actuator_forcerange[2 * actuators[i]] = -limit;
    impl_->m->actuator_forcerange[2 * actuators[i] + 1] = limit;
  }
}

const std::vector<trial::SolvedBodyContact>& MujocoEngine::contacts() const {
  return impl_->solved;
}

namespace {

std::shared_ptr<const CompiledModel> compileDwc(const dynamics::DynamicWorkCell& dwc,
                                                const MujocoOptions& options) {
  const MjcfModel names = exportMjcf(dwc, options);
  auto out = std::make_shared<CompiledModel>();
  out->options = options;
  out->model = compile(names.xml, dwc.fileName().empty() ? "dynamic workcell" : dwc.fileName());
  const mjModel* m = out->model.get();
  const auto& bodies = dwc.bodies();
  out->dwcBody.assign(static_cast<std::size_t>(m->nbody), -1);
  out->body.resize(bodies.size());
  out->freeJoint.assign(bodies.size(), -1);
  out->linkJoint.assign(bodies.size(), -1);
  out->kinematicJoints.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const int id = idOf(m, mjOBJ_BODY, names.bodyNames[b]);
    out->body[b] = id;
    out->dwcBody[static_cast<std::size_t>(id)] = static_cast<int>(b);
    for (const std::string& joint : names.kinematicJoints[b]) {
      out->kinematicJoints[b].push_back(idOf(m, mjOBJ_JOINT, joint));
    }
    const int joint = mj_name2id(m, mjOBJ_JOINT, names.bodyNames[b].c_str());
    if (joint < 0) continue;
    (m->jnt_type[joint] == mjJNT_FREE ? out->freeJoint : out->linkJoint)[b] = joint;
  }
  for (const auto& device : names.activeJoints) {
    auto& joints = out->activeJoints.emplace_back();
    auto& actuators = out->actuators.emplace_back();
    for (const std::string& name : device) {
      joints.push_back(idOf(m, mjOBJ_JOINT, name));
      actuators.push_back(idOf(m, mjOBJ_ACTUATOR, name));
    }
  }
  return out;
}

class MujocoEngineFactory final : public trial::EngineFactory {
 public:
  MujocoEngineFactory(const dynamics::DynamicWorkCell& dwc, const MujocoOptions& options)
      : dwc_(dwc), model_(compileDwc(dwc, options)) {}

  std::string name() const override { return "mujoco"; }

  std::string settings() const override {
    const MujocoOptions& o = model_->options;
    const int v = mj_version();
    char text[640];
    std::snprintf(text, sizeof(text),
                  "MuJoCo %d.%d.%d; step %.9g s; %s; %s; %s cone impratio %.9g; solref %.9g %.9g; "
                  "motor kv %.9g armature %.9g; prismatic motor kv %.9g armature %.9g; kinematic "
                  "mass %.9g kg armature %.9g; %d segments per round; "
                  "max speed %.9g m/s, escape %.9g m",
                  v / 100, v / 10 % 10, v % 10, o.timeStep, o.solver.c_str(), o.integrator.c_str(),
                  o.cone.c_str(), o.impratio, o.solrefTimeConstant, o.solrefDampingRatio,
                  o.motorGain, o.motorArmature, o.prismaticMotorGain, o.prismaticMotorArmature,
                  o.kinematicMass, o.kinematicArmature, o.roundSegments, o.maxSpeed,
                  o.escapeDistance);
    return text;
  }

  using trial::EngineFactory::create;
  std::unique_ptr<trial::PhysicsEngine> create(
      const trial::PhysicsVariation& variation) const override {
    return std::make_unique<MujocoEngine>(dwc_, model_, variation);
  }

 private:
  const dynamics::DynamicWorkCell& dwc_;
  std::shared_ptr<const CompiledModel> model_;
};

}  // namespace

std::shared_ptr<const trial::EngineFactory> mujocoEngineFactory(
    const dynamics::DynamicWorkCell& dwc, MujocoOptions options) {
  return std::make_shared<MujocoEngineFactory>(dwc, options);
}

}  // namespace rwsim::mujoco
