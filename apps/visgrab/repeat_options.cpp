#include "repeat_options.hpp"

#include <cstdint>
#include <filesystem>

#include "visgrab/results/statistics.hpp"
#include "visgrab/runner/noise_model.hpp"

namespace visgrab::app {

void addRepeatOptions(CLI::App& command) {
  command
      .add_option("--repeats",
                  "Run each grasp N times: repeat 0 unperturbed, repeats 1..N-1 under seeded "
                  "perturbations of the hand's and objects' poses, friction and mass "
                  "(docs/noise-model.md); trials.csv gains repeat and seed columns and "
                  "RESULTS/grasps.csv gives each grasp's P(success) with its Wilson interval "
                  "(default 1: no repeats)")
      ->type_name("N")
      ->check(integerAtLeast(1));
  command
      .add_option("--noise",
                  "The noise model of the repeats (xml/noise-model.xsd; default: the values of "
                  "scenes/noise/default.noise.xml)")
      ->type_name("FILE");
  command.add_option("--seed", "Base seed of the repeats' perturbations (default 1)")
      ->type_name("S")
      ->check(integerAtLeast(0));
  addFlag(command, "--adaptive",
          "Stop repeating a grasp once its first trials agree (all held or all not held) by a "
          "rule with a stated error rate; grasps whose repeats disagree run all N "
          "(docs/noise-model.md, \"Adaptive repeats\")");
  command.add_option("--adaptive-alpha", "The adaptive rule's error rate (default 0.05)")
      ->type_name("A");
  command
      .add_option("--adaptive-margin",
                  "The adaptive rule's margin (default 0.65: a grasp is decided when its "
                  "unperturbed and 3 perturbed trials agree)")
      ->type_name("M");
}

void readRepeatOptions(const Arguments& a, runner::RunOptions& options) {
  options.repeats = integerOption(a, "repeats", 1, 1);
  if (options.repeats > results::kMaxRepeats) {
    throw UsageError("--repeats: at most " + std::to_string(results::kMaxRepeats) +
                     " (a grasp's P to within 0.01; docs/noise-model.md), got " +
                     std::to_string(options.repeats));
  }
  if (const auto noise = a.option("noise")) options.noise = *noise;
  options.noiseSeed = static_cast<std::uint64_t>(integerOption(a, "seed", 1, 0));
  options.adaptive = a.flag("adaptive");
  options.adaptiveAlpha = fractionOption(a, "adaptive-alpha", options.adaptiveAlpha);
  options.adaptiveMargin = fractionOption(a, "adaptive-margin", options.adaptiveMargin);
  if (options.repeats == 1) {
    for (const char* name : {"noise", "seed"}) {
      if (a.option(name)) throw UsageError(std::string("--") + name + " needs --repeats N, N > 1");
    }
    if (options.adaptive) throw UsageError("--adaptive needs --repeats N, N > 1");
  }
  if (!options.adaptive && (a.option("adaptive-alpha") || a.option("adaptive-margin"))) {
    throw UsageError("--adaptive-alpha and --adaptive-margin need --adaptive");
  }
  if (options.adaptive) {
    const int k = results::repeatsToDecide(options.adaptiveAlpha, options.adaptiveMargin);
    const int needed =
        results::minimumAdaptiveRepeats(options.adaptiveAlpha, options.adaptiveMargin);
    if (options.repeats < needed) {
      throw UsageError("--adaptive decides a grasp after the unperturbed and " + std::to_string(k) +
                       " agreeing perturbed trials: --repeats " + std::to_string(options.repeats) +
                       " never stops one early (give " + std::to_string(needed) +
                       " or more, or a larger --adaptive-margin)");
    }
  }
}

std::vector<std::string> repeatArguments(const Arguments& a) {
  runner::RunOptions options;
  readRepeatOptions(a, options);
  if (options.repeats == 1) return {};
  std::vector<std::string> words = {"--repeats", std::to_string(options.repeats), "--seed",
                                    std::to_string(options.noiseSeed)};
  if (!options.noise.empty()) {
    runner::loadNoiseModel(options.noise);  // a bad file fails here, not in every array task
    words.insert(words.end(), {"--noise", std::filesystem::absolute(options.noise).string()});
  }
  if (options.adaptive) {
    words.emplace_back("--adaptive");
    for (const char* name : {"adaptive-alpha", "adaptive-margin"}) {
      if (const auto value = a.option(name))
        words.insert(words.end(), {std::string("--") + name, *value});
    }
  }
  return words;
}

}  // namespace visgrab::app
