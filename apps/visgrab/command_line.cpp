#include "command_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli_common/cli_errors.hpp"
#include "cli_common/data_folder.hpp"
#include "rw/common/diagnostic.hpp"
#include "rwsim/engines/engine_registry.hpp"

namespace visgrab::app {

namespace {

// The command the parse went into deepest (the top level when none).
const CLI::App* deepestCommand(const CLI::App& root) {
  const CLI::App* app = &root;
  while (!app->get_subcommands().empty()) app = app->get_subcommands().back();
  return app;
}

}  // namespace

// --- Arguments ------------------------------------------------------------------------------

const CLI::Option& Arguments::get(const std::string& name) const {
  const CLI::Option* opt = cmd_->get_option_no_throw("--" + name);
  if (opt == nullptr) {
    throw std::logic_error(commandPath(*cmd_) + " has no option --" + name);
  }
  return *opt;
}

std::vector<std::string> Arguments::positionals() const {
  std::vector<std::string> out;
  for (const CLI::Option* opt : cmd_->get_options()) {
    if (!opt->get_positional()) continue;
    for (const auto& r : opt->results()) out.push_back(r);
  }
  return out;
}

bool Arguments::flag(const std::string& name) const { return get(name).count() > 0; }

std::optional<std::string> Arguments::option(const std::string& name) const {
  const CLI::Option& opt = get(name);
  if (opt.count() == 0 || opt.results().empty()) return std::nullopt;
  return opt.results().back();
}

std::vector<std::string> Arguments::values(const std::string& name) const {
  const CLI::Option& opt = get(name);
  return opt.count() == 0 ? std::vector<std::string>{} : opt.results();
}

std::vector<std::vector<std::string>> Arguments::occurrences(const std::string& name) const {
  std::vector<std::vector<std::string>> out;
  bool separated = true;
  for (const auto& r : values(name)) {
    // CLI11 puts an empty result between two occurrences (inject_separator).
    if (r.empty()) {
      separated = true;
      continue;
    }
    if (separated) out.emplace_back();
    separated = false;
    out.back().push_back(r);
  }
  return out;
}

void Arguments::requirePositionals(std::size_t n, const std::string& what) const {
  const auto p = positionals();
  if (p.size() < n) throw UsageError("missing " + what);
  if (p.size() > n) throw UsageError("unexpected argument '" + p[n] + "'");
}

// --- CommandLine ----------------------------------------------------------------------------

CommandLine::CommandLine()
    : root_(std::make_unique<CLI::App>("visgrab: the VisGraB benchmark for vision-based grasping",
                                       "visgrab")),
      formatter_(cli::makeHelpFormatter()) {
  root_->formatter(formatter_);
  root_->require_subcommand(1);
  root_->set_version_flag("--version", std::string("visgrab ") + VISGRAB_VERSION,
                          "Print the version and exit");
  root_->footer(
      "Run 'visgrab COMMAND --help' (or -h) for a command's options.\n"
      "Options: '--name value' and '--name=value' are the same; an option given twice is an\n"
      "error unless its help says 'repeatable'.\n"
      "Exit codes: 0 success, 1 bad input (an unreadable or invalid file) or a run that ran\n"
      "no trial, 2 a command-line mistake, 130 or 143 when SIGINT (Ctrl-C) or SIGTERM stopped\n"
      "a run (its finished trials are kept; --resume continues it).");
}

CLI::App& CommandLine::addGroup(const std::string& name, const std::string& summary) {
  CLI::App* group = root_->add_subcommand(name, summary);
  group->require_subcommand(1);
  group->group("Commands");
  return *group;
}

CLI::App& CommandLine::addCommand(CLI::App* parent, const std::string& name,
                                  const std::string& summary, RunFunction run) {
  CLI::App* cmd = (parent != nullptr ? parent : root_.get())->add_subcommand(name, summary);
  cmd->group("Commands");
  cmd->final_callback([this, cmd, run = std::move(run)] {
    chosen_ = cmd;
    run_ = run;
  });
  return *cmd;
}

int CommandLine::run(const std::vector<std::string>& argv) {
  chosen_ = nullptr;
  run_ = nullptr;
  if (argv.empty() || argv[0] == "help") {
    std::cout << root_->help();
    return argv.empty() ? 2 : 0;
  }
  // An unknown command word (CLI11 would only say that a command is missing).
  const CLI::App* group = root_.get();
  for (const std::string& word : argv) {
    if (word.empty() || word[0] == '-' || group->get_subcommands({}).empty()) break;
    const CLI::App* next = nullptr;
    for (const CLI::App* sub : group->get_subcommands({})) {
      if (sub->check_name(word)) next = sub;
    }
    if (next == nullptr) {
      std::cerr << commandPath(*group) << ": unknown command '" << word << "'; run '"
                << commandPath(*group) << " --help' for the list\n";
      return 2;
    }
    group = next;
  }
  std::vector<std::string> reversed(argv.rbegin(), argv.rend());
  try {
    root_->parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::cout << root_->help();
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    const CLI::App* cmd = deepestCommand(*root_);
    const bool top = cmd == root_.get();
    std::cerr << commandPath(*cmd) << ": " << cli::describeParseError(e, *cmd) << "\n"
              << formatter_->make_usage(cmd, commandPath(*cmd)) << "run '" << commandPath(*cmd)
              << " --help' for " << (top ? "the commands" : "its options") << "\n";
    return 2;
  }
  try {
    return run_(Arguments(*chosen_));
  } catch (const UsageError& e) {
    std::cerr << commandPath(*chosen_) << ": " << e.what() << "\n"
              << formatter_->make_usage(chosen_, commandPath(*chosen_)) << "run '"
              << commandPath(*chosen_) << " --help' for its options\n";
    return 2;
  }
}

// --- Options --------------------------------------------------------------------------------

std::string commandPath(const CLI::App& cmd) {
  std::string path = cmd.get_name();
  for (const CLI::App* p = cmd.get_parent(); p != nullptr; p = p->get_parent()) {
    path = p->get_name() + " " + path;
  }
  return path;
}

CLI::Option* addFlag(CLI::App& cmd, const std::string& name, const std::string& description) {
  return cmd.add_flag(name, description)
      ->multi_option_policy(CLI::MultiOptionPolicy::Throw)
      ->disable_flag_override();
}

CLI::Option* addThreadsOption(CLI::App& cmd) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return cmd.add_option("--threads", "Worker threads (default: the number of cores, here)")
      ->type_name("N")
      ->default_str(std::to_string(cores))
      ->check(integerAtLeast(1));
}

