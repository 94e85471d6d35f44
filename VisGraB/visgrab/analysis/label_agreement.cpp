#include "visgrab/analysis/label_agreement.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "rw/common/xml_attributes.hpp"
#include "visgrab/analysis/detail/format.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/results/csv.hpp"

namespace visgrab::analysis {

namespace {

using rwsim::trial::GraspOutcome;

std::string percentOf(double fraction) {
  return std::isnan(fraction) ? std::string("–") : detail::fixed(100.0 * fraction, 1) + " %";
}

HeldAgreement tallied(const int cells[2][2], const char* key, const char* name) {
  // cells[run held][label held]
  HeldAgreement h = heldAgreement(cells[1][1], cells[1][0], cells[0][1], cells[0][0]);
  h.kind = "labels";
  h.key = key;
  h.name = name;
  return h;
}

// The method whose trials of `sceneId` are compared: `method` if the scene has trials of it,
// else (empty) the scene's only method.
std::string comparedMethod(const AgreementRun& run, const std::filesystem::path& labelsFile,
                           const std::string& sceneId, const std::string& method) {
  std::set<std::string> methods;
  for (const results::TrialRecord& t : run.results.trials) {
    if (t.sceneId == sceneId) methods.insert(t.method);
  }
  if (methods.empty()) {
    throw std::invalid_argument(run.dir.string() + " has no trial of scene " + sceneId +
                                " to compare with the labels of " + labelsFile.string());
  }
  std::string names;
  for (const std::string& m : methods) names += (names.empty() ? "" : ", ") + m;
  if (!method.empty()) {
    if (methods.count(method) == 0) {
      throw std::invalid_argument(run.dir.string() + " has no trial of method " + method +
                                  " in scene " + sceneId + " (its methods there: " + names + ")");
    }
    return method;
  }
  if (methods.size() > 1) {
    throw std::invalid_argument(run.dir.string() + " ran " + std::to_string(methods.size()) +
                                " methods in scene " + sceneId + " (" + names +
                                "): name the one whose grasps are those of " + labelsFile.string() +
                                " with --method");
  }
  return *methods.begin();
}

}  // namespace

LabelAgreement compareWithLabels(const AgreementRun& run, const std::vector<int>& labels,
                                 const std::filesystem::path& labelsFile,
                                 const std::string& sceneId, const std::string& method) {
  LabelAgreement out;
  out.dir = run.dir;
  out.labelsFile = labelsFile;
  out.sceneId = sceneId;
  out.protocol = run.results.sources.protocol;
  out.labels = static_cast<int>(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] != 0 && labels[i] != 1) {
      throw std::invalid_argument(labelsFile.string() + ": label " + std::to_string(i) + " is " +
                                  std::to_string(labels[i]) + ", expected 0 or 1");
    }
  }
  out.method = comparedMethod(run, labelsFile, sceneId, method);
  // The run's outcome per label index (repeat 0: the unperturbed trial).
  std::vector<const results::TrialRecord*> byIndex(labels.size(), nullptr);
  for (const results::TrialRecord& t : run.results.trials) {
    if (t.sceneId != sceneId || t.method != out.method || t.repeat != 0) continue;
    const auto index =
        rw::common::parseInteger(t.graspId, 0, static_cast<long long>(labels.size()) - 1);
    if (!index.error.empty() || byIndex[static_cast<std::size_t>(index.value)] != nullptr) {
      ++out.unmatchedTrials;
      continue;
    }
    byIndex[static_cast<std::size_t>(index.value)] = &t;
  }
  int all[2][2] = {{0, 0}, {0, 0}};
  int simulated[2][2] = {{0, 0}, {0, 0}};
  int sameSimulated = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const results::TrialRecord* t = byIndex[i];
    if (t == nullptr) {
      ++out.missingTrials;
      continue;
    }
    const bool held = rwsim::trial::isHeld(t->outcome);
    const bool label = labels[i] == 1;
    ++all[held ? 1 : 0][label ? 1 : 0];
    ++out.confusion[static_cast<std::size_t>(t->outcome)][label ? 1 : 0];
    if (rwsim::trial::isDecidedBeforeSimulation(t->outcome)) {
      ++out.decidedBeforeSimulation;
    } else {
      ++simulated[held ? 1 : 0][label ? 1 : 0];
      if (held == label) ++sameSimulated;
    }
    if (held != label) out.disagreements.push_back({t->graspId, t->outcome, label});
  }
  if (out.missingTrials == out.labels) {
    throw std::invalid_argument(
        run.dir.string() + " has no trial of scene " + sceneId + " and method " + out.method +
        " whose grasp id is the index of one of the " + std::to_string(out.labels) + " labels of " +
        labelsFile.string() + " (import the file with `visgrab import acronym` and run it)");
  }
  out.held = tallied(all, "all", "every compared grasp");
  out.held.decidedBeforeSimulation = out.decidedBeforeSimulation;
  // A label is only held or not held: the "same outcome" is the same verdict.
  out.held.sameOutcome = out.held.bothHeld + out.held.neitherHeld;
  out.simulated = tallied(simulated, "simulated", "grasps simulated (not decided before)");
  out.simulated.sameOutcome = sameSimulated;
  return out;
}

