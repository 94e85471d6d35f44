#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

/// What visgrab and visgrab-viewer share about their command lines (both parse with CLI11, by
/// the same rules: `--name value` = `--name=value`; an option given twice is a mistake unless
/// it is repeatable; `-h`/`--help` everywhere).
namespace visgrab::cli {

/// The help layout of every command: "usage:" in lower case, COMMAND for a subcommand, a wide
/// first column for the value types.
std::shared_ptr<CLI::Formatter> makeHelpFormatter();

/// CLI11's message for `e`, raised while parsing `cmd` (the command the parse reached),
/// in the words of the programs' other messages: "unknown
/// option --x", "--out DIR is required", "--db is given 2 times (once at most)", "--grasp:
/// expected ID|N after it", "--per-type needs an integer >= 1, got \"0\"".
std::string describeParseError(const CLI::ParseError& e, const CLI::App& cmd);

}  // namespace visgrab::cli