CLI::Option* addDataOption(CLI::App& cmd) {
  return cmd
      .add_option("--data",
                  "The project's scene data: objects, hands, materials (default: $VISGRAB_DATA, "
                  "else the installed share/visgrab/scenes, else the source tree's scenes/)")
      ->type_name("DIR")
      ->envname("VISGRAB_DATA")
      ->default_str(visgrab::cli::defaultDataFolder(VISGRAB_SCENES_DIR).string());
}

CLI::Option* addQuietFlag(CLI::App& cmd) {
  return addFlag(cmd, "--quiet", "No progress output on stderr");
}

CLI::Option* addScenesOption(CLI::App& cmd) {
  return cmd
      .add_option("--scenes",
                  "The scenes to take (docs/database-format.md, Filters): ',' AND, ';' OR, "
                  "'!' NOT, e.g. 'plain,single,cocacola' or 'textured/double/*' (default: all; "
                  "repeatable: OR)")
      ->type_name("FILTER")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

CLI::Option* addEngineOption(CLI::App& cmd) {
  std::string names;
  for (const auto& e : rwsim::engines::knownEngines()) names += (names.empty() ? "" : "|") + e;
  std::string built;
  for (const auto& e : rwsim::engines::availableEngines()) built += (built.empty() ? "" : ", ") + e;
  const std::string help =
      "The physics engine of the trials: ode (the benchmark's, default) or mujoco (a second "
      "engine for cross-checks, built when Debian's libmujoco-dev is installed; "
      "docs/validation.md). This build has: " +
      built;
  return cmd.add_option("--engine", help)->type_name(names);
}

std::string engineOption(const Arguments& a) {
  const auto engine = a.option("engine");
  if (!engine) return std::string(rwsim::engines::kDefaultEngine);
  try {
    rwsim::engines::checkEngine(*engine);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--engine: ") + e.what());
  }
  return *engine;
}

std::filesystem::path handOptionPath(const std::string& text, const std::filesystem::path& data) {
  try {
    return cli::handPath(text, data);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--hand: ") + e.what());
  }
}

std::string scenesFilter(const Arguments& a) {
  std::string text;
  for (const auto& f : a.values("scenes")) text += (text.empty() ? "" : ";") + f;
  return text;
}

CLI::Option* addNumberList(CLI::App& cmd, const std::string& name, const std::string& typeName,
                           const std::string& description) {
  CLI::Option* opt = cmd.add_option(name, description)
                         ->type_name(typeName)
                         ->expected(1, CLI::detail::expected_max_vector_size)
                         ->allow_extra_args()
                         ->delimiter(',')
                         ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  // An empty result between two occurrences, so a list given twice is found out.
  opt->inject_separator();
  return opt;
}

namespace {

// The integer `text` is, if all of it is one.
std::optional<long> parseInteger(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return std::nullopt;
  return v;
}

}  // namespace

CLI::Validator integerAtLeast(int lo) {
  return CLI::Validator(
      [lo](std::string& text) -> std::string {
        const auto v = parseInteger(text);
        if (v && *v >= lo && *v <= std::numeric_limits<int>::max()) return {};
        return "needs an integer >= " + std::to_string(lo) + ", got \"" + text + "\"";
      },
      "");
}

CLI::Validator positiveNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
          return "needs a number, got '" + text + "'";
        }
        return v > 0.0 ? std::string() : "must be > 0, got " + text;
      },
      "");
}

