#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace visgrab::app {

/// A command-line mistake found after parsing; it is printed with the command's usage line and
/// the process exits with code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What the command line gave one command, read by option name ("db" for `--db`) from the
/// CLI11 app that parsed it (where each option is defined once, with its type and check).
class Arguments {
 public:
  /// The values `cmd` parsed; `cmd` must outlive this.
  explicit Arguments(const CLI::App& cmd) : cmd_(&cmd) {}

  /// The positional arguments in order.
  std::vector<std::string> positionals() const;
  /// True if the flag was given.
  bool flag(const std::string& name) const;
  /// The value of an option, if given (from the command line or its environment variable).
  std::optional<std::string> option(const std::string& name) const;
  /// Every value of a repeatable option, in order (empty if not given).
  std::vector<std::string> values(const std::string& name) const;
  /// Every value of an option that takes several (split at commas too), one list per time it
  /// was given.
  std::vector<std::vector<std::string>> occurrences(const std::string& name) const;
  /// @throws UsageError unless exactly `n` positionals were given (`what` names them).
  void requirePositionals(std::size_t n, const std::string& what) const;

 private:
  const CLI::Option& get(const std::string& name) const;
  const CLI::App* cmd_;
};

/// One command's run function: the exit code for the parsed arguments.
using RunFunction = std::function<int(const Arguments&)>;

/// The visgrab command line: one CLI11 app holding every command, each with its options and the
/// function that runs it. The rules are the same for every command (and for visgrab-viewer):
/// `--name value` and `--name=value` are the same; an option or flag given twice is a usage
/// error, except the options whose help says "repeatable" (they collect every value in order);
/// `-h`/`--help` on any command prints its options with types, defaults and units.
class CommandLine {
 public:
  /// The top-level app `visgrab` with `--help` and `--version`.
  CommandLine();

  /// The top-level app (its subcommands are the commands and groups), for tests.
  const CLI::App& root() const { return *root_; }

  /// Adds a group of commands (`wc`, `db`) under the top level; one of its commands must follow.
  CLI::App& addGroup(const std::string& name, const std::string& summary);

  /// Adds the command `name` under `parent` (nullptr: the top level; else a group) that calls
  /// `run` when the command line chooses it. Its options are added to the returned app.
  CLI::App& addCommand(CLI::App* parent, const std::string& name, const std::string& summary,
                       RunFunction run);

  /// Parses `argv` (without the program name) and runs the chosen command. Exit codes: the
  /// command's own (0 ok, 1 bad input), 2 for a command-line mistake (printed to stderr with
  /// the command's usage line).
  int run(const std::vector<std::string>& argv);

 private:
  std::unique_ptr<CLI::App> root_;
  std::shared_ptr<CLI::Formatter> formatter_;
  // The command the last parse chose, and its run function.
  const CLI::App* chosen_ = nullptr;
  RunFunction run_;
};

/// Every visgrab command (wc, sim, grasp, db, run, benchmark, analyze, merge, slurm, baseline,
/// render, agreement).
std::unique_ptr<CommandLine> makeCommandLine();

/// The name of `cmd` as typed: "visgrab db list".
std::string commandPath(const CLI::App& cmd);

/// A flag `name` on `cmd` (no value; given twice is a usage error).
CLI::Option* addFlag(CLI::App& cmd, const std::string& name, const std::string& description);

/// `--threads N` on `cmd` (default: the number of cores; N >= 1); read it with threadsOption.
CLI::Option* addThreadsOption(CLI::App& cmd);

/// `--data DIR` on `cmd`: the folder with the project's scene data; read it with dataFolder.
CLI::Option* addDataOption(CLI::App& cmd);

/// `--quiet` on `cmd`: no progress on stderr.
CLI::Option* addQuietFlag(CLI::App& cmd);

/// The help of every `--db` option.
inline constexpr const char* kDatabaseOptionHelp =
    "A generated database folder or an original VisGraB manifest";

/// `--scenes FILTER` on `cmd` (repeatable: the filters are OR-ed); read it with scenesFilter.
CLI::Option* addScenesOption(CLI::App& cmd);

/// `--engine ode|mujoco` on `cmd`: the physics engine of its trials; read it with engineOption.
CLI::Option* addEngineOption(CLI::App& cmd);

/// --engine's value ("ode" when not given). @throws UsageError for an unknown engine or one this
/// build lacks (saying how to get it).
std::string engineOption(const Arguments& a);

/// The --scenes filters as one filter text (joined by ';', OR); empty when none was given.
std::string scenesFilter(const Arguments& a);

/// An option that takes several numbers (`--pose 1 2 3`, `--pose=1,2,3` or one quoted word);
/// read it with Arguments::occurrences.
CLI::Option* addNumberList(CLI::App& cmd, const std::string& name, const std::string& typeName,
                           const std::string& description);

/// A check for an option's value: an integer >= `lo`.
CLI::Validator integerAtLeast(int lo);

/// A check for an option's value: a finite number > 0.
CLI::Validator positiveNumber();

/// The value of option `name` as an integer >= `lo`, or `def` when not given.
/// @throws UsageError naming the option for anything else.
int integerOption(const Arguments& a, const std::string& name, int def, int lo);

/// `text`, the value of option `option`, as a finite number.
/// @throws UsageError naming the option for anything else.
double parseNumber(const std::string& option, const std::string& text);

/// The value of option `name` as a number strictly between 0 and 1, or `def` when not given.
/// @throws UsageError naming the option for anything else.
double fractionOption(const Arguments& a, const std::string& name, double def);

/// `text`, a --hand value, as a file: cli::handPath. @throws UsageError ("--hand: unknown hand
/// ...") for a name that is neither a file nor a hand of `data`.
std::filesystem::path handOptionPath(const std::string& text, const std::filesystem::path& data);

/// --threads N (default: the number of cores).
int threadsOption(const Arguments& a);

/// The folder with the project's scene data (objects, hands, materials): --data, else
/// $VISGRAB_DATA, else the source tree's scenes/ folder this binary was built from.
std::filesystem::path dataFolder(const Arguments& a);

/// `run` with the commands' error policy: a UsageError goes on (exit 2); a load error prints
/// its file:line diagnostics and any other exception its message, exit 1.
RunFunction guarded(RunFunction run);

}  // namespace visgrab::app
