#include "mujoco/mujoco_grasp_trial.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/control/pd_controller.hpp"
#include "rwsim/control/ramp_trajectory.hpp"

namespace visgrab::mujoco {

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::simulator::GraspOutcome;

mjModel* compile(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "exported.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error("MuJoCo: cannot make a virtual file for the model");
  }
  const int file = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[file], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (m == nullptr) throw std::runtime_error(std::string("MuJoCo: ") + error);
  return m;
}

// Share of the previous step's constraint forces on the hand's joints that their motors take up
// in advance (driveJoints()). A velocity constraint takes up all of it, but with this one-step
// delay 1.0 oscillates (longer, less stable closing); 0 leaves a velocity servo of gain M/dt, and
// contact loads turn the unsaturated spread about 0.14 rad so that closing never rests before
// about 0.9 s. From 0.6 to 0.8 the SDH box trials close like the project's (1.37-1.41 s
// simulated per trial at 0.7 against its 1.445 s), all stable.
constexpr double kConstraintFeedForward = 0.7;

// MuJoCo's warnings are counted in mjData::warning, which the trial checks; without a handler
// MuJoCo would also append them to MUJOCO_LOG.TXT in the working folder.
void ignoreWarning(const char* /*message*/) {}

int idOf(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw std::invalid_argument("the MJCF model has no '" + name + "'");
  return id;
}

}  // namespace

// One trial on the shared mjModel/mjData: GraspTrial's phases.
struct MujocoGraspTrial::Run {
  Run(MujocoGraspTrial& trial, const rwsim::simulator::GraspParameters& g,
      const rwsim::dynamics::PDController& controller)
      : t(trial), grasp(g), pd(controller.p, controller.d) {}

  MujocoGraspTrial& t;
  const rwsim::simulator::GraspParameters& grasp;
  rwsim::control::PDController pd;
  int baseBody = 0;  // MuJoCo id
  double dt = 0.0;
  Transform3D baseTarget = Transform3D::Identity();
  MujocoTrialResult result;

