#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "command_line.hpp"

namespace visgrab::app {

/// `--protocol lift|shake|FILE` on `cmd` (run, benchmark, grasp, slurm, render): the trial
/// protocol (docs/protocols.md), with the help of the commands that run trials.
CLI::Option* addProtocolOption(CLI::App& command);

/// The protocol file --protocol names (a name in DATA/protocols or a path; cli::protocolPath),
/// nullopt without the option. The file is loaded once here, so that a bad one fails before
/// anything runs. @throws UsageError for an unknown name; rw::common::LoadError (file:line) for
/// a file that does not load; std::invalid_argument for values out of range.
std::optional<std::filesystem::path> protocolOption(const Arguments& a);

}  // namespace visgrab::app
