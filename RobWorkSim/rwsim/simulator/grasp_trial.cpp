#include "rwsim/simulator/grasp_trial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/models/device.hpp"
#include "rw/proximity/collision_detector.hpp"
#include "rwsim/control/pd_controller.hpp"
#include "rwsim/control/ramp_trajectory.hpp"
#include "rwsim/simulator/detail/trial_support.hpp"
#include "rwsim/simulator/grasp_quality.hpp"

namespace rwsim::simulator {

using rw::kinematics::FrameId;
using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;

// A collision geometry of a frame prepared for the contact generation.
struct FrameShape {
  std::shared_ptr<const contacts::ContactShape> shape;
  Transform3D X_frame_shape = Transform3D::Identity();
};

// Everything a trial needs that does not change between trials (shared by copies and threads).
struct detail::TrialData {
  dynamics::DeviceId hand;
  dynamics::BodyId baseBody;
  FrameId baseFrame;
  FrameId tcp;
  const dynamics::PDController* controller = nullptr;
  std::vector<bool> isHandBody;
  std::vector<bool> isHandFrame;
  std::vector<bool> isObjectFrame;
  std::vector<dynamics::BodyId> objects;
  std::vector<double> radius;
  std::shared_ptr<const contacts::ContactDetector> detector;
  std::shared_ptr<const trial::EngineFactory> engine;
  std::unique_ptr<const rw::proximity::CollisionDetector> collision;
  // Per frame index: its collision geometry for penetration depths (empty without geometry).
  std::vector<std::vector<FrameShape>> frameShapes;
};

namespace {

std::shared_ptr<detail::TrialData> prepare(const dynamics::DynamicWorkCell& dwc,
                                           const GraspTrialSetup& setup) {
  auto data = std::make_shared<detail::TrialData>();
  data->hand = dwc.findDevice(setup.hand);
  if (!data->hand.valid()) {
    throw std::invalid_argument("no rigid device named '" + setup.hand + "'");
  }
  const auto& rd = dwc.device(data->hand);
  data->baseBody = rd.baseBody;
  const auto& base = dwc.body(rd.baseBody);
  if (base.kind != dynamics::BodyKind::kKinematic) {
    throw std::invalid_argument("the base " + base.name + " of hand '" + setup.hand +
                                "' is not a kinematic body (KinematicBase)");
  }
  data->baseFrame = base.frame;
  data->controller = dwc.findController(setup.controller);
  if (data->controller == nullptr) {
    throw std::invalid_argument("no controller named '" + setup.controller + "'");
  }
  if (data->controller->device != data->hand) {
    throw std::invalid_argument("controller '" + setup.controller + "' does not drive '" +
                                setup.hand + "'");
  }
  const auto& wc = dwc.workcell();
  const std::string tcpName =
      !setup.tcpFrame.empty()
          ? setup.tcpFrame
          : (wc.findFrame(setup.hand + ".TCP").valid() ? setup.hand + ".TCP" : base.name);
  data->tcp = wc.findFrame(tcpName);
  if (!data->tcp.valid()) throw std::invalid_argument("no frame named '" + tcpName + "'");
  setup.protocol.requireJawFrame(setup.X_tcp_jaw.has_value(), "hand '" + setup.hand + "'");
  return data;
}

void classifyBodies(const dynamics::DynamicWorkCell& dwc, detail::TrialData& data) {
  const auto& rd = dwc.device(data.hand);
  const auto& tree = dwc.workcell().frames();
  const std::size_t n = dwc.bodies().size();
  data.isHandBody.assign(n, false);
  data.isHandBody[rd.baseBody.index()] = true;
  for (const dynamics::BodyId link : rd.linkBodies) {
    if (link.valid()) data.isHandBody[link.index()] = true;
  }
  data.isHandFrame.assign(tree.size(), false);
  data.isObjectFrame.assign(tree.size(), false);
  for (const auto& f : tree.frames()) {
    if (rd.device->contains(f.id()))
      data.isHandFrame[static_cast<std::size_t>(f.id().index)] = true;
  }
  data.radius.assign(n, 0.0);
  for (std::size_t b = 0; b < n; ++b) {
    const auto& body = dwc.bodies()[b];
    for (const FrameId f : body.geometryFrames) {
      auto& mark = data.isHandBody[b] ? data.isHandFrame : data.isObjectFrame;
      if (data.isHandBody[b] || body.kind == dynamics::BodyKind::kRigid) {
        mark[static_cast<std::size_t>(f.index)] = true;
      }
    }
    if (!data.isHandBody[b] && body.kind == dynamics::BodyKind::kRigid) {
      data.objects.emplace_back(b);
      data.radius[b] = detail::maxRadiusFromCog(dwc, dynamics::BodyId(b));
    }
  }
}

void checkGrasp(const GraspParameters& g, int dof) {
  const auto check = [dof](const Q& q, const char* what, bool allowEmpty) {
    if (allowEmpty && q.size() == 0) return;
    if (q.size() != dof) {
      throw std::invalid_argument(std::string(what) + " has " + std::to_string(q.size()) +
                                  " values but the hand has " + std::to_string(dof) + " DOF");
    }
    if (!q.allFinite()) throw std::invalid_argument(std::string(what) + " is not finite");
  };
  check(g.qOpen, "qOpen", false);
  check(g.qClosed, "qClosed", false);
  check(g.tauMax, "tauMax", true);
  if (g.tauMax.size() > 0 && g.tauMax.minCoeff() < 0.0) {
    throw std::invalid_argument("tauMax must not be negative");
  }
  if (!g.X_W_tcp.matrix().allFinite()) throw std::invalid_argument("the TCP pose is not finite");
}

void prepareFrameShapes(const dynamics::DynamicWorkCell& dwc, detail::TrialData& data) {
  const auto& wc = dwc.workcell();
  std::map<const rw::geometry::Geometry*, std::shared_ptr<const contacts::ContactShape>> built;
  data.frameShapes.assign(wc.frames().size(), {});
  for (const auto& f : wc.frames().frames()) {
    const rw::models::Object* object = wc.findObject(f.id());
    if (object == nullptr) continue;
    for (const rw::models::GeometryInstance& g : object->collision) {
      std::shared_ptr<const contacts::ContactShape>& shape = built[g.geometry.get()];
      if (!shape) shape = contacts::ContactShape::build(*g.geometry);
      data.frameShapes[static_cast<std::size_t>(f.id().index)].push_back(
          FrameShape{shape, g.X_frame_geometry});
    }
  }
}

// Deepest overlap of the geometries of frames a and b (the contact generation's depth, margin 0);
// `points` is a buffer.
double penetrationDepth(const detail::TrialData& data, FrameId a, FrameId b,
                        const rw::kinematics::FKTable& fk,
                        std::vector<contacts::ContactPoint>& points) {
  contacts::ContactOptions options;
  options.margin = 0.0;
  points.clear();
  const Transform3D& X_W_a = fk.worldTransform(a);
  const Transform3D& X_W_b = fk.worldTransform(b);
  for (const FrameShape& sa : data.frameShapes[static_cast<std::size_t>(a.index)]) {
    for (const FrameShape& sb : data.frameShapes[static_cast<std::size_t>(b.index)]) {
      contacts::collide(*sa.shape, X_W_a * sa.X_frame_shape, *sb.shape, X_W_b * sb.X_frame_shape,
                        options, points);
    }
  }
  double depth = 0.0;
  for (const contacts::ContactPoint& p : points) depth = std::max(depth, p.depth);
  return depth;
}

// The trial's in-collision test (reference §4.2 step 5): pairs of a hand frame and a non-hand
// frame that rw_proximity finds colliding. As RobWork's GraspTaskSimulator, a pair with an
// object (11) outranks one with the environment (12); the detail names the deepest pair of the
// outranking kind, and `penetration` is the deepest of all.
PlacementCheck checkPlacement(const dynamics::DynamicWorkCell& dwc, const detail::TrialData& data,
                              const rw::kinematics::State& state) {
  const auto& tree = dwc.workcell().frames();
  const rw::kinematics::FKTable fk(tree, state);
  PlacementCheck out;
  FrameId hand;
  FrameId other;
  double deepestOfKind = -1.0;
  std::vector<contacts::ContactPoint> points;
  for (const auto& pair : data.collision->collidingPairs(fk)) {
    const bool handA = data.isHandFrame[static_cast<std::size_t>(pair.first.index)];
    const bool handB = data.isHandFrame[static_cast<std::size_t>(pair.second.index)];
    if (handA == handB) continue;
    const FrameId h = handA ? pair.first : pair.second;
    const FrameId o = handA ? pair.second : pair.first;
    const bool object = data.isObjectFrame[static_cast<std::size_t>(o.index)];
    const double depth = penetrationDepth(data, h, o, fk, points);
    out.penetration = std::max(out.penetration, depth);
    if (out.collides && out.withObject && !object) continue;
    if (out.collides && object == out.withObject && depth <= deepestOfKind) continue;
    out.collides = true;
    out.withObject = object;
    deepestOfKind = depth;
    hand = h;
    other = o;
  }
  if (!out.collides) return out;
  char mm[64];
  std::snprintf(mm, sizeof(mm), " by %.1f mm", deepestOfKind * 1e3);
  out.detail = "hand frame " + tree.frame(hand).name() + " penetrates " +
               (out.withObject ? "object frame " : "environment frame ") +
               tree.frame(other).name() + mm +
               (out.withObject ? " (RobWork 11 CollisionObjectInitially)"
                               : " (RobWork 12 CollisionEnvironmentInitially)");
  return out;
}

// The trial's variation with the protocol's gravity (on: `variation` as it is).
trial::PhysicsVariation withProtocolGravity(const trial::PhysicsVariation& variation,
                                            const trial::TrialProtocol& protocol) {
  trial::PhysicsVariation out = variation;
  if (!protocol.gravity) out.gravity = false;
  return out;
}

// One trial: the phases of reference §4.3 as adapted in the module's documentation.
class TrialRun {
 public:
  TrialRun(const dynamics::DynamicWorkCell& dwc, const GraspTrialSetup& setup,
           const detail::TrialData& data, const GraspParameters& grasp,
           const trial::PhysicsVariation& variation, const Observer& observer)
      : dwc_(dwc),
        setup_(setup),
        data_(data),
        grasp_(grasp),
        observer_(observer),
        frictionScale_(variation.frictionScale),
        engine_(data.engine->create(withProtocolGravity(variation, setup.protocol))),
        sim_(*engine_),
        pd_(data.controller->p, data.controller->d),
        dt_(sim_.timeStep()),
        timeLimit_(setup.timeLimit > 0.0
                       ? setup.timeLimit
                       : std::max(10.0, setup.closeTimeLimit +
                                            trial::phasesDuration(setup.protocol) + 1.0)) {}

