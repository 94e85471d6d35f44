#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rwsim/trial/grasp_outcome.hpp"
#include "visgrab/results/trial_record.hpp"

/// How far two runs of the same grasps (typically on two physics engines) agree: the outcome
/// confusion matrix, held vs not held agreement with Cohen's kappa, per condition and per object,
/// and the trials they disagree on. Definitions and sources: docs/validation.md.
namespace visgrab::analysis {

/// Number of outcomes (rwsim::trial::kOutcomeTable order), the confusion matrix's size.
inline constexpr std::size_t kAgreementOutcomeCount = rwsim::trial::kOutcomeTable.size();

/// Held (stable or slipped) vs not held agreement of two runs over some trials simulated in
/// both, with the 2 x 2 table's cells and Cohen's (1960) kappa. Shares are fractions (0..1);
/// undefined values are NaN.
struct HeldAgreement {
  /// Kind of group: "overall", "condition", "object" (single-object scenes) or "pair"
  /// (double-object scenes).
  std::string kind;
  /// Key for files: "overall", a condition group's key ("textured-single-all"), an object's
  /// name or "pair-<letter>".
  std::string key;
  /// Heading: "overall", "textured, single, all", "cocacola", "pair e (cocacola, saltcylinder)".
  std::string name;
  /// Trials simulated in both runs (not decided before simulation in either): the n of the
  /// figures below.
  int trials = 0;
  /// Held in both runs.
  int bothHeld = 0;
  /// Held in run A only.
  int onlyAHeld = 0;
  /// Held in run B only.
  int onlyBHeld = 0;
  /// Held in neither run.
  int neitherHeld = 0;
  /// Of the simulated trials, those with the same outcome in both runs.
  int sameOutcome = 0;
  /// Shared trials decided before simulation (in collision, invalid contacts) in either run;
  /// not part of the figures.
  int decidedBeforeSimulation = 0;
  /// Of those, the ones with the same outcome in both runs.
  int decidedSame = 0;
  /// p_o = (bothHeld + neitherHeld) / trials.
  double observedAgreement = 0.0;
  /// p_e = p_A p_B + (1 - p_A)(1 - p_B): the agreement expected by chance from the held shares.
  double expectedAgreement = 0.0;
  /// kappa = (p_o - p_e) / (1 - p_e) (Cohen 1960); NaN without trials or when p_e = 1.
  double kappa = 0.0;
  /// Cohen's (1960) large-sample standard error sqrt(p_o (1 - p_o) / (n (1 - p_e)^2)).
  double kappaStandardError = 0.0;
  /// kappa - 1.96 SE, at least -1: the low end of the 95 % interval.
  double kappaLow = 0.0;
  /// kappa + 1.96 SE, at most 1: the high end of the 95 % interval.
  double kappaHigh = 0.0;
  /// p_A = (bothHeld + onlyAHeld) / trials: run A's held share.
  double heldShareA = 0.0;
  /// p_B = (bothHeld + onlyBHeld) / trials: run B's held share.
  double heldShareB = 0.0;
};

/// The figures of HeldAgreement (kind, key, name and the decided counts left empty) for the
/// 2 x 2 table with the given cells. @throws std::invalid_argument for a negative cell.
HeldAgreement heldAgreement(int bothHeld, int onlyAHeld, int onlyBHeld, int neitherHeld);

/// A shared trial on which the two runs disagree.
struct Disagreement {
  /// Scene id.
  std::string sceneId;
  /// Method.
  std::string method;
  /// Grasp id within scene and method.
  std::string graspId;
  /// Rank of the grasp (run A's).
  int rank = 0;
  /// Run A's outcome.
  rwsim::trial::GraspOutcome outcomeA = rwsim::trial::GraspOutcome::kSimulationFailure;
  /// Run B's outcome.
  rwsim::trial::GraspOutcome outcomeB = rwsim::trial::GraspOutcome::kSimulationFailure;
  /// True when held vs not held differs; false when only the outcome does (stable vs slipped,
  /// dropped vs missed, ...).
  bool heldDiffers = false;
  /// True when neither run decided the trial before simulation (it counts in HeldAgreement).
  bool simulatedInBoth = false;
};

/// A run as the comparison reads it: its folder and its results.
struct AgreementRun {
  /// The result folder (as given).
  std::filesystem::path dir;
  /// Its results (results::readResults).
  results::RunResults results;
};

/// Everything `visgrab agreement` reports about runs A and B.
struct Agreement {
  /// Run A's folder.
  std::filesystem::path dirA;
  /// Run B's folder.
  std::filesystem::path dirB;
  /// Run A's engine as recorded ("ode" when run.csv predates the record).
  std::string engineA;
  /// Run B's engine as recorded ("ode" when run.csv predates the record).
  std::string engineB;
  /// The database both ran on (run A's record; empty if unknown).
  std::filesystem::path database;
  /// Trials in run A.
  int trialsA = 0;
  /// Trials in run B.
  int trialsB = 0;
  /// Trials in both (same scene, method and grasp id): the ones compared.
  int shared = 0;
  /// Trials only in run A (ignored).
  int onlyInA = 0;
  /// Trials only in run B (ignored).
  int onlyInB = 0;
  /// confusion[a][b]: shared trials with outcome a in run A and b in run B (indices in
  /// rwsim::trial::kOutcomeTable order).
  std::array<std::array<int, kAgreementOutcomeCount>, kAgreementOutcomeCount> confusion{};
  /// Overall first, then the four condition groups with trials (textured/plain x single/double),
  /// then the objects of single-object scenes and the pairs of double-object scenes with trials
  /// (in id order). Trials of scenes with unknown conditions count in "overall" only.
  std::vector<HeldAgreement> groups;
  /// The shared trials whose outcomes differ, in run A's order.
  std::vector<Disagreement> disagreements;
};

/// Reads a result folder of `visgrab run` (results::readResults; its warnings into `warnings`
/// if given). @throws std::invalid_argument naming `dir` when it is not a run's folder (no
/// run.csv or no trials.csv); rw::common::LoadError (file:line) for corrupt files.
AgreementRun readAgreementRun(const std::filesystem::path& dir,
                              std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// Compares runs `a` and `b`, matching trials by (scene, method, grasp id).
/// @throws std::invalid_argument naming the folders when the runs share no trial, or when they
/// ran on different databases (see sameDatabase).
Agreement compareRuns(const AgreementRun& a, const AgreementRun& b);

/// Whether two recorded databases are the same: an empty record (unknown) matches anything;
/// otherwise the same path, or index files (a folder's index.xml, or the manifest) with the
/// same bytes. A record whose index cannot be read only matches the same path.
bool sameDatabase(const std::filesystem::path& a, const std::filesystem::path& b);

/// Whether two runs ran on the same database: when both recorded the database's index hash
/// (run.csv's database_hash), whether the hashes are equal, wherever the databases are now;
/// else sameDatabase of the recorded paths.
bool sameDatabase(const results::RunSources& a, const results::RunSources& b);

/// The `visgrab render` command line that draws trial `d` as run `dir` simulated it (its
/// recorded database, grasps, hand and engine), writing the picture `out`.
std::string renderCommand(const std::filesystem::path& dir, const Disagreement& d,
                          const std::string& out);

/// Kappa with its standard error and 95 % interval, e.g. "0.727 (SE 0.016, 95 % 0.697 to
/// 0.758)"; "–" when undefined.
std::string kappaText(const HeldAgreement& h);

/// The column names of one HeldAgreement in agreement.csv.
std::vector<std::string> heldAgreementCsvHeader();

/// One HeldAgreement as agreement.csv's fields (heldAgreementCsvHeader's order; undefined
/// figures empty).
std::vector<std::string> heldAgreementCsvFields(const HeldAgreement& h);

/// The readable summary `visgrab agreement` prints: counts, agreement, kappa, held shares, and
/// one line per condition group.
std::string agreementSummary(const Agreement& agreement);

/// agreement.csv: one row per group (Agreement::groups), one header row; shares as fractions,
/// undefined values empty.
std::string agreementCsv(const Agreement& agreement);

/// confusion.csv: the column outcome_a, then one column per outcome of run B; one row per
/// outcome of run A (kOutcomeTable order).
std::string confusionCsv(const Agreement& agreement);

/// disagreements.csv: one row per disagreement with both outcomes, its kind ("held" or
/// "outcome"), whether it was simulated in both, and the render commands for either run.
std::string disagreementsCsv(const Agreement& agreement);

/// agreement.md: the summary, the group table, the confusion matrix and the disagreements.
std::string agreementMarkdown(const Agreement& agreement);

/// Writes agreement.csv, confusion.csv, disagreements.csv and agreement.md into `outDir` (made
/// if missing), each atomically. @throws std::runtime_error if a file cannot be written.
void writeAgreement(const Agreement& agreement, const std::filesystem::path& outDir);

}  // namespace visgrab::analysis
