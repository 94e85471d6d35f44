#include "visgrab/results/trial_columns.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "visgrab/database/scene_set.hpp"
#include "visgrab/results/csv.hpp"

namespace visgrab::results {

namespace {

using rwsim::trial::GraspOutcome;

// A Q value: empty means "not computed" (NaN).
std::string formatQuality(double q) { return std::isnan(q) ? std::string() : formatDouble(q); }

double parseQuality(const std::string& field) {
  return field.empty() ? std::numeric_limits<double>::quiet_NaN() : parseDouble(field);
}

std::string nonEmpty(const std::string& field, const char* what) {
  if (field.empty()) throw std::invalid_argument(std::string("empty ") + what);
  return field;
}

// Each column's three functions, as captureless lambdas (the table holds function pointers).
constexpr std::array<TrialColumn, 15> kColumns = {{
    {"scene", "scene", "The scene id.", [](const TrialRecord& t) { return csvField(t.sceneId); },
     [](const std::string& f, TrialRecord& t) { t.sceneId = nonEmpty(f, "scene id"); },
     [](const TrialRecord& t) { return TrialValue(t.sceneId); }},
    {"method", "method", "The method (grasp list field 2).",
     [](const TrialRecord& t) { return csvField(t.method); },
     [](const std::string& f, TrialRecord& t) { t.method = nonEmpty(f, "method"); },
     [](const TrialRecord& t) { return TrialValue(t.method); }},
    {"grasp", "id", "The grasp id.", [](const TrialRecord& t) { return csvField(t.graspId); },
     [](const std::string& f, TrialRecord& t) { t.graspId = f; },
     [](const TrialRecord& t) { return TrialValue(t.graspId); }},
    {"rank", "rank", "0-based position among the scene's grasps of this method, as given.",
     [](const TrialRecord& t) { return std::to_string(t.rank); },
     [](const std::string& f, TrialRecord& t) {
       t.rank = parseInt(f);
       if (t.rank < 0) throw std::invalid_argument("negative rank " + f);
     },
     [](const TrialRecord& t) { return TrialValue(static_cast<long long>(t.rank)); }},
    {"repeat", "repeat",
     "Which run of the grasp: 0 unperturbed, 1..N-1 under the noise model's seeded perturbations "
     "(columns written only by a run with --repeats N > 1).",
     [](const TrialRecord& t) { return std::to_string(t.repeat); },
     [](const std::string& f, TrialRecord& t) {
       t.repeat = parseInt(f);
       if (t.repeat < 0) throw std::invalid_argument("negative repeat " + f);
     },
     [](const TrialRecord& t) { return TrialValue(static_cast<long long>(t.repeat)); }, true},
    {"seed", "seed", "The seed (63 bits) of the repeat's perturbation (0 for repeat 0).",
     [](const TrialRecord& t) { return std::to_string(t.seed); },
     [](const std::string& f, TrialRecord& t) {
       const bool digits =
           !f.empty() && f.size() <= 20 && f.find_first_not_of("0123456789") == std::string::npos;
       if (!digits) throw std::invalid_argument("seed '" + f + "' is not an unsigned integer");
       errno = 0;
       const unsigned long long v = std::strtoull(f.c_str(), nullptr, 10);
       if (errno == ERANGE || v > static_cast<unsigned long long>(INT64_MAX)) {
         throw std::invalid_argument("seed " + f + " is out of range (63 bits)");
       }
       t.seed = v;
     },
     [](const TrialRecord& t) { return TrialValue(static_cast<long long>(t.seed)); }, true},
    {"outcome", "outcome",
     "The outcome's name (stable, slipped, dropped, missed, in_collision, invalid_contacts, "
     "simulation_failure, ...).",
     [](const TrialRecord& t) { return std::string(rwsim::trial::outcomeName(t.outcome)); },
     [](const std::string& f, TrialRecord& t) {
       const auto outcome = rwsim::trial::outcomeFromName(f);
       if (!outcome) throw std::invalid_argument("unknown outcome '" + f + "'");
       t.outcome = *outcome;
     },
     [](const TrialRecord& t) {
       return TrialValue(std::string(rwsim::trial::outcomeName(t.outcome)));
     }},
    {"robwork_code", "robwork_code", "RobWork's status code of the outcome.",
     [](const TrialRecord& t) { return std::to_string(rwsim::trial::robworkCode(t.outcome)); },
     [](const std::string& f, TrialRecord& t) {
       // Derived from the outcome: read only to check the file is consistent.
       const int expected = rwsim::trial::robworkCode(t.outcome);
       if (parseInt(f) != expected) {
         throw std::invalid_argument("RobWork code " + f + " does not match outcome '" +
                                     std::string(rwsim::trial::outcomeName(t.outcome)) +
                                     "' (expected " + std::to_string(expected) + ")");
       }
     },
     [](const TrialRecord& t) {
       return TrialValue(static_cast<long long>(rwsim::trial::robworkCode(t.outcome)));
     }},
    {"q_lift", "q_lift", "Paper eq. 5 (0 unless held).",
     [](const TrialRecord& t) { return formatDouble(t.qLift); },
     [](const std::string& f, TrialRecord& t) { t.qLift = parseDouble(f); },
     [](const TrialRecord& t) { return TrialValue(t.qLift); }},
    {"q_gws", "q_gws",
     "Paper eq. 6-7 on the measured contact forces (0 unless held; NaN when not computed).",
     [](const TrialRecord& t) { return formatQuality(t.qGws); },
     [](const std::string& f, TrialRecord& t) { t.qGws = parseQuality(f); },
     [](const TrialRecord& t) { return TrialValue(t.qGws); }},
    {"q_gws_unit", "q_gws_unit",
     "The grasp wrench space quality with unit normal forces (0 unless held; NaN when not "
     "computed).",
     [](const TrialRecord& t) { return formatQuality(t.qGwsUnit); },
     [](const std::string& f, TrialRecord& t) { t.qGwsUnit = parseQuality(f); },
     [](const TrialRecord& t) { return TrialValue(t.qGwsUnit); }},
    {"object", "object", "Id (1..18) of the object held or touched most; 0 when none was touched.",
     [](const TrialRecord& t) { return std::to_string(t.object); },
     [](const std::string& f, TrialRecord& t) {
       t.object = parseInt(f);
       if (t.object < 0 || t.object > database::kObjectCount) {
         throw std::invalid_argument("object " + f + " is not 0.." +
                                     std::to_string(database::kObjectCount));
       }
     },
     [](const TrialRecord& t) { return TrialValue(static_cast<long long>(t.object)); }},
    {"simulated_time", "simulated_time", "Simulated time, s.",
     [](const TrialRecord& t) { return formatDouble(t.simulatedTime); },
     [](const std::string& f, TrialRecord& t) { t.simulatedTime = parseDouble(f); },
     [](const TrialRecord& t) { return TrialValue(t.simulatedTime); }},
    {"closing_capped", "closing_capped",
     "True when the closing ran into the closing time limit with the fingers still moving (the "
     "grasp was judged as it stood).",
     [](const TrialRecord& t) { return std::string(t.closingCapped ? "1" : "0"); },
     [](const std::string& f, TrialRecord& t) {
       if (f != "0" && f != "1")
         throw std::invalid_argument("closing_capped '" + f + "' is not 0 or 1");
       t.closingCapped = f == "1";
     },
     [](const TrialRecord& t) { return TrialValue(t.closingCapped); }},
    {"detail", "detail", "Free text (failure details).",
     [](const TrialRecord& t) { return csvField(t.detail, true); },
     [](const std::string& f, TrialRecord& t) { t.detail = f; },
     [](const TrialRecord& t) { return TrialValue(t.detail); }},
}};

}  // namespace

std::span<const TrialColumn> trialColumns() { return kColumns; }

std::string trialColumnLine(bool repeated) {
  std::string line;
  for (const TrialColumn& c : kColumns) {
    if (c.repeatedOnly && !repeated) continue;
    if (!line.empty()) line += ',';
    line += c.name;
  }
  return line;
}

void recordResult(const rwsim::trial::GraspTrialResult& result, int objectId, TrialRecord& record) {
  record.outcome = result.outcome;
  record.qLift = result.qLift;
  record.qGws = result.qGws;
  record.qGwsUnit = result.qGwsUnit;
  record.object = objectId;
  record.simulatedTime = result.simulatedTime;
  record.closingCapped = result.closingCapped;
  record.detail = result.detail;
}

}  // namespace visgrab::results