int integerOption(const Arguments& a, const std::string& name, int def, int lo) {
  const auto v = a.option(name);
  if (!v) return def;
  const auto n = parseInteger(*v);
  if (n && *n >= lo && *n <= std::numeric_limits<int>::max()) return static_cast<int>(*n);
  throw UsageError("--" + name + " needs an integer >= " + std::to_string(lo) + ", got \"" + *v +
                   "\"");
}

double parseNumber(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
    throw UsageError("--" + option + ": '" + text + "' is not a number");
  }
  return v;
}

double fractionOption(const Arguments& a, const std::string& name, double def) {
  const auto text = a.option(name);
  if (!text) return def;
  const double v = parseNumber(name, *text);
  if (!(v > 0.0 && v < 1.0)) {
    throw UsageError("--" + name + " needs a number between 0 and 1 (exclusive), got " + *text);
  }
  return v;
}

int threadsOption(const Arguments& a) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return integerOption(a, "threads", static_cast<int>(cores), 1);
}

std::filesystem::path dataFolder(const Arguments& a) {
  // $VISGRAB_DATA reaches the option through CLI11 (envname). Without either: the installed
  // data next to the program, else the source tree's (cli_common/data_folder.hpp).
  if (auto data = a.option("data")) return *data;
  return visgrab::cli::defaultDataFolder(VISGRAB_SCENES_DIR);
}

RunFunction guarded(RunFunction run) {
  return [run = std::move(run)](const Arguments& a) {
    try {
      return run(a);
    } catch (const UsageError&) {
      throw;
    } catch (const rw::common::LoadError& e) {
      std::cerr << e.what() << "\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
  };
}

}  // namespace visgrab::app
