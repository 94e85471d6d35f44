#include "command_line.hpp"

#include "rw/common/diagnostic.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <thread>

namespace visgrab::app {

Arguments::Arguments(const std::vector<std::string>& args, const std::vector<std::string>& flags) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0 || a.size() == 2) {
      positionals_.push_back(a);
      continue;
    }
    std::string name = a.substr(2);
    if (const auto eq = name.find('='); eq != std::string::npos) {
      options_.emplace_back(name.substr(0, eq), name.substr(eq + 1));
    } else if (std::find(flags.begin(), flags.end(), name) != flags.end()) {
      options_.emplace_back(name, std::nullopt);
    } else if (i + 1 < args.size()) {
      options_.emplace_back(name, args[++i]);
    } else {
      throw UsageError("option --" + name + " needs a value");
    }
  }
}

bool Arguments::flag(const std::string& name) const {
  return std::any_of(options_.begin(), options_.end(),
                     [&](const auto& o) { return o.first == name; });
}

std::optional<std::string> Arguments::option(const std::string& name) const {
  for (auto it = options_.rbegin(); it != options_.rend(); ++it) {
    if (it->first == name) return it->second;
  }
  return std::nullopt;
}

std::vector<std::string> Arguments::values(const std::string& name) const {
  std::vector<std::string> out;
  for (const auto& [n, value] : options_) {
    if (n == name && value) out.push_back(*value);
  }
  return out;
}

void Arguments::rejectUnknown(const std::vector<std::string>& known) const {
  for (const auto& [name, value] : options_) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw UsageError("unknown option --" + name);
    }
  }
}

void Arguments::requirePositionals(std::size_t n, const std::string& what) const {
  if (positionals_.size() < n) throw UsageError("missing " + what);
  if (positionals_.size() > n) throw UsageError("unexpected argument '" + positionals_[n] + "'");
}

int integerOption(const Arguments& a, const std::string& name, int def, int lo) {
  const auto v = a.option(name);
  if (!v) return def;
  try {
    std::size_t used = 0;
    const int n = std::stoi(*v, &used);
    if (used == v->size() && n >= lo) return n;
  } catch (const std::exception&) {
  }
  throw UsageError("--" + name + " needs an integer >= " + std::to_string(lo) + ", got \"" + *v +
                   "\"");
}

int threadsOption(const Arguments& a) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return integerOption(a, "threads", static_cast<int>(cores), 1);
}

std::filesystem::path dataFolder(const Arguments& a) {
  if (const auto d = a.option("data")) return *d;
  if (const char* env = std::getenv("VISGRAB_DATA"); env != nullptr && *env != '\0') return env;
  return VISGRAB_SCENES_DIR;
}

std::function<int(const std::vector<std::string>&)> guarded(
    std::function<int(const std::vector<std::string>&)> run) {
  return [run = std::move(run)](const std::vector<std::string>& args) {
    try {
      return run(args);
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

namespace {

// "group name" or, for a one-word command (empty name), "group".
std::string commandWords(const Command& c) {
  return c.name.empty() ? c.group : c.group + " " + c.name;
}

void printHelp(const std::vector<Command>& commands) {
  std::cout << "visgrab: the VisGraB benchmark for vision-based grasping\n\nUsage:\n";
  for (const Command& c : commands) {
    std::cout << "  visgrab " << commandWords(c) << " " << c.usage << "\n      " << c.summary
              << "\n";
  }
  std::cout << "\n  visgrab --help | --version\n";
}

}  // namespace

int dispatch(const std::vector<Command>& commands, const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h" || argv[0] == "help") {
    printHelp(commands);
    return argv.empty() ? 2 : 0;
  }
  if (argv[0] == "--version") {
    std::cout << "visgrab " << VISGRAB_VERSION << "\n";
    return 0;
  }
  const bool groupKnown = std::any_of(commands.begin(), commands.end(),
                                      [&](const Command& c) { return c.group == argv[0]; });
  for (const Command& c : commands) {
    const bool oneWord = c.name.empty();
    if (c.group != argv[0] || (!oneWord && (argv.size() < 2 || c.name != argv[1]))) continue;
    const std::vector<std::string> rest(argv.begin() + (oneWord ? 1 : 2), argv.end());
    if (std::find(rest.begin(), rest.end(), "--help") != rest.end()) {
      std::cout << "usage: visgrab " << commandWords(c) << " " << c.usage << "\n"
                << c.summary << "\n";
      return 0;
    }
    try {
      return c.run(rest);
    } catch (const UsageError& e) {
      std::cerr << "visgrab " << commandWords(c) << ": " << e.what() << "\nusage: visgrab "
                << commandWords(c) << " " << c.usage << "\n";
      return 2;
    }
  }
  std::cerr << "visgrab: unknown command '" << argv[0]
            << (argv.size() > 1 && groupKnown ? " " + argv[1] : "")
            << "'; run 'visgrab --help' for the list\n";
  return 2;
}

}  // namespace visgrab::app