  GraspTrialResult run(const rw::kinematics::State& initial);

 private:
  bool inCollision(const rw::kinematics::State& state);
  bool advance(std::string_view phase);
  bool close();
  // The PD's speed limits: the device's (clampToVelocityLimits) and the protocol's closing
  // speeds, the smaller of both per joint; empty when neither applies.
  Q closingSpeedLimits(const rw::models::Device& device) const;
  // One value per active joint of `device`: `prismatic` for prismatic joints, else `revolute`.
  Q perJointType(const rw::models::Device& device, double prismatic, double revolute) const;
  bool gripForceReached() const;
  void noteClosingCap(const Q& v, const Q& restSpeed);
  bool runPhases();
  bool lift(const trial::ProtocolPhase& phase, const Transform3D& X_W_base);
  bool pull(const trial::ProtocolPhase& phase);
  bool followRamp(const trial::ProtocolPhase& phase, const Transform3D& X_W_base,
                  const Transform3D& X_end, std::string_view name);
  bool shake(const trial::ProtocolPhase& phase);
  bool settle(double time);
  void finish(GraspOutcome outcome, std::string detail = {}) {
    result_.outcome = outcome;
    result_.detail = std::move(detail);
  }
  void evaluate(const Transform3D& X_h0, const Transform3D& X_o0);
  GraspTrialResult withMessages() {
    if (!closingNote_.empty()) result_.detail += " [" + closingNote_ + "]";
    if (!sim_.engineMessages().empty()) result_.detail += " [" + sim_.engineMessages() + "]";
    return result_;
  }

