#pragma once

#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab sim FILE.dwc.xml --time T ...` (simulate a dynamic workcell and write body poses)
/// and `visgrab grasp FILE.dwc.xml --hand NAME --pose ... --qopen ... --qclose ...` (one grasp
/// trial).
void addSimulationCommands(CommandLine& cli);

}  // namespace visgrab::app