  Transform3D pose(int body) const {
    const mjData* d = t.d_;
    Transform3D X = Transform3D::Identity();
    X.linear() = Eigen::Quaterniond(d->xquat[4 * body], d->xquat[4 * body + 1],
                                    d->xquat[4 * body + 2], d->xquat[4 * body + 3])
                     .toRotationMatrix();
    X.translation() = Vector3D(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]);
    return X;
  }
  Q handQ() const {
    Q q(static_cast<Eigen::Index>(t.handQposAdr_.size()));
    for (std::size_t i = 0; i < t.handQposAdr_.size(); ++i) {
      q[static_cast<Eigen::Index>(i)] = t.d_->qpos[t.handQposAdr_[i]];
    }
    return q;
  }
  Q handV() const {
    Q v(static_cast<Eigen::Index>(t.handDofAdr_.size()));
    for (std::size_t i = 0; i < t.handDofAdr_.size(); ++i) {
      v[static_cast<Eigen::Index>(i)] = t.d_->qvel[t.handDofAdr_[i]];
    }
    return v;
  }
  void finish(GraspOutcome outcome, std::string detail) {
    result.outcome = outcome;
    result.detail = std::move(detail);
  }

  // One step: the PD command to the fingers, the base towards baseTarget.
  bool advance() {
    mjData* d = t.d_;
    mj_step1(t.m_, d);
    const Q v = pd.update(handQ(), dt);
    t.driveJoints(v, rwsim::control::twistToReach(pose(baseBody), baseTarget, dt).linear);
    mj_step2(t.m_, d);
    ++result.steps;
    result.constraintRows += d->nefc;
    result.solverIterations += d->solver_iter;
    result.simulatedTime = d->time;
    for (int i = 0; i < t.m_->nq; ++i) {
      if (!std::isfinite(d->qpos[i])) {
        finish(GraspOutcome::kSimulationFailure, "MuJoCo state is not finite");
        return false;
      }
    }
    if (d->warning[mjWARN_BADQACC].number > 0) {
      finish(GraspOutcome::kSimulationFailure, "MuJoCo reported a bad acceleration");
      return false;
    }
    if (d->time > t.setup_.timeLimit) {
      finish(GraspOutcome::kTimeout, "simulated time passed the limit");
      return false;
    }
    return true;
  }

  bool close() {
    const auto& s = t.setup_;
    double restSince = -1.0;
    while (true) {
      if (!advance()) return false;
      const double time = t.d_->time;
      if (time < s.minCloseTime) continue;
      if ((handQ() - grasp.qClosed).cwiseAbs().maxCoeff() <= s.closedTolerance) break;
      if ((handV().cwiseAbs().array() < t.restSpeed_.array()).all()) {
        if (restSince < 0.0) restSince = time;
        if (time - restSince >= s.restTime - 1e-9) break;
      } else {
        restSince = -1.0;
      }
      if (time >= s.closeTimeLimit) break;
    }
    return true;
  }

  // Hand-contact counts per dwc body (contacts pushing harder than the threshold).
  std::vector<int> handContactCounts() const {
    const mjModel* m = t.m_;
    const mjData* d = t.d_;
    std::vector<int> counts(t.isHandBody_.size(), 0);
    for (int i = 0; i < d->ncon; ++i) {
      const int a = t.dwcBodyOf_[static_cast<std::size_t>(m->geom_bodyid[d->contact[i].geom1])];
      const int b = t.dwcBodyOf_[static_cast<std::size_t>(m->geom_bodyid[d->contact[i].geom2])];
      if (a < 0 || b < 0) continue;
      const bool handA = t.isHandBody_[static_cast<std::size_t>(a)];
      const bool handB = t.isHandBody_[static_cast<std::size_t>(b)];
      if (handA == handB) continue;
      mjtNum f[6];
      mj_contactForce(m, d, i, f);
      if (f[0] > t.setup_.contactForceThreshold) ++counts[static_cast<std::size_t>(handA ? b : a)];
    }
    return counts;
  }

  bool lift(int objectBody) {
    const auto& s = t.setup_;
    const Transform3D X_h0 = pose(baseBody);
    const Vector3D o0 = pose(objectBody).translation();
    Transform3D X_end = X_h0;
    X_end.translation().z() += s.liftHeight;
    rwsim::control::RampLimits limits;
    limits.linearVelocity = s.liftSpeed;
    limits.linearAcceleration = s.liftAcceleration;
    const rwsim::control::RampTrajectory trajectory(X_h0, X_end, limits);
    const double t0 = t.d_->time;
    while (t.d_->time - t0 < trajectory.duration() - 1e-9) {
      baseTarget = trajectory.pose(t.d_->time - t0 + dt);
      if (!advance()) return false;
    }
    baseTarget = X_end;
    const double t1 = t.d_->time;
    while (t.d_->time - t1 < s.settleTime - 1e-9) {
      if (!advance()) return false;
    }
    const Vector3D h = pose(baseBody).translation() - X_h0.translation();
    const Vector3D o = pose(objectBody).translation() - o0;
    result.drift = (o - h).norm();
    return true;
  }
};

