#pragma once

#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab wc info FILE` and `visgrab wc check FILE`.
void addWorkcellCommands(CommandLine& cli);

}  // namespace visgrab::app
