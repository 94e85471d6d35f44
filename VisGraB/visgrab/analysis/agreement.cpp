#include "visgrab/analysis/agreement.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "visgrab/analysis/analysis.hpp"
#include "visgrab/analysis/detail/format.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/results_file.hpp"

namespace visgrab::analysis {

namespace {

namespace fs = std::filesystem;
using rwsim::trial::GraspOutcome;
using rwsim::trial::isDecidedBeforeSimulation;
using rwsim::trial::isHeld;

constexpr double kUndefinedFigure = std::numeric_limits<double>::quiet_NaN();
// The normal quantile of the two-sided 95 % interval.
constexpr double kZ95 = 1.959963984540054;

std::size_t outcomeIndex(GraspOutcome outcome) { return static_cast<std::size_t>(outcome); }

std::string engineOf(const results::RunResults& run) {
  return run.sources.engine.empty() ? std::string("ode") : run.sources.engine;
}

/// The bytes of a database's index (a folder's index.xml or the manifest file); nullopt when it
/// cannot be read.
std::optional<std::string> indexBytes(const fs::path& database) {
  std::error_code ec;
  const fs::path index = fs::is_directory(database, ec) ? database / "index.xml" : database;
  std::ifstream in(index, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A name for an object id (its benchmark name, else "object N").
std::string objectLabel(int id) {
  if (id >= 1 && id <= database::kObjectCount) return std::string(database::objectName(id));
  return "object " + std::to_string(id);
}

/// The tallies of one group while trials are counted.
struct GroupTally {
  std::string kind, key, name;
  int cells[2][2] = {{0, 0}, {0, 0}};  // [A held][B held]
  int sameOutcome = 0;
  int decided = 0;
  int decidedSame = 0;

  int total() const { return cells[0][0] + cells[0][1] + cells[1][0] + cells[1][1] + decided; }

  void add(GraspOutcome a, GraspOutcome b) {
    if (isDecidedBeforeSimulation(a) || isDecidedBeforeSimulation(b)) {
      ++decided;
      if (a == b) ++decidedSame;
      return;
    }
    ++cells[isHeld(a) ? 1 : 0][isHeld(b) ? 1 : 0];
    if (a == b) ++sameOutcome;
  }

  HeldAgreement finish() const {
    HeldAgreement h = heldAgreement(cells[1][1], cells[1][0], cells[0][1], cells[0][0]);
    h.kind = kind;
    h.key = key;
    h.name = name;
    h.sameOutcome = sameOutcome;
    h.decidedBeforeSimulation = decided;
    h.decidedSame = decidedSame;
    return h;
  }
};

/// The object or pair group a scene's trials count in, if its conditions are known.
std::optional<std::tuple<int, std::string, std::string, std::string>> subjectGroup(
    const std::optional<database::SceneConditions>& c) {
  if (!c || c->objects.empty()) return std::nullopt;
  if (c->kind == database::SceneKind::kSingle) {
    const std::string name = objectLabel(c->objects.front());
    return std::make_tuple(c->objects.front(), std::string("object"), name, name);
  }
  const auto pair = c->pair();
  if (!pair) return std::nullopt;
  const std::string letter(1, pair->letter);
  // Pairs after the single objects, in letter order.
  return std::make_tuple(
      1000 + pair->letter, std::string("pair"), "pair-" + letter,
      "pair " + letter + " (" + objectLabel(pair->first) + ", " + objectLabel(pair->second) + ")");
}

/// The tallies of every group: overall, the four conditions, the objects and the pairs.
class GroupTallies {
 public:
  GroupTallies() : overall_{"overall", "overall", "overall"} {
    for (const ConditionGroup& g : conditionGroups()) {
      if (g.texture && g.kind && !g.arrangement) {
        conditions_.emplace_back(g, GroupTally{"condition", g.key, g.name});
      }
    }
  }

  /// Counts the shared trial `a` (run A's record) whose outcome in run B is `b`.
  void add(const results::TrialRecord& a, GraspOutcome b) {
    overall_.add(a.outcome, b);
    for (auto& [group, tally] : conditions_) {
      if (a.conditions && group.contains(a.conditions)) tally.add(a.outcome, b);
    }
    if (const auto subject = subjectGroup(a.conditions)) {
      const auto& [order, kind, key, name] = *subject;
      subjects_.try_emplace(order, GroupTally{kind, key, name}).first->second.add(a.outcome, b);
    }
  }

  /// Overall, the conditions with trials, the objects and pairs (Agreement::groups).
  std::vector<HeldAgreement> finish() const {
    std::vector<HeldAgreement> groups{overall_.finish()};
    for (const auto& [group, tally] : conditions_) {
      if (tally.total() > 0) groups.push_back(tally.finish());
    }
    for (const auto& [order, tally] : subjects_) groups.push_back(tally.finish());
    return groups;
  }

 private:
  GroupTally overall_;
  std::vector<std::pair<ConditionGroup, GroupTally>> conditions_;
  // By object id, pairs after the objects (subjectGroup).
  std::map<int, GroupTally> subjects_;
};

/// The disagreement of a shared trial (run A's record `a`, run B's `b`), if the outcomes differ.
std::optional<Disagreement> disagreementOf(const results::TrialRecord& a,
                                           const results::TrialRecord& b) {
  if (a.outcome == b.outcome) return std::nullopt;
  Disagreement d;
  d.sceneId = a.sceneId;
  d.method = a.method;
  d.graspId = a.graspId;
  d.rank = a.rank;
  d.outcomeA = a.outcome;
  d.outcomeB = b.outcome;
  d.heldDiffers = isHeld(a.outcome) != isHeld(b.outcome);
  d.simulatedInBoth =
      !isDecidedBeforeSimulation(a.outcome) && !isDecidedBeforeSimulation(b.outcome);
  return d;
}

/// Shell word: as it is when it holds only safe characters, else in single quotes.
std::string shellWord(const std::string& text) {
  const bool safe = !text.empty() && text.find_first_not_of(
                                         "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                         "0123456789_-./=:,+@%") == std::string::npos;
  if (safe) return text;
  std::string out = "'";
  for (const char ch : text) {
    if (ch == '\'') {
      out += "'\\''";
    } else {
      out += ch;
    }
  }
  return out + "'";
}

/// `text` with every character but letters, digits, '.', '_' and '-' replaced by '_'.
std::string fileWord(const std::string& text) {
  std::string out = text;
  for (char& ch : out) {
    const bool keep = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                      (ch >= '0' && ch <= '9') || ch == '.' || ch == '_' || ch == '-';
    if (!keep) ch = '_';
  }
  return out;
}

/// The picture name of a disagreement drawn on run `which` ("a" or "b").
std::string pictureName(const Disagreement& d, const std::string& which) {
  return fileWord(d.sceneId) + "-" + fileWord(d.method) + "-" + fileWord(d.graspId) + "-" + which +
         ".png";
}

/// A fraction for CSV: shortest exact text, empty when undefined.
std::string fractionField(double value) {
  return std::isnan(value) ? std::string() : results::formatDouble(value);
}

std::string percentText(double fraction) {
  return std::isnan(fraction) ? std::string("–") : detail::fixed(100.0 * fraction, 1) + " %";
}

std::string kindName(const Disagreement& d) { return d.heldDiffers ? "held" : "outcome"; }

/// The Markdown cell of `text` (pipes escaped).
std::string mdCell(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    if (ch == '|') out += '\\';
    out += ch;
  }
  return out;
}

/// agreement.md's table of the groups.
void markdownGroups(std::ostream& s, const Agreement& g) {
  s << "## Held vs not held, per group\n\n";
  s << "| group | n | both held | only A | only B | neither | agreement | chance | kappa | "
       "95 % interval | held A | held B | same outcome | decided before simulation |\n";
  s << "|---|--:|--:|--:|--:|--:|--:|--:|--:|---|--:|--:|--:|--:|\n";
  for (const HeldAgreement& h : g.groups) {
    const std::string interval = std::isnan(h.kappaLow) ? std::string("–")
                                                        : detail::fixed(h.kappaLow, 3) + " to " +
                                                              detail::fixed(h.kappaHigh, 3);
    s << "| " << mdCell(h.name) << " | " << h.trials << " | " << h.bothHeld << " | " << h.onlyAHeld
      << " | " << h.onlyBHeld << " | " << h.neitherHeld << " | " << percentText(h.observedAgreement)
      << " | " << percentText(h.expectedAgreement) << " | "
      << (std::isnan(h.kappa) ? std::string("–") : detail::fixed(h.kappa, 3)) << " | " << interval
      << " | " << percentText(h.heldShareA) << " | " << percentText(h.heldShareB) << " | "
      << h.sameOutcome << " | " << h.decidedBeforeSimulation << " |\n";
  }
}

/// agreement.md's confusion matrix.
void markdownConfusion(std::ostream& s, const Agreement& g) {
  s << "\n## Outcomes (rows: A, columns: B)\n\n| A \\ B |";
  for (const auto& info : rwsim::trial::kOutcomeTable) s << " " << info.name << " |";
  s << "\n|---|";
  for (std::size_t j = 0; j < kAgreementOutcomeCount; ++j) s << "--:|";
  s << "\n";
  for (std::size_t i = 0; i < kAgreementOutcomeCount; ++i) {
    s << "| " << rwsim::trial::kOutcomeTable[i].name << " |";
    for (std::size_t j = 0; j < kAgreementOutcomeCount; ++j) s << " " << g.confusion[i][j] << " |";
    s << "\n";
  }
}

/// agreement.md's list of disagreements.
void markdownDisagreements(std::ostream& s, const Agreement& g) {
  s << "\n## Disagreements (" << g.disagreements.size() << ")\n\n";
  if (g.disagreements.empty()) {
    s << "None: every shared trial has the same outcome in both runs.\n";
    return;
  }
  s << "| scene | method | grasp | A | B | differs in | render A | render B |\n";
  s << "|---|---|---|---|---|---|---|---|\n";
  for (const Disagreement& d : g.disagreements) {
    s << "| " << mdCell(d.sceneId) << " | " << mdCell(d.method) << " | " << mdCell(d.graspId)
      << " | " << rwsim::trial::outcomeName(d.outcomeA) << " | "
      << rwsim::trial::outcomeName(d.outcomeB) << " | "
      << (d.heldDiffers ? "held vs not held" : "outcome")
      << (d.simulatedInBoth ? "" : " (decided before simulation)") << " | `"
      << mdCell(renderCommand(g.dirA, d, pictureName(d, "a"))) << "` | `"
      << mdCell(renderCommand(g.dirB, d, pictureName(d, "b"))) << "` |\n";
  }
}

}  // namespace

HeldAgreement heldAgreement(int bothHeld, int onlyAHeld, int onlyBHeld, int neitherHeld) {
  if (bothHeld < 0 || onlyAHeld < 0 || onlyBHeld < 0 || neitherHeld < 0) {
    throw std::invalid_argument("heldAgreement: negative count in the 2 x 2 table");
  }
  HeldAgreement h;
  h.bothHeld = bothHeld;
  h.onlyAHeld = onlyAHeld;
  h.onlyBHeld = onlyBHeld;
  h.neitherHeld = neitherHeld;
  h.trials = bothHeld + onlyAHeld + onlyBHeld + neitherHeld;
  if (h.trials == 0) {
    h.observedAgreement = h.expectedAgreement = h.kappa = kUndefinedFigure;
    h.kappaStandardError = h.kappaLow = h.kappaHigh = kUndefinedFigure;
    h.heldShareA = h.heldShareB = kUndefinedFigure;
    return h;
  }
  const double n = h.trials;
  h.observedAgreement = (bothHeld + neitherHeld) / n;
  h.heldShareA = (bothHeld + onlyAHeld) / n;
  h.heldShareB = (bothHeld + onlyBHeld) / n;
  h.expectedAgreement = h.heldShareA * h.heldShareB + (1.0 - h.heldShareA) * (1.0 - h.heldShareB);
  const double chance = 1.0 - h.expectedAgreement;
  // p_e = 1: both runs gave every trial the same verdict, kappa is 0/0.
  if (chance <= 1e-12) {
    h.kappa = h.kappaStandardError = h.kappaLow = h.kappaHigh = kUndefinedFigure;
    return h;
  }
  h.kappa = (h.observedAgreement - h.expectedAgreement) / chance;
  h.kappaStandardError =
      std::sqrt(h.observedAgreement * (1.0 - h.observedAgreement) / (n * chance * chance));
  // Kappa lies in [-1, 1]; the normal approximation's interval is clipped to it.
  h.kappaLow = std::max(-1.0, h.kappa - kZ95 * h.kappaStandardError);
  h.kappaHigh = std::min(1.0, h.kappa + kZ95 * h.kappaStandardError);
  return h;
}

AgreementRun readAgreementRun(const fs::path& dir, std::vector<rw::common::Diagnostic>* warnings) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw std::invalid_argument(dir.string() + ": not a folder (expected a run's result folder)");
  }
  std::string missing;
  for (const std::string_view name : {results::kRunFileName, results::kTrialsFileName}) {
    if (!fs::is_regular_file(dir / name, ec)) {
      missing += (missing.empty() ? "" : " and ") + std::string(name);
    }
  }
  if (!missing.empty()) {
    throw std::invalid_argument(dir.string() + ": not a result folder of `visgrab run` (no " +
                                missing + ")");
  }
  AgreementRun run;
  run.dir = dir;
  run.results = results::readResults(dir, warnings);
  return run;
}

bool sameDatabase(const results::RunSources& a, const results::RunSources& b) {
  // Both runs recorded their database's index hash: it decides, wherever the databases are.
  if (!a.databaseHash.empty() && !b.databaseHash.empty()) {
    return a.databaseHash == b.databaseHash;
  }
  return sameDatabase(a.database, b.database);
}

bool sameDatabase(const fs::path& a, const fs::path& b) {
  if (a.empty() || b.empty()) return true;
  if (a.lexically_normal() == b.lexically_normal()) return true;
  std::error_code ec;
  if (fs::equivalent(a, b, ec)) return true;
  const auto bytesA = indexBytes(a);
  const auto bytesB = indexBytes(b);
  return bytesA && bytesB && *bytesA == *bytesB;
}

Agreement compareRuns(const AgreementRun& a, const AgreementRun& b) {
  const auto& ra = a.results;
  const auto& rb = b.results;
  if (!sameDatabase(ra.sources, rb.sources)) {
    const bool hashed = !ra.sources.databaseHash.empty() && !rb.sources.databaseHash.empty();
    throw std::invalid_argument(
        a.dir.string() + " and " + b.dir.string() + " ran on different databases (" +
        ra.sources.database.string() + " and " + rb.sources.database.string() +
        (hashed ? ": their recorded index hashes differ, " + ra.sources.databaseHash + " and " +
                      rb.sources.databaseHash + ")"
                : ": neither the same path nor index files with the same content)"));
  }
  Agreement out;
  out.dirA = a.dir;
  out.dirB = b.dir;
  out.engineA = engineOf(ra);
  out.engineB = engineOf(rb);
  out.database = ra.sources.database.empty() ? rb.sources.database : ra.sources.database;
  out.trialsA = static_cast<int>(ra.trials.size());
  out.trialsB = static_cast<int>(rb.trials.size());

  // A trial is its grasp and repeat (runs with --repeats: each repeat pairs with the same repeat).
  using Key = std::tuple<std::string, std::string, std::string, int>;
  std::map<Key, const results::TrialRecord*> inB;
  for (const auto& t : rb.trials) inB.emplace(Key{t.sceneId, t.method, t.graspId, t.repeat}, &t);

  GroupTallies tallies;
  for (const auto& ta : ra.trials) {
    const auto it = inB.find(Key{ta.sceneId, ta.method, ta.graspId, ta.repeat});
    if (it == inB.end()) continue;
    const results::TrialRecord& tb = *it->second;
    ++out.shared;
    ++out.confusion[outcomeIndex(ta.outcome)][outcomeIndex(tb.outcome)];
    tallies.add(ta, tb.outcome);
    if (auto d = disagreementOf(ta, tb)) out.disagreements.push_back(std::move(*d));
  }
  if (out.shared == 0) {
    throw std::invalid_argument(a.dir.string() + " and " + b.dir.string() +
                                " share no trial (no scene, method and grasp id in both; " +
                                std::to_string(out.trialsA) + " and " +
                                std::to_string(out.trialsB) + " trials)");
  }
  out.onlyInA = out.trialsA - out.shared;
  out.onlyInB = out.trialsB - out.shared;
  out.groups = tallies.finish();
  return out;
}

std::string renderCommand(const fs::path& dir, const Disagreement& d, const std::string& out) {
  // --results gives render the run's database, grasps, hand and engine; --method and the grasp
  // id pick the trial's grasp.
  return "visgrab render --results " + shellWord(dir.string()) + " --scene " +
         shellWord(d.sceneId) + " --method " + shellWord(d.method) + " --grasp " +
         shellWord(d.graspId) + " --out " + shellWord(out);
}

std::string kappaText(const HeldAgreement& h) {
  if (std::isnan(h.kappa)) return "–";
  std::string text = detail::fixed(h.kappa, 3);
  if (!std::isnan(h.kappaStandardError)) {
    text += " (SE " + detail::fixed(h.kappaStandardError, 3) + ", 95 % " +
            detail::fixed(h.kappaLow, 3) + " to " + detail::fixed(h.kappaHigh, 3) + ")";
  }
  return text;
}

std::vector<std::string> heldAgreementCsvHeader() {
  return {"kind",
          "key",
          "name",
          "trials",
          "both_held",
          "only_a_held",
          "only_b_held",
          "neither_held",
          "observed_agreement",
          "expected_agreement",
          "kappa",
          "kappa_se",
          "kappa_low",
          "kappa_high",
          "held_share_a",
          "held_share_b",
          "same_outcome",
          "decided_before_simulation",
          "decided_same"};
}

std::vector<std::string> heldAgreementCsvFields(const HeldAgreement& h) {
  return {h.kind,
          h.key,
          h.name,
          std::to_string(h.trials),
          std::to_string(h.bothHeld),
          std::to_string(h.onlyAHeld),
          std::to_string(h.onlyBHeld),
          std::to_string(h.neitherHeld),
          fractionField(h.observedAgreement),
          fractionField(h.expectedAgreement),
          fractionField(h.kappa),
          fractionField(h.kappaStandardError),
          fractionField(h.kappaLow),
          fractionField(h.kappaHigh),
          fractionField(h.heldShareA),
          fractionField(h.heldShareB),
          std::to_string(h.sameOutcome),
          std::to_string(h.decidedBeforeSimulation),
          std::to_string(h.decidedSame)};
}

std::string agreementSummary(const Agreement& g) {
  std::ostringstream s;
  const HeldAgreement& all = g.groups.front();
  s << "agreement of " << g.dirA.string() << " (A, " << g.engineA << ") and " << g.dirB.string()
    << " (B, " << g.engineB << ")\n";
  s << "  trials: " << g.trialsA << " in A, " << g.trialsB << " in B, " << g.shared << " shared ("
    << g.onlyInA << " only in A, " << g.onlyInB << " only in B: ignored)\n";
  s << "  decided before simulation (in collision, invalid contacts) in either run: "
    << all.decidedBeforeSimulation << " (" << all.decidedSame
    << " with the same outcome in both; counted apart)\n";
  s << "  simulated in both: " << all.trials << "\n";
  s << "  held vs not held: agreement " << percentText(all.observedAgreement) << ", kappa "
    << kappaText(all) << "\n";
  s << "  held share: A " << percentText(all.heldShareA) << ", B " << percentText(all.heldShareB)
    << " (chance agreement " << percentText(all.expectedAgreement) << ")\n";
  s << "  held in both " << all.bothHeld << ", only A " << all.onlyAHeld << ", only B "
    << all.onlyBHeld << ", neither " << all.neitherHeld << "; same outcome " << all.sameOutcome
    << " of " << all.trials << "\n";
  int held = 0;
  for (const Disagreement& d : g.disagreements) held += d.heldDiffers ? 1 : 0;
  s << "  disagreements: " << g.disagreements.size() << " (" << held << " held vs not held, "
    << g.disagreements.size() - static_cast<std::size_t>(held) << " outcome only)\n";
  for (const HeldAgreement& h : g.groups) {
    if (h.kind != "condition") continue;
    s << "  " << h.name << ": n " << h.trials << ", agreement " << percentText(h.observedAgreement)
      << ", kappa " << (std::isnan(h.kappa) ? std::string("–") : detail::fixed(h.kappa, 3))
      << ", held A " << percentText(h.heldShareA) << ", B " << percentText(h.heldShareB) << "\n";
  }
  return s.str();
}

std::string agreementCsv(const Agreement& g) {
  std::string text = results::csvRecord(heldAgreementCsvHeader());
  for (const HeldAgreement& h : g.groups) text += results::csvRecord(heldAgreementCsvFields(h));
  return text;
}

std::string confusionCsv(const Agreement& g) {
  std::vector<std::string> header{"outcome_a"};
  for (const auto& info : rwsim::trial::kOutcomeTable) header.emplace_back(info.name);
  std::string text = results::csvRecord(header);
  for (std::size_t i = 0; i < kAgreementOutcomeCount; ++i) {
    std::vector<std::string> row{std::string(rwsim::trial::kOutcomeTable[i].name)};
    for (std::size_t j = 0; j < kAgreementOutcomeCount; ++j) {
      row.push_back(std::to_string(g.confusion[i][j]));
    }
    text += results::csvRecord(row);
  }
  return text;
}

std::string disagreementsCsv(const Agreement& g) {
  std::string text =
      results::csvRecord({"scene", "method", "grasp", "rank", "outcome_a", "outcome_b",
                          "disagreement", "simulated_in_both", "render_a", "render_b"});
  for (const Disagreement& d : g.disagreements) {
    text += results::csvRecord({d.sceneId, d.method, d.graspId, std::to_string(d.rank),
                                std::string(rwsim::trial::outcomeName(d.outcomeA)),
                                std::string(rwsim::trial::outcomeName(d.outcomeB)), kindName(d),
                                d.simulatedInBoth ? "true" : "false",
                                renderCommand(g.dirA, d, pictureName(d, "a")),
                                renderCommand(g.dirB, d, pictureName(d, "b"))});
  }
  return text;
}

std::string agreementMarkdown(const Agreement& g) {
  std::ostringstream s;
  const HeldAgreement& all = g.groups.front();
  s << "# Agreement between two runs\n\n";
  s << "- A: `" << g.dirA.string() << "` (engine " << g.engineA << ")\n";
  s << "- B: `" << g.dirB.string() << "` (engine " << g.engineB << ")\n";
  s << "- database: `" << (g.database.empty() ? "unknown" : g.database.string()) << "`\n";
  s << "- trials: " << g.trialsA << " in A, " << g.trialsB << " in B, " << g.shared << " shared; "
    << g.onlyInA << " only in A and " << g.onlyInB << " only in B are ignored\n";
  s << "- decided before simulation (in collision, invalid contacts) in either run: "
    << all.decidedBeforeSimulation << ", " << all.decidedSame
    << " of them with the same outcome in both (the same placement decides them alike); not in "
       "the figures below\n";
  s << "- simulated in both: " << all.trials << "; held vs not held agreement "
    << percentText(all.observedAgreement) << ", Cohen's kappa " << kappaText(all)
    << "; held share A " << percentText(all.heldShareA) << ", B " << percentText(all.heldShareB)
    << "\n\n";
  s << "Kappa discounts the agreement two runs would reach by chance with their held shares "
       "(docs/validation.md).\n\n";

  markdownGroups(s, g);
  markdownConfusion(s, g);
  markdownDisagreements(s, g);
  return s.str();
}

void writeAgreement(const Agreement& g, const fs::path& outDir) {
  database::writeFileAtomically(outDir / "agreement.csv", agreementCsv(g));
  database::writeFileAtomically(outDir / "confusion.csv", confusionCsv(g));
  database::writeFileAtomically(outDir / "disagreements.csv", disagreementsCsv(g));
  database::writeFileAtomically(outDir / "agreement.md", agreementMarkdown(g));
}

}  // namespace visgrab::analysis
