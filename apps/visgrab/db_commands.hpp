#pragma once

#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab db generate | list | show`: make and browse the scene database.
void addDatabaseCommands(CommandLine& cli);

}  // namespace visgrab::app
