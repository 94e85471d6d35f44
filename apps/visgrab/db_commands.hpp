#pragma once

#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab db generate | list | show`: make and browse the scene database.
std::vector<Command> databaseCommands();

}  // namespace visgrab::app
