#include "agreement_commands.hpp"
#include "baseline_commands.hpp"
#include "command_line.hpp"
#include "db_commands.hpp"
#include "import_commands.hpp"
#include "merge_commands.hpp"
#include "render_commands.hpp"
#include "run_commands.hpp"
#include "sim_commands.hpp"
#include "slurm_commands.hpp"
#include "wc_commands.hpp"

namespace visgrab::app {

std::unique_ptr<CommandLine> makeCommandLine() {
  auto cli = std::make_unique<CommandLine>();
  addWorkcellCommands(*cli);
  addSimulationCommands(*cli);
  addDatabaseCommands(*cli);
  addRunCommands(*cli);
  addMergeCommands(*cli);
  addSlurmCommands(*cli);
  addBaselineCommands(*cli);
  addRenderCommands(*cli);
  addAgreementCommands(*cli);
  addImportCommands(*cli);
  return cli;
}

}  // namespace visgrab::app
