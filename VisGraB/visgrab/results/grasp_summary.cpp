#include "visgrab/results/grasp_summary.hpp"

#include <cmath>
#include <stdexcept>

#include "visgrab/database/atomic_file.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/results_file.hpp"

namespace visgrab::results {

double GraspSummary::probability() const {
  return repeats > 0 ? static_cast<double>(held) / repeats : std::nan("");
}

Interval GraspSummary::interval() const {
  return wilsonInterval(held, repeats, kGraspIntervalLevel);
}

std::vector<GraspSummary> summarizeGrasps(const std::vector<TrialRecord>& trials,
                                          const std::vector<RunScene>& scenes,
                                          const std::vector<std::string>& methods) {
  std::vector<TrialRecord> sorted = trials;
  sortTrials(sorted, scenes, methods);
  std::vector<GraspSummary> out;
  for (const TrialRecord& t : sorted) {
    const bool same = !out.empty() && out.back().sceneId == t.sceneId &&
                      out.back().method == t.method && out.back().graspId == t.graspId;
    if (!same) {
      if (t.repeat != 0) {
        throw std::invalid_argument("grasp (" + t.sceneId + ", " + t.method + ", " + t.graspId +
                                    ") has no unperturbed trial (repeat 0)");
      }
      GraspSummary& g = out.emplace_back();
      g.sceneId = t.sceneId;
      g.method = t.method;
      g.graspId = t.graspId;
      g.rank = t.rank;
      g.unperturbed = t.outcome;
    }
    GraspSummary& g = out.back();
    ++g.repeats;
    g.held += isSuccess(t.outcome) ? 1 : 0;
    ++g.counts[static_cast<std::size_t>(t.outcome)];
  }
  return out;
}

std::string formatGraspSummary(const std::vector<GraspSummary>& grasps) {
  std::vector<std::string> header = {"scene", "method", "grasp",    "rank",      "repeats",
                                     "held",  "p",      "p_ci_low", "p_ci_high", "unperturbed"};
  for (const auto& info : rwsim::trial::kOutcomeTable) {
    header.push_back("count_" + std::string(info.name));
  }
  std::string text = csvRecord(header);
  for (const GraspSummary& g : grasps) {
    const Interval ci = g.interval();
    std::vector<std::string> row = {g.sceneId,
                                    g.method,
                                    g.graspId,
                                    std::to_string(g.rank),
                                    std::to_string(g.repeats),
                                    std::to_string(g.held),
                                    formatDouble(g.probability()),
                                    formatDouble(ci.low),
                                    formatDouble(ci.high),
                                    std::string(rwsim::trial::outcomeName(g.unperturbed))};
    for (const int n : g.counts) row.push_back(std::to_string(n));
    text += csvRecord(row);
  }
  return text;
}

void writeGraspSummary(const std::filesystem::path& dir, const RunResults& run) {
  database::writeFileAtomically(dir / kGraspsFileName, formatGraspSummary(summarizeGrasps(
                                                           run.trials, run.scenes, run.methods)));
}

}  // namespace visgrab::results
