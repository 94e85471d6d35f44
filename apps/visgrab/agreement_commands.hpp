#pragma once

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab agreement`: how far two runs of the same grasps (e.g. on two engines) agree.
void addAgreementCommands(CommandLine& cli);

}  // namespace visgrab::app
