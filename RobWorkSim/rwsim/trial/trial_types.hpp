#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/math/types.hpp"
#include "rwsim/contacts/contact_detector.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/trial/grasp_outcome.hpp"
#include "rwsim/trial/physics_engine.hpp"
#include "rwsim/trial/trial_protocol.hpp"

namespace rwsim::trial {

/// The grasp to execute: paper eq. 1.
struct GraspParameters {
  /// World pose of the hand's TCP frame at the grasp.
  rw::math::Transform3D X_W_tcp = rw::math::Transform3D::Identity();
  /// Configuration when placed.
  rw::math::Q qOpen;
  /// Configuration the fingers close towards.
  rw::math::Q qClosed;
  /// Motor torque limit per DOF (empty: the dwc's ForceLimits).
  rw::math::Q tauMax;
};

/// Engine settings; defaults follow RobWork's ODE simulator (reference §8.3), overridable from
/// the dwc file's PhysicsEngine properties.
struct SimulatorOptions {
  /// Integration step, s (RobWork's grasp simulator uses 0.005).
  double timeStep = 0.005;
  /// "WorldStep" (dense LCP) or "WorldQuickStep" (iterative).
  std::string stepMethod = "WorldStep";
  /// Global constraint force mixing.
  double worldCfm = 1e-7;
  /// Global error reduction parameter.
  double worldErp = 0.2;
  /// Allowed penetration before correction, m.
  double contactSurfaceLayer = 0.0001;
  /// Largest velocity used to correct penetration, m/s.
  double maxCorrectingVelocity = 0.1;
  /// Contact generation.
  contacts::ContactOptions contacts;
  /// Constraint force mixing of contact joints (RobWork: 1e-6).
  double contactCfm = 1e-6;
  /// Error reduction parameter of contact joints (RobWork: 0.2).
  double contactErp = 0.2;
  /// A body faster than this (m/s) or farther than escapeDistance from its start is a failure.
  double maxSpeed = 50.0;
  /// See maxSpeed, m.
  double escapeDistance = 50.0;
};

/// Which hand and how to run trials.
struct GraspTrialSetup {
  /// Rigid device name of the hand.
  std::string hand;
  /// PD controller name.
  std::string controller = "GraspController";
  /// TCP frame (full name); empty: "<hand>.TCP" if it exists, else the hand's base frame.
  std::string tcpFrame;
  /// The hand's parallel-jaw frame in its TCP frame (z the approach, x the closing axis, origin
  /// between the pads), which protocol axes in frame "jaw" (AxisFrame::kJaw) are given in; none:
  /// the hand has none, and such a protocol is an error.
  std::optional<rw::math::Transform3D> X_tcp_jaw;
  /// What the trial does after placing the hand and how it judges the grasp (gravity, closing
  /// rule, motion phases, success rule); default: the paper's lift of 10 cm.
  TrialProtocol protocol;
  /// Drift of the object in the hand above which a held grasp is "slipped", m (RobWork: 1 cm).
  double slipThreshold = 0.01;
  /// Simulated-time limit, s (passing it ends the trial as kTimeout); 0 (the default): 10 s, or
  /// longer when the protocol needs it (closeTimeLimit + trial::phasesDuration + 1 s).
  double timeLimit = 0.0;
  /// Closing ends at the latest after this long (then the grasp is evaluated as it is), s.
  double closeTimeLimit = 5.0;
  /// Closing is not judged before this, s.
  double minCloseTime = 0.2;
  /// The fingers are static when every active joint is slower than this (rad/s, revolute) ...
  double restSpeedRevolute = 0.01;
  /// ... or this (m/s, prismatic) ...
  double restSpeedPrismatic = 0.001;
  /// ... for this long without a break, s.
  double restTime = 0.1;
  /// Or when every joint is this close to qClosed (rad or m).
  double closedTolerance = 1e-3;
  /// Clamp the PD commands to the joint velocity limits (RobWork does not; clamping lets fingers
  /// lose contact when a held object shifts, so it is off by default).
  bool clampToVelocityLimits = false;
  /// A contact counts when its normal force exceeds this, N (the legacy plugin's filter).
  double contactForceThreshold = 1e-4;
  /// Cone edges for Q_GWS and Q_GWS,unit (RobWork: 10).
  int gwsConeEdges = 10;
  /// Compute Q_GWS and Q_GWS,unit (6-D hulls, often the dearest part of a trial); false leaves
  /// both 0.
  bool computeGws = true;
  /// The ODE engine's settings (the default engine; another engine brings its own).
  SimulatorOptions simulator;
  /// Called after every successful step with the engine and the phase ("close", "lift",
  /// "shake", "pull", "settle"), e.g. to record a trajectory. Runs on the thread that runs the
  /// trial.
  std::function<void(const PhysicsEngine&, std::string_view phase)> observer;
};

/// See GraspTrialSetup::observer.
using Observer = std::function<void(const PhysicsEngine&, std::string_view phase)>;

/// A contact on the grasped object after lifting, in the object's frame.
struct TrialContact {
  /// Position.
  rw::math::Vector3D position;
  /// Unit normal pointing into the object.
  rw::math::Vector3D normal;
  /// Normal force magnitude, N.
  double normalForce = 0.0;
  /// Friction coefficient of the pair.
  double mu = 0.0;
  /// The whole contact force on the object (normal and friction), N: the paper's f_i.
  rw::math::Vector3D force = rw::math::Vector3D::Zero();
  /// The hand link that touches the object.
  dynamics::BodyId handBody;
};

/// What a trial measured.
struct GraspTrialResult {
  /// Outcome.
  GraspOutcome outcome = GraspOutcome::kSimulationFailure;
  /// Paper eq. 5 (0 when not held).
  double qLift = 0.0;
  /// Q_GWS as the paper's tables computed it (§2.4.1, eq. 6-7): Ferrari-Canny L1 epsilon after
  /// lifting with cones centred on the measured contact forces (see gwsQualities() in
  /// grasp_quality.hpp); 0 when not held.
  double qGws = 0.0;
  /// The same with unit normal forces and cones on the contact normals (RobWork's
  /// GraspTaskSimulator; this project's Q_GWS before the paper's definition); 0 when not held.
  double qGwsUnit = 0.0;
  /// The grasped object (none if none).
  dynamics::BodyId object;
  /// Hand configuration when the fingers came to rest.
  rw::math::Q qGrasp;
  /// Contacts on the object after lifting.
  std::vector<TrialContact> contacts;
  /// Simulated time used, s.
  double simulatedTime = 0.0;
  /// Free text about failures; ends with "[closing hit the cap: ...]" when closingCapped.
  std::string detail;
  /// The closing phase ran into GraspTrialSetup::closeTimeLimit with the fingers still moving
  /// (the rest test not met): the grasp was judged as it stood.
  bool closingCapped = false;
  /// Hand displacement during the protocol's phases (paper eq. 5, h: the lift), m.
  rw::math::Vector3D handLift = rw::math::Vector3D::Zero();
  /// Object displacement during the protocol's phases (paper eq. 5, o), m.
  rw::math::Vector3D objectLift = rw::math::Vector3D::Zero();
};

/// Whether a hand placed for a grasp penetrates the scene (step 1 of a trial).
struct PlacementCheck {
  /// True when some hand frame's collision geometry overlaps a non-hand frame's.
  bool collides = false;
  /// True when the deepest such pair involves an object (RobWork 11), false for the environment
  /// (RobWork 12); meaningful only when `collides`.
  bool withObject = false;
  /// Deepest overlap over the colliding pairs, m (0 when free): the largest contact depth the
  /// simulator's own contact generation (margin 0) finds between their geometries.
  double penetration = 0.0;
  /// The deepest pair, e.g. "hand frame SchunkHand.f1.Link3 penetrates object frame
  /// cocacola by 4.1 mm (RobWork 11 CollisionObjectInitially)"; empty when free.
  std::string detail;
};

}  // namespace rwsim::trial
