#pragma once

#include <array>
#include <optional>
#include <string_view>

/// The grasp trial's value types, engine-free: what the results, formats and analyses read.
namespace rwsim::trial {

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

/// True for the outcomes the paper counts as a successful grasp (§2.4: "stable grasp" or
/// "object slipped": the object is in the hand after lifting).
constexpr bool isHeld(GraspOutcome outcome) {
  return outcome == GraspOutcome::kStable || outcome == GraspOutcome::kSlipped;
}

/// True for the outcomes decided before any simulation (the placement's collision test and the
/// grasp utilities' contact IK): two engines agree on them by construction.
constexpr bool isDecidedBeforeSimulation(GraspOutcome outcome) {
  return outcome == GraspOutcome::kInCollision || outcome == GraspOutcome::kInvalidContacts;
}

/// The words a trial's detail carries when its closing ran into the closing time limit before
/// the fingers came to rest (the grasp was then judged as it stood); see
/// GraspTrialResult::closingCapped.
inline constexpr std::string_view kClosingCapNote = "closing hit the cap";
/// Whether a trial's detail (as written to trials.csv) says its closing hit the cap (how the
/// flag is recovered from trials.csv files older than its own column).
bool closingHitCap(std::string_view detail);

}  // namespace rwsim::trial