MujocoGraspTrial::MujocoGraspTrial(const rwsim::dynamics::DynamicWorkCell& dwc,
                                   const MjcfModel& model, rwsim::simulator::GraspTrialSetup setup)
    : dwc_(dwc), setup_(std::move(setup)), placement_(dwc, setup_) {
  mju_user_warning = ignoreWarning;
  m_ = compile(model.xml);
  d_ = mj_makeData(m_);
  const auto& bodies = dwc.bodies();
  const std::size_t n = bodies.size();
  bodyIds_.resize(n);
  dwcBodyOf_.assign(static_cast<std::size_t>(m_->nbody), -1);
  jointQposAdr_.assign(n, -1);
  for (auto& v : slideQposAdr_) v.assign(n, -1);
  isHandBody_.assign(n, false);
  for (std::size_t b = 0; b < n; ++b) {
    bodyIds_[b] = idOf(m_, mjOBJ_BODY, model.bodyNames[b]);
    dwcBodyOf_[static_cast<std::size_t>(bodyIds_[b])] = static_cast<int>(b);
    const int jnt = mj_name2id(m_, mjOBJ_JOINT, bodies[b].name.c_str());
    if (jnt >= 0) jointQposAdr_[b] = m_->jnt_qposadr[jnt];
    for (std::size_t k = 0; k < model.slideJoints[b].size() && k < 3; ++k) {
      slideQposAdr_[k][b] = m_->jnt_qposadr[idOf(m_, mjOBJ_JOINT, model.slideJoints[b][k])];
    }
  }
  const auto handId = placement_.handDevice();
  const auto& rd = dwc.device(handId);
  isHandBody_[rd.baseBody.index()] = true;
  for (const auto link : rd.linkBodies) {
    if (link.valid()) isHandBody_[link.index()] = true;
  }
  for (const std::string& joint : model.activeJoints[handId.index()]) {
    const int j = idOf(m_, mjOBJ_JOINT, joint);
    handQposAdr_.push_back(m_->jnt_qposadr[j]);
    handDofAdr_.push_back(m_->jnt_dofadr[j]);
    handActuators_.push_back(idOf(m_, mjOBJ_ACTUATOR, joint));
  }
  const auto& active = rd.device->activeJoints();
  restSpeed_.resize(static_cast<Eigen::Index>(active.size()));
  for (std::size_t i = 0; i < active.size(); ++i) {
    restSpeed_[static_cast<Eigen::Index>(i)] =
        dwc.workcell().frames().frame(active[i]).type() == rw::kinematics::FrameType::kPrismatic
            ? setup_.restSpeedPrismatic
            : setup_.restSpeedRevolute;
  }
  const auto& slides = model.slideJoints[rd.baseBody.index()];
  if (slides.size() != 3) {
    throw std::invalid_argument("the hand's base " + bodies[rd.baseBody.index()].name +
                                " has no slide joints in the MJCF model");
  }
  drivenDofs_ = handDofAdr_;
  drivenActuators_ = handActuators_;
  for (const std::string& s : slides) {
    drivenDofs_.push_back(m_->jnt_dofadr[idOf(m_, mjOBJ_JOINT, s)]);
    drivenActuators_.push_back(idOf(m_, mjOBJ_ACTUATOR, s));
  }
  const auto nv = static_cast<std::size_t>(m_->nv);
  fullM_.assign(nv * nv, 0.0);
  mj_forward(m_, d_);
  exportedPosition_.resize(n);
  exportedRotation_.resize(n);
  for (std::size_t b = 0; b < n; ++b) {
    const int id = bodyIds_[b];
    exportedPosition_[b] = Vector3D(d_->xpos[3 * id], d_->xpos[3 * id + 1], d_->xpos[3 * id + 2]);
    exportedRotation_[b] =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d_->xmat + 9 * id);
  }
}

MujocoGraspTrial::~MujocoGraspTrial() {
  mj_deleteData(d_);
  mj_deleteModel(m_);
}

