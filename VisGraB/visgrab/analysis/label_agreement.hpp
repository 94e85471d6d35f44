#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "visgrab/analysis/agreement.hpp"

/// How far a run's verdicts agree with published labels of the same grasps (ACRONYM's FleX
/// `grasps/qualities/flex/object_in_gripper`): held (stable or slipped) against the label's
/// "held", with Cohen's kappa; the outcome against the label; the grasps they disagree on.
/// docs/validation.md, "Agreement with ACRONYM's labels".
namespace visgrab::analysis {

/// A grasp on which the run and the labels disagree.
struct LabelDisagreement {
  /// Grasp id (the grasp's index in the labelled file).
  std::string graspId;
  /// The run's outcome.
  rwsim::trial::GraspOutcome outcome = rwsim::trial::GraspOutcome::kSimulationFailure;
  /// The label: true = held.
  bool label = false;
};

/// Everything `visgrab agreement RUN --labels FILE` reports.
struct LabelAgreement {
  /// The run's folder.
  std::filesystem::path dir;
  /// The labels' file (as given).
  std::filesystem::path labelsFile;
  /// The scene whose trials were compared.
  std::string sceneId;
  /// The method whose trials were compared.
  std::string method;
  /// The run's protocol as recorded (results::RunSources::protocol; empty: the lift).
  std::string protocol;
  /// Labels in the file.
  int labels = 0;
  /// Labels without a trial in the run (grasp ids "0".."labels-1" not run).
  int missingTrials = 0;
  /// Trials of the scene and method whose grasp id is not a label's index (ignored).
  int unmatchedTrials = 0;
  /// Compared grasps decided before simulation (in collision, invalid contacts): counted as
  /// not held, since the grasp failed.
  int decidedBeforeSimulation = 0;
  /// confusion[outcome][label]: compared grasps by the run's outcome (rwsim::trial::kOutcomeTable
  /// order) and the label (0 not held, 1 held).
  std::array<std::array<int, 2>, kAgreementOutcomeCount> confusion{};
  /// Held agreement over every compared grasp: run A is the run, run B the labels.
  HeldAgreement held;
  /// The same over the grasps the run simulated (not decided before simulation).
  HeldAgreement simulated;
  /// The compared grasps on which held and the label differ, in grasp id order.
  std::vector<LabelDisagreement> disagreements;
};

/// Compares the trials of scene `sceneId` and method `method` in `run` (repeat 0 only) with
/// `labels` (index i is grasp id "i"; 0 = not held, 1 = held). An empty `method` is the
/// scene's only method. @throws std::invalid_argument naming the folder and the labels' file
/// when a label is not 0 or 1, when the scene has no trial of `method`, when `method` is empty
/// and the scene's trials are of several methods (naming them), or when no compared trial has a
/// label's id.
LabelAgreement compareWithLabels(const AgreementRun& run, const std::vector<int>& labels,
                                 const std::filesystem::path& labelsFile,
                                 const std::string& sceneId, const std::string& method = {});

/// A note for the summary when the run's protocol is the lift (gravity, no shake): ACRONYM's
/// labels come from a shake without gravity, so the comparison measures another protocol.
/// Empty for any other protocol.
std::string labelProtocolNote(const LabelAgreement& agreement);

/// The readable summary: counts, agreement, kappa, held shares, the outcome-by-label table.
std::string labelAgreementSummary(const LabelAgreement& agreement);

/// label-agreement.csv: one row each for "all" and "simulated" (HeldAgreement's figures).
std::string labelAgreementCsv(const LabelAgreement& agreement);

/// label-confusion.csv: outcome, not_held, held; one row per outcome.
std::string labelConfusionCsv(const LabelAgreement& agreement);

/// label-disagreements.csv: scene, method, grasp_id, outcome, label, render (the `visgrab
/// render` command that draws the trial).
std::string labelDisagreementsCsv(const LabelAgreement& agreement);

/// Writes the three CSV files into `outDir` (made if missing), each atomically.
/// @throws std::runtime_error if a file cannot be written.
void writeLabelAgreement(const LabelAgreement& agreement, const std::filesystem::path& outDir);

}  // namespace visgrab::analysis
