#include "agreement_commands.hpp"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "visgrab/analysis/agreement.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

int runAgreement(const Arguments& a) {
  const std::vector<std::string> dirs = a.positionals();
  if (dirs.size() != 2) throw UsageError("expected two result folders, RUN_A and RUN_B");
  std::vector<analysis::AgreementRun> runs;
  for (const std::string& dir : dirs) {
    std::vector<rw::common::Diagnostic> warnings;
    runs.push_back(analysis::readAgreementRun(dir, &warnings));
    for (const auto& w : warnings) std::cerr << w.format() << "\n";
  }
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
      "(docs/validation.md).",
      guarded(runAgreement));
  agreement.add_option("RUN_A", "The first run's result folder (`visgrab run --out`)")
      ->required()
      ->type_name("");
  agreement.add_option("RUN_B", "The second run's result folder, on the same database")
      ->required()
      ->type_name("");
  agreement
      .add_option("--out",
                  "A folder to write agreement.csv, confusion.csv, disagreements.csv and "
                  "agreement.md into")
      ->type_name("DIR");
}

}  // namespace visgrab::app