std::string labelAgreementSummary(const LabelAgreement& g) {
  std::ostringstream s;
  const HeldAgreement& h = g.held;
  s << "agreement of " << g.dir.string() << " (scene " << g.sceneId << ", method " << g.method
    << ") with the labels of " << g.labelsFile.string() << "\n";
  s << "  labels: " << g.labels << "; compared " << h.trials << " (" << g.missingTrials
    << " without a trial, " << g.unmatchedTrials << " trials without a label: ignored)\n";
  s << "  decided before simulation (in collision, invalid contacts): " << g.decidedBeforeSimulation
    << ", counted as not held\n";
  s << "  held vs not held: agreement " << percentOf(h.observedAgreement) << ", kappa "
    << kappaText(h) << "\n";
  s << "  held share: run " << percentOf(h.heldShareA) << ", labels " << percentOf(h.heldShareB)
    << " (chance agreement " << percentOf(h.expectedAgreement) << ")\n";
  s << "  held in both " << h.bothHeld << ", only the run " << h.onlyAHeld << ", only the labels "
    << h.onlyBHeld << ", neither " << h.neitherHeld << "\n";
  s << "  over the " << g.simulated.trials << " simulated grasps: agreement "
    << percentOf(g.simulated.observedAgreement) << ", kappa " << kappaText(g.simulated) << "\n";
  s << "  outcome by label (not held / held):";
  for (std::size_t i = 0; i < kAgreementOutcomeCount; ++i) {
    const auto& row = g.confusion[i];
    if (row[0] + row[1] == 0) continue;
    s << " " << rwsim::trial::kOutcomeTable[i].name << " " << row[0] << "/" << row[1] << ";";
  }
  s << "\n";
  return s.str();
}

std::string labelAgreementCsv(const LabelAgreement& g) {
  return results::csvRecord(heldAgreementCsvHeader()) +
         results::csvRecord(heldAgreementCsvFields(g.held)) +
         results::csvRecord(heldAgreementCsvFields(g.simulated));
}

std::string labelConfusionCsv(const LabelAgreement& g) {
  std::string text = results::csvRecord({"outcome", "not_held", "held"});
  for (std::size_t i = 0; i < kAgreementOutcomeCount; ++i) {
    text +=
        results::csvRecord({std::string(rwsim::trial::kOutcomeTable[i].name),
                            std::to_string(g.confusion[i][0]), std::to_string(g.confusion[i][1])});
  }
  return text;
}

std::string labelProtocolNote(const LabelAgreement& g) {
  if (!g.protocol.empty()) return {};
  return "note: " + g.dir.string() +
         " ran the lift protocol (gravity, one lift); ACRONYM's labels come from a shake "
         "without gravity: run the grasps with --protocol shake to compare like with like "
         "(docs/protocols.md)";
}

std::string labelDisagreementsCsv(const LabelAgreement& g) {
  std::string text =
      results::csvRecord({"scene", "method", "grasp_id", "outcome", "label", "render"});
  for (const LabelDisagreement& d : g.disagreements) {
    Disagreement trial;
    trial.sceneId = g.sceneId;
    trial.method = g.method;
    trial.graspId = d.graspId;
    text += results::csvRecord(
        {g.sceneId, g.method, d.graspId, std::string(rwsim::trial::outcomeName(d.outcome)),
         d.label ? "1" : "0", renderCommand(g.dir, trial, "label-" + d.graspId + ".png")});
  }
  return text;
}

void writeLabelAgreement(const LabelAgreement& g, const std::filesystem::path& outDir) {
  database::writeFileAtomically(outDir / "label-agreement.csv", labelAgreementCsv(g));
  database::writeFileAtomically(outDir / "label-confusion.csv", labelConfusionCsv(g));
  database::writeFileAtomically(outDir / "label-disagreements.csv", labelDisagreementsCsv(g));
}

}  // namespace visgrab::analysis
