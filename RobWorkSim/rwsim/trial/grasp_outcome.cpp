#include <cstddef>
#include <string_view>

#include "rwsim/trial/grasp_outcome.hpp"

namespace rwsim::trial {

namespace {

// RobWork codes are GraspResult::TestStatus (reference §3.2). "In collision" maps to 2
// (CollisionInitially), as the VisGraB-era SimTaskPlugin reported it; which of RobWork's newer
// codes 11 (object) / 12 (environment) would apply is said in the trial's detail text.
constexpr std::array<OutcomeInfo, 8> kRows = {{
    {GraspOutcome::kStable, "stable", 1},
    {GraspOutcome::kSlipped, "slipped", 5},
    {GraspOutcome::kDropped, "dropped", 4},
    {GraspOutcome::kMissed, "missed", 3},
    {GraspOutcome::kInCollision, "in_collision", 2},
    {GraspOutcome::kInvalidContacts, "invalid_contacts", 8},
    {GraspOutcome::kSimulationFailure, "simulation_failure", 7},
    {GraspOutcome::kTimeout, "timeout", 6},
}};

constexpr bool rowsInEnumOrder() {
  for (std::size_t i = 0; i < kRows.size(); ++i) {
    if (static_cast<std::size_t>(kRows[i].outcome) != i) return false;
  }
  return true;
}

static_assert(kRows.size() == static_cast<std::size_t>(GraspOutcome::kTimeout) + 1,
              "kOutcomeTable needs one row per GraspOutcome");
static_assert(rowsInEnumOrder(), "kOutcomeTable rows must follow the GraspOutcome order");

}  // namespace

const std::array<OutcomeInfo, 8> kOutcomeTable = kRows;

std::string_view outcomeName(GraspOutcome outcome) {
  return kOutcomeTable[static_cast<std::size_t>(outcome)].name;
}

int robworkCode(GraspOutcome outcome) {
  return kOutcomeTable[static_cast<std::size_t>(outcome)].robworkCode;
}

bool closingHitCap(std::string_view detail) {
  return detail.find(kClosingCapNote) != std::string_view::npos;
}

std::optional<GraspOutcome> outcomeFromName(std::string_view name) {
  for (const OutcomeInfo& row : kOutcomeTable) {
    if (row.name == name) return row.outcome;
  }
  return std::nullopt;
}

}  // namespace rwsim::trial