// The project's motors are velocity constraints with a force limit, solved with the contacts,
// and its kinematic base follows its commanded velocity exactly. Here, after mj_step1 (positions,
// velocities, mass matrix, bias forces), the generalised forces that bring the driven dofs (the
// hand's active joints and the base's slides) to their commanded velocities in this step are
// solved from M a + bias = tau, the other dofs' accelerations taken as 0 and the hand joints'
// constraint forces (contacts, limits, the coupling) taken from the previous step, fed forward
// at kConstraintFeedForward; the force limits form an active set: a joint whose force would pass
// its limit gets the limit and its acceleration follows from the others. A finger pressed against
// an object thus pushes with its force limit, as in the project, and a joint loaded below its
// limit holds its velocity against most of the load.
void MujocoGraspTrial::driveJoints(const rw::math::Q& handVelocity,
                                   const rw::math::Vector3D& baseVelocity) {
  const auto nv = static_cast<std::size_t>(m_->nv);
  const auto n = static_cast<Eigen::Index>(drivenDofs_.size());
  const auto nHand = static_cast<Eigen::Index>(handDofAdr_.size());
  mj_fullM(m_, fullM_.data(), d_->qM);
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd bias(n);
  Eigen::VectorXd a(n);  // accelerations wanted (free dofs) or resulting (saturated ones)
  for (Eigen::Index i = 0; i < n; ++i) {
    const int row = drivenDofs_[static_cast<std::size_t>(i)];
    for (Eigen::Index k = 0; k < n; ++k) {
      M(i, k) = fullM_[static_cast<std::size_t>(row) * nv +
                       static_cast<std::size_t>(drivenDofs_[static_cast<std::size_t>(k)])];
    }
    bias[i] = d_->qfrc_bias[row] - d_->qfrc_passive[row];
    if (i < nHand) bias[i] -= kConstraintFeedForward * d_->qfrc_constraint[row];
    const double target = i < nHand ? handVelocity[i] : baseVelocity[i - nHand];
    a[i] = (target - d_->qvel[row]) / m_->opt.timestep;
  }
  std::vector<bool> saturated(static_cast<std::size_t>(n), false);
  Eigen::VectorXd tau(n);
  for (Eigen::Index round = 0; round <= nHand; ++round) {
    std::vector<Eigen::Index> sat;
    std::vector<Eigen::Index> free;
    for (Eigen::Index i = 0; i < n; ++i) {
      (saturated[static_cast<std::size_t>(i)] ? sat : free).push_back(i);
    }
    if (!sat.empty()) {
      // M_ss a_s = tau_s - bias_s - M_sf a_f
      const auto ns = static_cast<Eigen::Index>(sat.size());
      Eigen::MatrixXd Mss(ns, ns);
      Eigen::VectorXd rhs(ns);
      for (Eigen::Index r = 0; r < ns; ++r) {
        rhs[r] = tau[sat[static_cast<std::size_t>(r)]] - bias[sat[static_cast<std::size_t>(r)]];
        for (Eigen::Index c = 0; c < ns; ++c) {
          Mss(r, c) = M(sat[static_cast<std::size_t>(r)], sat[static_cast<std::size_t>(c)]);
        }
        for (const Eigen::Index f : free) rhs[r] -= M(sat[static_cast<std::size_t>(r)], f) * a[f];
      }
      const Eigen::VectorXd as = Mss.ldlt().solve(rhs);
      for (Eigen::Index r = 0; r < ns; ++r) a[sat[static_cast<std::size_t>(r)]] = as[r];
    }
    // Saturate the free joint that passes its limit by the largest fraction, then solve again.
    Eigen::Index worst = -1;
    double worstExcess = 1.0;
    for (const Eigen::Index f : free) {
      tau[f] = M.row(f).dot(a) + bias[f];
      const int act = drivenActuators_[static_cast<std::size_t>(f)];
      if (!m_->actuator_forcelimited[act]) continue;
      const double hi = m_->actuator_forcerange[2 * act + 1];
      const double excess = std::abs(tau[f]) / std::max(hi, 1e-12);
      if (excess > worstExcess) {
        worstExcess = excess;
        worst = f;
      }
    }
    const bool changed = worst >= 0;
    if (changed) {
      const int act = drivenActuators_[static_cast<std::size_t>(worst)];
      tau[worst] = std::clamp(tau[worst], m_->actuator_forcerange[2 * act],
                              m_->actuator_forcerange[2 * act + 1]);
      saturated[static_cast<std::size_t>(worst)] = true;
    }
    if (!changed) break;
  }
  for (Eigen::Index i = 0; i < n; ++i)
    d_->ctrl[drivenActuators_[static_cast<std::size_t>(i)]] = tau[i];
}