  const dynamics::DynamicWorkCell& dwc_;
  const GraspTrialSetup& setup_;
  const detail::TrialData& data_;
  const GraspParameters& grasp_;
  const Observer& observer_;
  double frictionScale_;
  std::unique_ptr<trial::PhysicsEngine> engine_;
  trial::PhysicsEngine& sim_;
  control::PDController pd_;
  double dt_;
  // setup_.timeLimit; unset, 10 s or longer when the protocol's phases need it (closing's cap +
  // phases + 1 s).
  double timeLimit_;
  GraspTrialResult result_;
  std::string closingNote_;
};

bool TrialRun::inCollision(const rw::kinematics::State& state) {
  const PlacementCheck check = checkPlacement(dwc_, data_, state);
  if (!check.collides) return false;
  finish(GraspOutcome::kInCollision, check.detail);
  return true;
}

bool TrialRun::advance(std::string_view phase) {
  const auto hand = data_.hand;
  sim_.setMotorVelocityTargets(hand, pd_.update(sim_.jointPositions(hand), dt_));
  const StepStatus status = sim_.step();
  result_.simulatedTime = sim_.time();
  if (status != StepStatus::kOk) {
    finish(GraspOutcome::kSimulationFailure,
           std::string(status == StepStatus::kRunaway ? "runaway: " : "numerical failure: ") +
               sim_.failureDetail());
    return false;
  }
  if (observer_) observer_(sim_, phase);
  if (sim_.time() > timeLimit_) {
    finish(GraspOutcome::kTimeout,
           "simulated time passed the limit of " + std::to_string(timeLimit_) + " s");
    return false;
  }
  return true;
}

Q TrialRun::perJointType(const rw::models::Device& device, double prismatic,
                         double revolute) const {
  const auto& tree = dwc_.workcell().frames();
  const auto& active = device.activeJoints();
  Q values(static_cast<Eigen::Index>(active.size()));
  for (std::size_t i = 0; i < active.size(); ++i) {
    values[static_cast<Eigen::Index>(i)] =
        tree.frame(active[i]).type() == rw::kinematics::FrameType::kPrismatic ? prismatic
                                                                              : revolute;
  }
  return values;
}

Q TrialRun::closingSpeedLimits(const rw::models::Device& device) const {
  const trial::TrialProtocol& protocol = setup_.protocol;
  const bool capped = protocol.closingSpeed > 0.0 || protocol.closingAngularSpeed > 0.0;
  if (!capped) return setup_.clampToVelocityLimits ? device.velocityLimits() : Q();
  // A speed of 0 caps nothing.
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const auto cap = [](double speed) { return speed > 0.0 ? speed : kNone; };
  const Q caps =
      perJointType(device, cap(protocol.closingSpeed), cap(protocol.closingAngularSpeed));
  return setup_.clampToVelocityLimits ? Q(caps.cwiseMin(device.velocityLimits())) : caps;
}

bool TrialRun::close() {
  const Q restSpeed = perJointType(*dwc_.device(data_.hand).device, setup_.restSpeedPrismatic,
                                   setup_.restSpeedRevolute);
  double restSince = -1.0;
  while (true) {
    if (!advance("close")) return false;
    const double t = sim_.time();
    if (t < setup_.minCloseTime) continue;
    if (setup_.protocol.closing == trial::ClosingRule::kForceThreshold && gripForceReached()) break;
    const Q q = sim_.jointPositions(data_.hand);
    if ((q - grasp_.qClosed).cwiseAbs().maxCoeff() <= setup_.closedTolerance) break;
    const Q v = sim_.jointVelocities(data_.hand);
    if ((v.cwiseAbs().array() < restSpeed.array()).all()) {
      if (restSince < 0.0) restSince = t;
      if (t - restSince >= setup_.restTime - 1e-9) break;
    } else {
      restSince = -1.0;
    }
    if (t >= setup_.closeTimeLimit) {
      noteClosingCap(v, restSpeed);
      break;
    }
  }
  return true;
}

bool TrialRun::gripForceReached() const {
  const std::vector<double> force =
      detail::handNormalForces(sim_.contacts(), data_.isHandBody, setup_.contactForceThreshold);
  return std::any_of(data_.objects.begin(), data_.objects.end(), [&](dynamics::BodyId o) {
    return force[o.index()] > setup_.protocol.gripForce;
  });
}

void TrialRun::noteClosingCap(const Q& v, const Q& restSpeed) {
  Eigen::Index fastest = 0;
  // The joint furthest above its rest speed (a rest speed of 0, possible in a set-up, counts as
  // a tiny one: no 0/0).
  (v.cwiseAbs().array() / restSpeed.array().max(1e-12)).maxCoeff(&fastest);
  const auto& tree = dwc_.workcell().frames();
  const auto joint =
      dwc_.device(data_.hand).device->activeJoints()[static_cast<std::size_t>(fastest)];
  const bool prismatic = tree.frame(joint).type() == rw::kinematics::FrameType::kPrismatic;
  char text[160];
  std::snprintf(text, sizeof(text),
                ": %.3g s simulated with %s still at %.3g %s (at rest below %.3g)",
                setup_.closeTimeLimit, tree.frame(joint).name().c_str(), std::abs(v[fastest]),
                prismatic ? "m/s" : "rad/s", restSpeed[fastest]);
  result_.closingCapped = true;
  closingNote_ = std::string(kClosingCapNote) + text;
}

bool TrialRun::runPhases() {
  for (const trial::ProtocolPhase& phase : setup_.protocol.phases) {
    bool ok = false;
    switch (phase.kind) {
      case trial::PhaseKind::kLift:
        ok = lift(phase, sim_.bodyPose(data_.baseBody));
        break;
      case trial::PhaseKind::kPull:
        ok = pull(phase);
        break;
      case trial::PhaseKind::kShake:
        ok = shake(phase);
        break;
    }
    if (!ok) return false;
  }
  return true;
}

bool TrialRun::lift(const trial::ProtocolPhase& phase, const Transform3D& X_W_base) {
  Transform3D X_end = X_W_base;
  X_end.translation().z() += phase.distance;
  return followRamp(phase, X_W_base, X_end, "lift");
}

// The base moved from X_W_base to X_end on the phase's ramp (speed, acceleration), then
// `phase.settle` s at rest; `name` is the observer's phase.
bool TrialRun::followRamp(const trial::ProtocolPhase& phase, const Transform3D& X_W_base,
                          const Transform3D& X_end, std::string_view name) {
  control::RampLimits limits;
  limits.linearVelocity = phase.speed;
  limits.linearAcceleration = phase.acceleration;
  const control::RampTrajectory trajectory(X_W_base, X_end, limits);
  const double t0 = sim_.time();
  while (sim_.time() - t0 < trajectory.duration() - 1e-9) {
    const Transform3D next = trajectory.pose(sim_.time() - t0 + dt_);
    const control::Twist twist = control::twistToReach(sim_.bodyPose(data_.baseBody), next, dt_);
    sim_.setKinematicVelocity(data_.baseBody, twist.linear, twist.angular);
    if (!advance(name)) return false;
  }
  sim_.setKinematicVelocity(data_.baseBody, Vector3D::Zero(), Vector3D::Zero());
  return settle(phase.settle);
}

bool TrialRun::settle(double time) {
  const double t1 = sim_.time();
  while (sim_.time() - t1 < time - 1e-9) {
    if (!advance("settle")) return false;
  }
  return true;
}

// A phase's axis in world coordinates (unit length) and the point a rotation turns about.
struct PhaseAxis {
  Vector3D axis;
  Vector3D centre;
};

// The axis of `phase` (given in its frame: the world, the TCP at X_W_tcp, or the jaw frame at
// X_W_tcp X_tcp_jaw) and the origin of the TCP (of the jaw frame for frame "jaw").
PhaseAxis phaseAxis(const trial::ProtocolPhase& phase, Transform3D X_W_tcp,
                    const std::optional<Transform3D>& X_tcp_jaw) {
  if (phase.frame == trial::AxisFrame::kJaw) X_W_tcp = X_W_tcp * X_tcp_jaw.value();
  const Vector3D axis = phase.frame == trial::AxisFrame::kWorld
                            ? phase.axis
                            : Vector3D(X_W_tcp.linear() * phase.axis);
  return {axis.normalized(), X_W_tcp.translation()};
}

bool TrialRun::pull(const trial::ProtocolPhase& phase) {
  const Transform3D X_W_base = sim_.bodyPose(data_.baseBody);
  const Transform3D X_W_tcp =
      rw::kinematics::worldTransform(dwc_.workcell().frames(), sim_.state(), data_.tcp);
  Transform3D X_end = X_W_base;
  X_end.translation() += phase.distance * phaseAxis(phase, X_W_tcp, setup_.X_tcp_jaw).axis;
  return followRamp(phase, X_W_base, X_end, "pull");
}

// The base follows X_W_base0 moved by s(t) = A (1 - cos(2 pi f t)) along the axis, or turned by
// s(t) about the axis through the TCP origin (the jaw frame's for frame "jaw"): at rest at the
// start and after every period, peak acceleration A (2 pi f)^2.
bool TrialRun::shake(const trial::ProtocolPhase& phase) {
  const Transform3D X_W_base0 = sim_.bodyPose(data_.baseBody);
  const Transform3D X_W_tcp0 =
      rw::kinematics::worldTransform(dwc_.workcell().frames(), sim_.state(), data_.tcp);
  // Named copies, not a structured binding: the lambda below captures them (clang 14, the fuzz
  // build's compiler, refuses to capture a binding).
  const PhaseAxis along = phaseAxis(phase, X_W_tcp0, setup_.X_tcp_jaw);
  const Vector3D u = along.axis;
  const Vector3D centre = along.centre;
  const double omega = 2.0 * std::numbers::pi * phase.frequency;
  const double duration = phase.cycles / phase.frequency;
  const auto pose = [&](double t) {
    const double s = phase.amplitude * (1.0 - std::cos(omega * std::min(t, duration)));
    Transform3D X = X_W_base0;
    if (phase.rotation) {
      const rw::math::Rotation3D R(Eigen::AngleAxisd(s, u));
      X.linear() = R * X_W_base0.linear();
      X.translation() = centre + R * (X_W_base0.translation() - centre);
    } else {
      X.translation() += s * u;
    }
    return X;
  };
  const double t0 = sim_.time();
  while (sim_.time() - t0 < duration - 1e-9) {
    const Transform3D next = pose(sim_.time() - t0 + dt_);
    const control::Twist twist = control::twistToReach(sim_.bodyPose(data_.baseBody), next, dt_);
    sim_.setKinematicVelocity(data_.baseBody, twist.linear, twist.angular);
    if (!advance("shake")) return false;
  }
  sim_.setKinematicVelocity(data_.baseBody, Vector3D::Zero(), Vector3D::Zero());
  return settle(phase.settle);
}

void TrialRun::evaluate(const Transform3D& X_h0, const Transform3D& X_o0) {
  const dynamics::BodyId object = result_.object;
  const auto counts =
      detail::handContactCounts(sim_.contacts(), data_.isHandBody, setup_.contactForceThreshold);
  const Transform3D X_h1 = sim_.bodyPose(data_.baseBody);
  const Transform3D X_o1 = sim_.bodyPose(object);
  result_.handLift = X_h1.translation() - X_h0.translation();
  result_.objectLift = X_o1.translation() - X_o0.translation();
  const bool lifted = setup_.protocol.phases.size() == 1 &&
                      setup_.protocol.phases.front().kind == trial::PhaseKind::kLift;
  if (counts[object.index()] == 0) {
    finish(GraspOutcome::kDropped, "no hand contact on " + dwc_.body(object).name +
                                       (lifted ? " after lifting" : " after the phases"));
    return;
  }
  std::vector<TrialContact> contacts =
      detail::objectContacts(dwc_, sim_.contacts(), data_.isHandBody, object, X_o1,
                             setup_.contactForceThreshold, frictionScale_);
  if (setup_.protocol.success == trial::SuccessRule::kTwoFingers) {
    std::vector<dynamics::BodyId> fingers;
    for (const TrialContact& c : contacts) {
      if (c.handBody != data_.baseBody &&
          std::find(fingers.begin(), fingers.end(), c.handBody) == fingers.end()) {
        fingers.push_back(c.handBody);
      }
    }
    if (fingers.size() < 2) {
      finish(GraspOutcome::kDropped, dwc_.body(object).name + " touches " +
                                         std::to_string(fingers.size()) +
                                         " finger link(s) after the phases, not two");
      return;
    }
  }
  const double drift = (result_.objectLift - result_.handLift).norm();
  const double h = result_.handLift.norm();
  result_.qLift = h > 0.0 ? std::max(0.0, 1.0 - drift / h) : 0.0;
  result_.contacts = std::move(contacts);
  const auto& body = dwc_.body(object);
  if (setup_.computeGws) {
    GwsQualityOptions options;
    options.coneEdges = setup_.gwsConeEdges;
    const GwsQualities q =
        gwsQualities(result_.contacts, body.mass.cog, data_.radius[object.index()], options);
    result_.qGws = q.qGws;
    result_.qGwsUnit = q.qGwsUnit;
  }
  finish(drift < setup_.slipThreshold ? GraspOutcome::kStable : GraspOutcome::kSlipped,
         "object drift " + std::to_string(drift) + " m during " +
             (lifted ? "a lift of " + std::to_string(h) + " m"
                     : "the phases (hand moved " + std::to_string(h) + " m)"));
}

/// `initial` with the hand at qOpen and its base placed so that the TCP is at X_W_tcp.
rw::kinematics::State placeHand(const dynamics::DynamicWorkCell& dwc, const detail::TrialData& data,
                                const GraspParameters& grasp,
                                const rw::kinematics::State& initial) {
  const auto& tree = dwc.workcell().frames();
  const auto& device = *dwc.device(data.hand).device;
  rw::kinematics::State state = initial;
  device.setQ(grasp.qOpen, state);
  const Transform3D X_tcp_base =
      rw::kinematics::relativeTransform(tree, state, data.tcp, data.baseFrame);
  const Transform3D X_W_base = grasp.X_W_tcp * X_tcp_base;
  const Transform3D X_W_parent =
      rw::kinematics::worldTransform(tree, state, state.parentOf(data.baseFrame));
  tree.frame(data.baseFrame).setMovableTransform(state, X_W_parent.inverse() * X_W_base);
  return state;
}

GraspTrialResult TrialRun::run(const rw::kinematics::State& initial) {
  const auto& device = *dwc_.device(data_.hand).device;
  const rw::kinematics::State state = placeHand(dwc_, data_, grasp_, initial);
  result_.qGrasp = grasp_.qOpen;
  if (inCollision(state)) return result_;

  sim_.reset(state);
  if (grasp_.tauMax.size() > 0) sim_.setMotorForceLimits(data_.hand, grasp_.tauMax);
  pd_.reset(grasp_.qOpen);
  if (const Q limits = closingSpeedLimits(device); limits.size() > 0) pd_.setVelocityLimits(limits);
  pd_.setTarget(grasp_.qClosed);
  if (!close()) return withMessages();
  result_.qGrasp = sim_.jointPositions(data_.hand);

  const auto counts =
      detail::handContactCounts(sim_.contacts(), data_.isHandBody, setup_.contactForceThreshold);
  int best = 0;
  for (const dynamics::BodyId o : data_.objects) {
    if (counts[o.index()] > best) {
      best = counts[o.index()];
      result_.object = o;
    }
  }
  if (!result_.object.valid()) {
    finish(GraspOutcome::kMissed, "no finger touches an object after closing");
    return withMessages();
  }
  const Transform3D X_h0 = sim_.bodyPose(data_.baseBody);
  const Transform3D X_o0 = sim_.bodyPose(result_.object);
  if (runPhases()) evaluate(X_h0, X_o0);
  return withMessages();
}

}  // namespace

GraspTrial::GraspTrial(const dynamics::DynamicWorkCell& dwc, GraspTrialSetup setup,
                       std::shared_ptr<const trial::EngineFactory> engine)
    : dwc_(&dwc), setup_(std::move(setup)) {
  trial::checkProtocol(setup_.protocol);
  auto data = prepare(dwc, setup_);
  classifyBodies(dwc, *data);
  data->detector = std::make_shared<contacts::ContactDetector>(
      dwc, setup_.simulator.contacts, dynamics::jointConnectedBodyPairs(dwc));
  data->engine =
      engine ? std::move(engine) : odeEngineFactory(dwc, setup_.simulator, data->detector);
  data->collision = std::make_unique<rw::proximity::CollisionDetector>(dwc.workcell());
  prepareFrameShapes(dwc, *data);
  data_ = std::move(data);
}

dynamics::DeviceId GraspTrial::handDevice() const { return data_->hand; }

const trial::EngineFactory& GraspTrial::engine() const { return *data_->engine; }

bool GraspTrial::isHandBody(dynamics::BodyId body) const {
  return body.valid() && body.index() < data_->isHandBody.size() && data_->isHandBody[body.index()];
}

rw::kinematics::State GraspTrial::placedState(const GraspParameters& grasp,
                                              const rw::kinematics::State& initial) const {
  const auto& device = *dwc_->device(data_->hand).device;
  checkGrasp(grasp, device.dof());
  return placeHand(*dwc_, *data_, grasp, initial);
}

FrameId GraspTrial::tcpFrame() const { return data_->tcp; }

PlacementCheck GraspTrial::checkPlacement(const GraspParameters& grasp,
                                          const rw::kinematics::State& initial) const {
  return simulator::checkPlacement(*dwc_, *data_, placedState(grasp, initial));
}

GraspTrialResult GraspTrial::run(const GraspParameters& grasp,
                                 const rw::kinematics::State& initial) const {
  return run(grasp, initial, setup_.observer);
}

GraspTrialResult GraspTrial::run(const GraspParameters& grasp, const rw::kinematics::State& initial,
                                 const Observer& observer) const {
  return run(grasp, initial, PhysicsVariation{}, observer);
}

GraspTrialResult GraspTrial::run(const GraspParameters& grasp, const rw::kinematics::State& initial,
                                 const PhysicsVariation& variation) const {
  return run(grasp, initial, variation, setup_.observer);
}

GraspTrialResult GraspTrial::run(const GraspParameters& grasp, const rw::kinematics::State& initial,
                                 const PhysicsVariation& variation,
                                 const Observer& observer) const {
  const auto& device = *dwc_->device(data_->hand).device;
  checkGrasp(grasp, device.dof());
  variation.check();
  TrialRun trial(*dwc_, setup_, *data_, grasp, variation, observer);
  return trial.run(initial);
}

}  // namespace rwsim::simulator
