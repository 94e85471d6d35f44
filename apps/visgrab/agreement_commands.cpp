#include "agreement_commands.hpp"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "visgrab/analysis/agreement.hpp"
#include "visgrab/analysis/label_agreement.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/importers/acronym.hpp"
#include "visgrab/results/results_file.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

// The scene of `run` made from `labels` (its database's <Source file>), else --scene, else the
// run's only scene.
std::string labelledScene(const Arguments& a, const analysis::AgreementRun& run,
                          const fs::path& labels) {
  if (const auto scene = a.option("scene")) return *scene;
  const fs::path& database = run.results.sources.database;
  std::error_code ec;
  if (!database.empty() && fs::exists(database, ec)) {
    const database::Database db = database::Database::openAny(database);
    for (const database::SceneEntry& s : db.list()) {
      if (s.source && s.source->file == labels.filename().string()) return s.id;
    }
  }
  if (run.results.scenes.size() == 1) return run.results.scenes.front().id;
  throw UsageError("no scene of " + run.dir.string() + "'s database was made from " +
                   labels.filename().string() + ", and the run has " +
                   std::to_string(run.results.scenes.size()) +
                   " scenes: name the labelled one with --scene");
}

// The run in `dir` as the agreement reads it; an unfinished run is refused without
// --allow-unfinished.
analysis::AgreementRun readRun(const Arguments& a, const std::string& dir) {
  std::vector<rw::common::Diagnostic> warnings;
  analysis::AgreementRun run = analysis::readAgreementRun(dir, &warnings);
  if (!a.flag("allow-unfinished")) results::requireFinished(run.results, dir, "--allow-unfinished");
  for (const auto& w : warnings) std::cerr << w.format() << "\n";
  return run;
}

int runLabelAgreement(const Arguments& a, const std::string& dir, const fs::path& labels) {
  const analysis::AgreementRun run = readRun(a, dir);
  const std::vector<int> values = importers::readAcronymLabels(labels);
  const analysis::LabelAgreement agreement = analysis::compareWithLabels(
      run, values, labels, labelledScene(a, run, labels), a.option("method").value_or(""));
  if (const std::string note = analysis::labelProtocolNote(agreement); !note.empty()) {
    std::cerr << note << "\n";
  }
  std::cout << analysis::labelAgreementSummary(agreement);
  if (const auto out = a.option("out")) {
    analysis::writeLabelAgreement(agreement, *out);
    std::cout << "written to " << *out
              << " (label-agreement.csv, label-confusion.csv, label-disagreements.csv)\n";
  }
  return 0;
}

int runAgreement(const Arguments& a) {
  const std::vector<std::string> dirs = a.positionals();
  if (const auto labels = a.option("labels")) {
    if (dirs.size() != 1) throw UsageError("with --labels, expected one result folder, RUN");
    return runLabelAgreement(a, dirs.front(), *labels);
  }
  if (a.option("scene")) throw UsageError("--scene needs --labels");
  if (a.option("method")) throw UsageError("--method needs --labels");
  if (dirs.size() != 2) throw UsageError("expected two result folders, RUN_A and RUN_B");
  std::vector<analysis::AgreementRun> runs;
  for (const std::string& dir : dirs) runs.push_back(readRun(a, dir));
  const analysis::Agreement agreement = analysis::compareRuns(runs[0], runs[1]);
  std::cout << analysis::agreementSummary(agreement);
  if (const auto out = a.option("out")) {
    analysis::writeAgreement(agreement, *out);
    std::cout << "written to " << *out
              << " (agreement.csv, confusion.csv, disagreements.csv, agreement.md)\n";
  }
  return 0;
}

}  // namespace

void addAgreementCommands(CommandLine& cli) {
  CLI::App& agreement = cli.addCommand(
      nullptr, "agreement",
      "How far two runs of the same grasps agree (e.g. on two physics engines): the outcome "
      "confusion matrix and, over the trials simulated in both, held vs not held agreement with "
      "Cohen's kappa, per condition and per object; trials decided before simulation counted "
      "apart; the disagreeing trials with their `visgrab render` commands "
      "(docs/validation.md). With --labels, one run against published labels.",
      guarded(runAgreement));
  agreement.add_option("RUN_A", "The first run's result folder (`visgrab run --out`)")
      ->required()
      ->type_name("");
  agreement
      .add_option("RUN_B",
                  "The second run's result folder, on the same database (not with --labels)")
      ->type_name("");
  agreement
      .add_option("--labels",
                  "Compare RUN_A with published labels instead: an ACRONYM .h5 (or GraspGen "
                  ".json) whose grasps RUN_A ran (`visgrab import acronym`); held (stable or "
                  "slipped) against grasps/qualities/flex/object_in_gripper, with Cohen's kappa")
      ->type_name("FILE");
  agreement
      .add_option("--scene",
                  "With --labels: the scene the labelled grasps ran in (default: the scene of "
                  "the run's database made from the labels' file)")
      ->type_name("ID");
  agreement
      .add_option("--method",
                  "With --labels: the method whose trials ran the labelled grasps (default: the "
                  "scene's only method)")
      ->type_name("NAME");
  agreement
      .add_option("--out",
                  "A folder to write agreement.csv, confusion.csv, disagreements.csv and "
                  "agreement.md into; with --labels label-agreement.csv, label-confusion.csv "
                  "and label-disagreements.csv")
      ->type_name("DIR");
  addFlag(agreement, "--allow-unfinished",
          "Compare a run that has not finished (its folder holds unfinished.txt) on the trials "
          "it has; without it such a folder is refused");
}

}  // namespace visgrab::app
