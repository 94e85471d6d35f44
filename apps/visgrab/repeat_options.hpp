#pragma once

#include <string>
#include <vector>

#include "command_line.hpp"
#include "visgrab/runner/benchmark_runner.hpp"

namespace visgrab::app {

/// The robust-verdict options of `visgrab run` (and `visgrab slurm`, which passes them on):
/// --repeats N, --noise FILE, --seed S, --adaptive, --adaptive-alpha A, --adaptive-margin M.
void addRepeatOptions(CLI::App& command);

/// Reads the repeat options into `options` (runner::RunOptions::repeats and the rest).
/// @throws UsageError for a value out of range or an option that needs another (--noise, --seed
/// and --adaptive need --repeats N > 1; --adaptive-alpha and --adaptive-margin need --adaptive;
/// an adaptive rule that could stop no grasp within N repeats).
void readRepeatOptions(const Arguments& a, runner::RunOptions& options);

/// The repeat options given, as `visgrab run` arguments (the noise file absolute), for a job
/// script; empty without --repeats. @throws UsageError like readRepeatOptions,
/// rw::common::LoadError (file:line) for a noise file that does not load.
std::vector<std::string> repeatArguments(const Arguments& a);

}  // namespace visgrab::app
