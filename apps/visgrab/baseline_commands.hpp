#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "command_line.hpp"

namespace visgrab::app {

/// `visgrab baseline`: the paper's baseline method (§4) from the stereo images to grasp files.
void addBaselineCommands(CommandLine& cli);

/// Runs the baseline with its default settings on the scenes of `db` that `filter` selects
/// (empty: all) and writes one grasp list (docs/grasp-format.md) atomically to `out`.
/// Prints progress to stderr unless `quiet`, and one line per scene that could not be
/// analysed. Returns the number of grasps written.
int writeBaselineGrasps(const std::filesystem::path& db, const std::string& filter,
                        const std::filesystem::path& out, int threads, bool quiet);

}  // namespace visgrab::app
