#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace visgrab::app {

/// A command-line mistake; main prints it with the usage line and exits with code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The arguments of one subcommand: positionals and `--name value` / `--flag` options.
class Arguments {
 public:
  /// Splits `args`; names listed in `flags` take no value, every other `--name` takes one.
  /// @throws UsageError for an option missing its value.
  Arguments(const std::vector<std::string>& args, const std::vector<std::string>& flags);

  /// The positional arguments in order.
  const std::vector<std::string>& positionals() const { return positionals_; }
  /// True if the flag was given.
  bool flag(const std::string& name) const;
  /// The value of an option, if given (the last one when it is given several times).
  std::optional<std::string> option(const std::string& name) const;
  /// Every value of an option given several times, in order (empty if not given).
  std::vector<std::string> values(const std::string& name) const;
  /// @throws UsageError if an option or flag not in `known` was given.
  void rejectUnknown(const std::vector<std::string>& known) const;
  /// @throws UsageError unless exactly `n` positionals were given (`what` names them).
  void requirePositionals(std::size_t n, const std::string& what) const;

 private:
  std::vector<std::string> positionals_;
  std::vector<std::pair<std::string, std::optional<std::string>>> options_;
};

/// One subcommand: `visgrab <group> <name> ...`.
struct Command {
  /// Group ("wc").
  std::string group;
  /// Name ("info"); empty for a one-word command (`visgrab sim FILE`).
  std::string name;
  /// Usage after "visgrab group name".
  std::string usage;
  /// One-line description.
  std::string summary;
  /// Runs the command; returns the process exit code.
  std::function<int(const std::vector<std::string>& args)> run;
};

/// The value of option `name` as an integer >= `lo`, or `def` when not given.
/// @throws UsageError naming the option for anything else.
int integerOption(const Arguments& a, const std::string& name, int def, int lo);

/// --threads N (default: the number of cores). @throws UsageError unless N >= 1.
int threadsOption(const Arguments& a);

/// The folder with the project's scene data (objects, hands, materials): --data, else
/// $VISGRAB_DATA, else the source tree's scenes/ folder this binary was built from.
std::filesystem::path dataFolder(const Arguments& a);

/// `run` with the commands' error policy: a UsageError goes on to dispatch (exit 2); a load
/// error prints its file:line diagnostics and any other exception its message, exit 1.
std::function<int(const std::vector<std::string>&)> guarded(
    std::function<int(const std::vector<std::string>&)> run);

/// Runs the command line (argv without the program name) against `commands`.
/// Exit codes: the command's own, 2 for usage errors.
int dispatch(const std::vector<Command>& commands, const std::vector<std::string>& argv);

}  // namespace visgrab::app