void MujocoGraspTrial::setState(const rw::kinematics::State& state) {
  const auto& tree = dwc_.workcell().frames();
  const rw::kinematics::FKTable fk(tree, state);
  const auto& bodies = dwc_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& body = bodies[b];
    const Transform3D& X = fk.worldTransform(body.frame);
    const auto& frame = tree.frame(body.frame);
    if (slideQposAdr_[0][b] >= 0) {
      if (!X.linear().isApprox(exportedRotation_[b], 1e-9)) {
        throw std::invalid_argument("kinematic body " + body.name +
                                    " is turned against its exported pose; its slides cannot turn");
      }
      const Vector3D shift = X.translation() - exportedPosition_[b];
      for (int k = 0; k < 3; ++k) d_->qpos[slideQposAdr_[k][b]] = shift[k];
    } else if (jointQposAdr_[b] >= 0 && frame.isJoint()) {
      d_->qpos[jointQposAdr_[b]] = frame.jointValue(state);
    } else if (jointQposAdr_[b] >= 0) {  // free joint
      const Eigen::Quaterniond q(X.linear());
      double* p = d_->qpos + jointQposAdr_[b];
      for (int k = 0; k < 3; ++k) p[k] = X.translation()[k];
      p[3] = q.w();
      p[4] = q.x();
      p[5] = q.y();
      p[6] = q.z();
    }
  }
}

MujocoTrialResult MujocoGraspTrial::run(const rwsim::simulator::GraspParameters& grasp,
                                        const rw::kinematics::State& initial) {
  const rw::kinematics::State state = placement_.placedState(grasp, initial);
  const auto hand = placement_.handDevice();
  const auto& rd = dwc_.device(hand);
  const auto* controller = dwc_.findController(setup_.controller);
  mj_resetData(m_, d_);
  setState(state);
  // Force limits: tauMax, else the dwc's (as exported).
  const auto& joints = rd.device->joints();
  std::size_t active = 0;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (!dwc_.workcell().frames().frame(joints[k]).isActiveJoint()) continue;
    const double limit = grasp.tauMax.size() > 0 ? grasp.tauMax[static_cast<Eigen::Index>(active)]
                                                 : rd.forceLimits[k];
    const int a = handActuators_[active];
    m_->actuator_forcerange[2 * a] = -limit;
    m_->actuator_forcerange[2 * a + 1] = limit;
    ++active;
  }
  mj_forward(m_, d_);

  Run r(*this, grasp, *controller);
  r.baseBody = bodyIds_[rd.baseBody.index()];
  r.dt = m_->opt.timestep;
  r.baseTarget = r.pose(r.baseBody);
  r.pd.reset(grasp.qOpen);
  r.pd.setTarget(grasp.qClosed);
  if (!r.close()) return r.result;

  const auto counts = r.handContactCounts();
  int best = 0;
  int object = -1;
  for (std::size_t b = 0; b < counts.size(); ++b) {
    if (!isHandBody_[b] && dwc_.bodies()[b].kind == rwsim::dynamics::BodyKind::kRigid &&
        counts[b] > best) {
      best = counts[b];
      object = static_cast<int>(b);
    }
  }
  if (object < 0) {
    r.finish(GraspOutcome::kMissed, "no finger touches an object after closing");
    return r.result;
  }
  if (!r.lift(bodyIds_[static_cast<std::size_t>(object)])) return r.result;
  if (r.handContactCounts()[static_cast<std::size_t>(object)] == 0) {
    r.finish(GraspOutcome::kDropped, "no hand contact on the object after lifting");
    return r.result;
  }
  r.finish(r.result.drift < setup_.slipThreshold ? GraspOutcome::kStable : GraspOutcome::kSlipped,
           "object drift " + std::to_string(r.result.drift) + " m");
  return r.result;
}

}  // namespace visgrab::mujoco
