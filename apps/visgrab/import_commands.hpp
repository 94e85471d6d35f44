#pragma once

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab import FORMAT FILE`: grasps of today's methods' files as a grasp list of jaw grasps.
void addImportCommands(CommandLine& cli);

}  // namespace visgrab::app
