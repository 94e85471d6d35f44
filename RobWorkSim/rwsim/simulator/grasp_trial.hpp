#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/kinematics/state.hpp"
#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/simulator/simulator.hpp"

namespace rwsim::simulator {

namespace detail {
struct TrialData;
}  // namespace detail

/// How a grasp trial ended (paper §2.4).
enum class GraspOutcome {
  kStable,             ///< held after lifting, drift below the slip threshold
  kSlipped,            ///< held after lifting, drifted more
  kDropped,            ///< touched, but not held after lifting
  kMissed,             ///< no finger touched the object after closing
  kInCollision,        ///< the hand penetrated an object or the table at its start pose
  kInvalidContacts,    ///< the contact IK found no configuration (set by grasp utilities)
  kSimulationFailure,  ///< NaN, runaway or exploding bodies
  kTimeout,            ///< the simulated-time limit passed
};

/// Name and RobWork status code of an outcome.
struct OutcomeInfo {
  /// The outcome.
  GraspOutcome outcome;
  /// Lower-case name used in files ("stable", "slipped", ...).
  std::string_view name;
  /// RobWork's GraspResult::TestStatus (reference §3.2).
  int robworkCode;
};

/// One row per outcome, in enum order (a static_assert in the source checks size and order):
/// stable 1, slipped 5, dropped 4, missed 3, in_collision 2 (RobWork's CollisionInitially, as
/// VisGraB's plugin reported it; the trial's detail says 11 or 12 for RobWork's newer split),
/// invalid_contacts 8, simulation_failure 7, timeout 6.
extern const std::array<OutcomeInfo, 8> kOutcomeTable;

/// Name of an outcome.
std::string_view outcomeName(GraspOutcome outcome);
/// RobWork status code of an outcome.
int robworkCode(GraspOutcome outcome);
/// The outcome with this name (as in kOutcomeTable), if any.
std::optional<GraspOutcome> outcomeFromName(std::string_view name);

/// The words a trial's detail carries when its closing ran into GraspTrialSetup::closeTimeLimit
/// before the fingers came to rest (the grasp was then judged as it stood); see
/// GraspTrialResult::closingCapped.
inline constexpr std::string_view kClosingCapNote = "closing hit the cap";
/// Whether a trial's detail (as written to trials.csv) says its closing hit the cap.
bool closingHitCap(std::string_view detail);

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

/// Which hand and how to run trials.
struct GraspTrialSetup {
  /// Rigid device name of the hand.
  std::string hand;
  /// PD controller name.
  std::string controller = "GraspController";
  /// TCP frame (full name); empty: "<hand>.TCP" if it exists, else the hand's base frame.
  std::string tcpFrame;
  /// Lift height, m (paper: 10 cm).
  double liftHeight = 0.10;
  /// Drift of the object in the hand above which a held grasp is "slipped", m (RobWork: 1 cm).
  double slipThreshold = 0.01;
  /// Simulated-time limit, s.
  double timeLimit = 10.0;
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
  /// Lift ramp: top speed (m/s) and acceleration (m/s^2); RobWork's body controller defaults.
  double liftSpeed = 0.5;
  /// See liftSpeed.
  double liftAcceleration = 1.0;
  /// Time after the lift before judging it, s.
  double settleTime = 0.2;
  /// A contact counts when its normal force exceeds this, N (the legacy plugin's filter).
  double contactForceThreshold = 1e-4;
  /// Cone edges for Q_GWS and Q_GWS,unit (RobWork: 10).
  int gwsConeEdges = 10;
  /// Compute Q_GWS and Q_GWS,unit (6-D hulls, often the dearest part of a trial); false leaves
  /// both 0.
  bool computeGws = true;
  /// Simulator settings.
  SimulatorOptions simulator;
  /// Called after every successful step with the simulator and the phase ("close", "lift",
  /// "settle"), e.g. to record a trajectory. Runs on the thread that runs the trial.
  std::function<void(const Simulator&, std::string_view phase)> observer;
};

/// See GraspTrialSetup::observer.
using Observer = std::function<void(const Simulator&, std::string_view phase)>;

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
  /// Hand displacement during the lift (paper eq. 5, h), m.
  rw::math::Vector3D handLift = rw::math::Vector3D::Zero();
  /// Object displacement during the lift (paper eq. 5, o), m.
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

/// Runs grasp trials on one dynamic workcell (const; each run() makes its own Simulator, so many
/// threads may run trials on one GraspTrial). A trial (reference §4 adapted to the paper, §2.4):
///  1. The hand's kinematic base is placed so that the TCP is at X_W_tcp with the hand at qOpen.
///     If rw_proximity's collision detector reports a pair of a hand frame and a non-hand frame,
///     the outcome is kInCollision (RobWork code 2; the detail names the deepest pair, its
///     penetration and whether RobWork's newer code would be 11, object, or 12, environment).
///     Nothing is simulated. checkPlacement() is this test on its own.
///  2. Closing: the PD controller (RobWork's law, velocity output) drives towards qClosed with
///     the motors' torque limited by tauMax (empty: the dwc's ForceLimits). It ends, not before
///     minCloseTime, when every joint is within closedTolerance of qClosed, or every active
///     joint stays slower than restSpeedRevolute / restSpeedPrismatic for restTime ("the
///     fingers are static"), or at closeTimeLimit.
///  3. No hand-object contact with a normal force above contactForceThreshold: kMissed. The
///     grasped object is the rigid non-hand body with most such contact points (ties: the lower
///     body index).
///  4. Lifting: the base moves liftHeight straight up (world z) on a ramp (liftSpeed,
///     liftAcceleration) with the controller still closing, then settles for settleTime.
///  5. No hand contact on the object: kDropped. Else, with h and o the hand's and the object's
///     displacement during lifting, drift = |o - h|, Q_lift = max(0, 1 - drift / |h|) (paper
///     eq. 5), kStable if drift < slipThreshold, else kSlipped; Q_GWS and Q_GWS,unit from the
///     contacts after lifting (gwsQualities(): gwsConeEdges edges, torques about the object's
///     COG over r, the largest distance of its collision geometry from the COG).
/// A failing step gives kSimulationFailure, passing timeLimit kTimeout (detail says why).
class GraspTrial {
 public:
  /// @throws std::invalid_argument if the hand, controller or TCP frame is unknown, the hand's
  /// base is not a kinematic body, or the controller drives another device.
  GraspTrial(const dynamics::DynamicWorkCell& dwc, GraspTrialSetup setup);
  /// Places the hand, closes, lifts and classifies. `initial` gives the objects' poses.
  /// Deterministic: the same input gives the same result in any thread.
  /// @throws std::invalid_argument if qOpen, qClosed or a non-empty tauMax does not have one
  /// value per DOF of the hand, or tauMax has a negative entry.
  GraspTrialResult run(const GraspParameters& grasp, const rw::kinematics::State& initial) const;
  /// Same, calling `observer` instead of the setup's (e.g. to record one trial's trajectory).
  GraspTrialResult run(const GraspParameters& grasp, const rw::kinematics::State& initial,
                       const Observer& observer) const;
  /// The setup in use.
  const GraspTrialSetup& setup() const { return setup_; }
  /// The state a trial starts from (step 1): `initial` with the hand at qOpen and its base
  /// placed so that the TCP is at X_W_tcp. @throws std::invalid_argument like run().
  rw::kinematics::State placedState(const GraspParameters& grasp,
                                    const rw::kinematics::State& initial) const;
  /// Step 1 alone: does the hand, placed for `grasp` in `initial`, penetrate the scene, and how
  /// deeply (the trial's own in-collision test; thread-safe, no simulation).
  /// @throws std::invalid_argument like run().
  PlacementCheck checkPlacement(const GraspParameters& grasp,
                                const rw::kinematics::State& initial) const;
  /// Index of the hand in DynamicWorkCell::devices().
  dynamics::DeviceId handDevice() const;
  /// True if body `body` (index in DynamicWorkCell::bodies()) is the hand's base or a link.
  bool isHandBody(dynamics::BodyId body) const;
  /// The TCP frame used.
  rw::kinematics::FrameId tcpFrame() const;

 private:
  const dynamics::DynamicWorkCell* dwc_;
  GraspTrialSetup setup_;
  std::shared_ptr<const detail::TrialData> data_;
};

}  // namespace rwsim::simulator
