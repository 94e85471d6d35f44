#pragma once

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab merge`: the result folders of a run's shards into the run's result folder.
void addMergeCommands(CommandLine& cli);

}  // namespace visgrab::app
