#pragma once

#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab run | analyze`: grasps through the simulator, results into the paper's analyses.
void addRunCommands(CommandLine& cli);

}  // namespace visgrab::app
