#pragma once

#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab render`: pictures of a scene, of a grasp's trial (three moments), of all grasps of a
/// scene (montage) and of a grasp over the left stereo image (overlay).
void addRenderCommands(CommandLine& cli);

}  // namespace visgrab::app
