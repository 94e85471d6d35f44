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
#include "rwsim/trial/trial_types.hpp"

namespace rwsim::simulator {

namespace detail {
struct TrialData;
}  // namespace detail

// The trial's value types live in rwsim_trial (engine-free); these names keep the simulator's
// callers unchanged.
using trial::closingHitCap;
using trial::GraspOutcome;
using trial::GraspParameters;
using trial::GraspTrialResult;
using trial::GraspTrialSetup;
using trial::kClosingCapNote;
using trial::kOutcomeTable;
using trial::Observer;
using trial::outcomeFromName;
using trial::OutcomeInfo;
using trial::outcomeName;
using trial::PhysicsVariation;
using trial::PlacementCheck;
using trial::robworkCode;
using trial::TrialContact;

/// Runs grasp trials on one dynamic workcell (const; each run() makes its own engine, so many
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
///     fingers are static"), or at closeTimeLimit; under the protocol's force rule also as soon
///     as the hand's total normal force on one object exceeds TrialProtocol::gripForce.
///  3. No hand-object contact with a normal force above contactForceThreshold: kMissed. The
///     grasped object is the rigid non-hand body with most such contact points (ties: the lower
///     body index).
///  4. The protocol's phases (setup.protocol; the paper's: the base moves 10 cm straight up
///     (world z) on a ramp of 0.5 m/s and 1 m/s^2, then settles for 0.2 s), driven as kinematic
///     velocities of the base with the controller still closing. Without the protocol's gravity
///     the engine has none (PhysicsVariation::gravity).
///  5. No hand contact on the object (success rule "two fingers": fewer than two finger links,
///     hand bodies other than the base, touch it): kDropped. Else, with h and o the hand's and
///     the object's displacement during the phases, drift = |o - h|, Q_lift = max(0, 1 - drift /
///     |h|) (paper eq. 5; 0 when the hand ends where it started, as after a shake), kStable if
///     drift < slipThreshold, else kSlipped; Q_GWS and Q_GWS,unit from the contacts after the
///     phases (gwsQualities(): gwsConeEdges edges, torques about the object's COG over r, the
///     largest distance of its collision geometry from the COG).
/// A failing step gives kSimulationFailure, passing timeLimit kTimeout (detail says why).
class GraspTrial {
 public:
  /// Trials on the engine `engine` makes (null: ODE with setup.simulator, the benchmark's engine).
  /// @throws std::invalid_argument if the hand, controller or TCP frame is unknown, the hand's
  /// base is not a kinematic body, the controller drives another device, or the protocol is
  /// invalid (trial::checkProtocol()).
  GraspTrial(const dynamics::DynamicWorkCell& dwc, GraspTrialSetup setup,
             std::shared_ptr<const trial::EngineFactory> engine = nullptr);
  /// Places the hand, closes, lifts and classifies. `initial` gives the objects' poses.
  /// Deterministic: the same input gives the same result in any thread.
  /// @throws std::invalid_argument if qOpen, qClosed or a non-empty tauMax does not have one
  /// value per DOF of the hand, or tauMax has a negative entry.
  GraspTrialResult run(const GraspParameters& grasp, const rw::kinematics::State& initial) const;
  /// Same, calling `observer` instead of the setup's (e.g. to record one trial's trajectory).
  GraspTrialResult run(const GraspParameters& grasp, const rw::kinematics::State& initial,
                       const Observer& observer) const;
  /// Same as run(grasp, initial), on an engine made with `variation`
  /// (EngineFactory::create(variation)): the friction coefficients and object masses the trial
  /// simulates are the dwc's scaled by it, and TrialContact::mu, hence Q_GWS, uses the scaled
  /// friction. The identity gives run(grasp, initial)'s result bit for bit.
  /// @throws std::invalid_argument like run(), or for an invalid variation
  /// (PhysicsVariation::check()) or one the engine cannot honour.
  GraspTrialResult run(const GraspParameters& grasp, const rw::kinematics::State& initial,
                       const trial::PhysicsVariation& variation) const;
  /// Same, calling `observer` instead of the setup's.
  GraspTrialResult run(const GraspParameters& grasp, const rw::kinematics::State& initial,
                       const trial::PhysicsVariation& variation, const Observer& observer) const;
  /// The setup in use.
  const GraspTrialSetup& setup() const { return setup_; }
  /// The engine the trials run on.
  const trial::EngineFactory& engine() const;
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
