#include "run_commands.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "baseline_commands.hpp"
#include "cli_common/data_folder.hpp"
#include "progress_reporter.hpp"
#include "protocol_option.hpp"
#include "repeat_options.hpp"
#include "rw/common/diagnostic.hpp"
#include "rw/common/stop_signals.hpp"
#include "stage_times.hpp"
#include "visgrab/analysis/report.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/view/report_pictures.hpp"

namespace visgrab::app {

namespace {

// True (with a message) when no trial ran and none was found done: every grasp it read was
// rejected, or (a whole run, not a shard, which may have no work) the grasp files hold no grasp
// of the run's scenes. A script must notice (exit 1). Some rejected grasps beside trials keep
// exit 0.
bool nothingRan(const runner::RunSummary& summary, const char* command, bool shard) {
  if (summary.trials > 0 || summary.resumed > 0) return false;
  if (!summary.rejected.empty()) {
    std::cerr << "visgrab " << command << ": every grasp (" << summary.rejected.size()
              << ") was rejected; no trial ran\n";
    return true;
  }
  if (shard) return false;
  std::cerr << "visgrab " << command
            << ": the grasp files hold no grasp of the run's scenes; no trial ran\n";
  return true;
}

namespace fs = std::filesystem;

// A note when the run's trials are of fewer scenes than the run covers: the analyses count the
// others as scenes where a method suggested no grasp (the paper's rule), which is what a method
// run on a subset by mistake (no --scenes) does not mean.
void noteScenesWithoutGrasps(const runner::RunSummary& summary) {
  const int without = summary.scenes - summary.scenesWithTrials;
  if (without <= 0 || summary.scenesWithTrials == 0) return;
  std::cerr << "note: the grasps are of " << summary.scenesWithTrials << " of the run's "
            << summary.scenes << " scenes; the analyses count the other " << without
            << " as scenes where a method suggested no grasp (to run only some scenes, give "
               "--scenes)\n";
}

// The runner's progress on stderr (none with --quiet).
std::function<void(const runner::RunProgress&)> runProgress(bool quiet) {
  if (quiet) return {};
  auto reporter = std::make_shared<ProgressReporter>("run", "trials");
  return [reporter](const runner::RunProgress& p) {
    // The last trial is reported before its scene counts as done: the scene's own report that
    // follows is the final line.
    if (p.trialsDone >= p.trialsTotal && p.scenesDone < p.scenesTotal) return;
    reporter->update(
        p.trialsDone, p.trialsTotal,
        "scenes " + std::to_string(p.scenesDone) + "/" + std::to_string(p.scenesTotal));
  };
}

// What a command stopped by SIGINT/SIGTERM prints; returns its exit code (128 + the signal).
int stoppedBySignal(const rw::common::StopRequested& e, const std::string& command) {
  std::cerr << "\nvisgrab " << command << ": " << rw::common::signalName(rw::common::stopSignal())
            << ": " << e.what() << "\n";
  return rw::common::stopExitCode(rw::common::stopSignal());
}

// Runs the benchmark with SIGINT and SIGTERM as a stop request (docs/report.md, "Stopping,
// failures and resuming"): the running trials finish and are written, then the run stops.
// Returns nullopt when it stopped (the message printed); the caller exits with stopExitCode.
std::optional<runner::RunSummary> runStoppable(runner::RunOptions& options, bool quiet,
                                               const std::string& command) {
  rw::common::catchStopSignals();
  options.stop = &rw::common::stopSignalFlag();
  try {
    return runner::runBenchmark(options, runProgress(quiet));
  } catch (const rw::common::StopRequested& e) {
    stoppedBySignal(e, command);
    return std::nullopt;
  }
}

/// --hand: a folder, a grasp description or a hand's name in DATA/hands (default: the SDH).
fs::path handOption(const Arguments& a, const fs::path& data) {
  const auto hand = a.option("hand");
  return hand ? handOptionPath(*hand, data) : data / "hands/sdh/sdh.grasp.xml";
}

int runRun(const Arguments& a) {
  runner::RunOptions options;
  const auto grasps = a.values("grasps");
  options.database = a.option("db").value();
  options.grasps.assign(grasps.begin(), grasps.end());
  options.out = a.option("out").value();
  options.hand = handOption(a, dataFolder(a));
  options.engine = engineOption(a);
  options.scenes = scenesFilter(a);
  options.threads = threadsOption(a);
  options.resume = a.flag("resume");
  options.protocol = protocolOption(a).value_or(fs::path());
  readRepeatOptions(a, options);
  if (const auto dt = a.option("dt")) {
    options.timeStep = parseNumber("dt", *dt);
    if (!(*options.timeStep > 0.0)) throw UsageError("--dt must be > 0, got " + *dt);
    if (options.engine != "ode") {
      throw UsageError("--dt sets ODE's time step; the " + options.engine +
                       " engine has its own (docs/validation.md)");
    }
  }
  const auto shard = a.option("shard");
  const auto of = a.option("of");
  if (shard.has_value() != of.has_value()) {
    throw UsageError("--shard K and --of N go together");
  }
  if (shard) {
    options.shard =
        runner::ShardSpec{integerOption(a, "shard", 1, 1), integerOption(a, "of", 1, 1)};
    if (options.shard->index > options.shard->count) {
      throw UsageError("--shard " + *shard + " is beyond --of " + *of +
                       " (shards are numbered 1 to N)");
    }
  }
  const bool quiet = a.flag("quiet");
  const auto done = runStoppable(options, quiet, "run");
  if (!done) return rw::common::stopExitCode(rw::common::stopSignal());
  const runner::RunSummary& summary = *done;
  for (const auto& d : summary.rejected) std::cerr << d.format() << "\n";
  if (options.repeats > 1) {
    std::cout << "grasps.csv: P(success) per grasp over " << options.repeats << " repeats"
              << (options.adaptive ? " (adaptive)" : "") << "\n";
  }
  std::cout << summary.trials << " trials run, " << summary.resumed << " resumed, "
            << summary.rejected.size() << " grasps rejected; " << summary.scenes << " scenes, "
            << summary.methods << " methods\n";
  for (const auto& [outcome, n] : summary.outcomes)
    std::cout << "  " << outcome << " " << n << "\n";
  std::cout << "results in " << options.out.string();
  if (options.shard) std::cout << " (" << runner::describe(*options.shard) << ")";
  std::cout << "\n";
  if (!options.shard) noteScenesWithoutGrasps(summary);
  return nothingRan(summary, "run", options.shard.has_value()) ? 1 : 0;
}

// The report's pictures (a few trials per method and condition, simulated again and drawn),
// unless --no-pictures.
analysis::ShowcaseDrawer pictureDrawer(const Arguments& a, int threads, bool quiet) {
  if (a.flag("no-pictures")) return {};
  view::ReportPictureOptions options;
  options.threads = threads;
  options.data = dataFolder(a);  // its protocols/: the protocol of a run other than the lift's
  if (!quiet) {
    auto reporter = std::make_shared<ProgressReporter>("report pictures", "pictures");
    options.progress = [reporter](int done, int total) { reporter->update(done, total); };
  }
  return [options, quiet](std::vector<analysis::Showcase>& showcases,
                          const std::vector<results::RunResults>& runs, const fs::path& dir) {
    view::drawShowcases(showcases, runs, dir, options);
    // One line per distinct reason a picture is missing.
    std::vector<std::string> reasons;
    for (const auto& s : showcases) {
      if (s.image.empty() && std::find(reasons.begin(), reasons.end(), s.note) == reasons.end()) {
        reasons.push_back(s.note);
      }
    }
    if (!quiet) {
      for (const auto& r : reasons) std::cerr << "report pictures: not drawn: " << r << "\n";
    }
  };
}

// The report's statistics options (--ci-level, --bootstrap, --seed) and --threads.
analysis::AnalysisOptions analysisOptions(const Arguments& a) {
  analysis::AnalysisOptions options;
  options.ciLevel = fractionOption(a, "ci-level", options.ciLevel);
  options.bootstrapResamples = integerOption(a, "bootstrap", options.bootstrapResamples, 0);
  options.bootstrapSeed = static_cast<std::uint64_t>(
      integerOption(a, "seed", static_cast<int>(options.bootstrapSeed), 0));
  options.threads = threadsOption(a);
  if (const auto problem = analysis::checkOptions(options)) {
    throw UsageError(problem->cliOption + ": " + problem->problem);
  }
  return options;
}

int runAnalyze(const Arguments& a) {
  const auto out = a.option("out");
  const analysis::AnalysisOptions options = analysisOptions(a);
  std::vector<fs::path> dirs;
  for (const auto& dir : a.positionals()) dirs.emplace_back(dir);
  std::vector<rw::common::Diagnostic> warnings;
  // Two folders of the same name get labels that tell them apart (benchA/results, ...).
  const std::vector<results::RunResults> runs = results::readResultFolders(dirs, &warnings);
  if (!a.flag("allow-unfinished")) {
    for (std::size_t i = 0; i < runs.size(); ++i) {
      results::requireFinished(runs[i], dirs[i], "--allow-unfinished");
    }
  }
  for (const auto& w : warnings) std::cerr << w.format() << "\n";
  analysis::writeReport(runs, *out, options, pictureDrawer(a, threadsOption(a), a.flag("quiet")));
  std::cout << "report in " << *out << " (report.html, report.md, CSV tables)\n";
  return 0;
}

// Generates the database at `dir` (the scenes `filter` selects) unless its index exists.
// Returns what it did, for the stage times.
std::string ensureDatabase(const fs::path& dir, const std::string& filter, int threads,
                           const fs::path& data, bool quiet) {
  if (fs::exists(dir / "index.xml")) return "present";
  std::cerr << "visgrab benchmark: no database at " << dir.string() << "; generating it\n";
  database::SceneFilter parsed;
  try {
    parsed = filter.empty() ? database::SceneFilter() : database::SceneFilter::parse(filter);
  } catch (const database::FilterError& e) {
    throw UsageError(std::string("--scenes: ") + e.what());
  }
  std::vector<database::SceneConditions> scenes;
  for (const auto& s : database::enumerateScenes()) {
    if (parsed.matches(database::sceneIdOf(s), &s)) scenes.push_back(s);
  }
  generator::GeneratorOptions options;
  options.out = dir;
  options.objectSpec = data / "objects" / "objects.xml";
  options.handFolder = data / "hands" / "sdh";
  options.materials = data / "materials.xml";
  options.threads = threads;
  // The same default as `visgrab db generate`: the realistic camera.
  options.camera = generator::findCameraProfile("realistic", data / "cameras");
  rw::common::catchStopSignals();
  options.stop = &rw::common::stopSignalFlag();
  std::optional<ProgressReporter> reporter;
  if (!quiet) reporter.emplace("generating the database", "scenes");
  const auto report =
      generator::generateDatabase(scenes, options, [&](const generator::GenerationProgress& p) {
        if (reporter) reporter->update(p.done, p.total, p.lastId);
      });
  reporter.reset();
  for (const auto& f : report.failures) std::cerr << "failed: " << f << "\n";
  if (!report.failures.empty()) throw std::runtime_error("the database could not be generated");
  return std::to_string(report.generated) + " scenes generated";
}

int runBenchmarkCommand(const Arguments& a) {
  const auto out = a.option("out");
  const fs::path data = dataFolder(a);
  const fs::path db = a.option("db").value_or("database");
  const int threads = threadsOption(a);
  const bool quiet = a.flag("quiet");
  const std::string scenes = scenesFilter(a);
  const std::optional<fs::path> protocol = protocolOption(a);  // a bad file fails before any work
  StageTimes times;
  times.start("database");
  try {
    times.stop(ensureDatabase(db, scenes, threads, data, quiet));
  } catch (const rw::common::StopRequested& e) {
    return stoppedBySignal(e, "benchmark");
  }
  std::vector<fs::path> graspSources;
  for (const auto& g : a.values("grasps")) graspSources.emplace_back(g);
  times.start("baseline");
  if (graspSources.empty()) {
    // No method given: the baseline's grasps, made once (an existing file is complete: it is
    // written atomically) and reused by --resume.
    const fs::path grasps = fs::path(*out) / "grasps" / "baseline.csv";
    if (!fs::exists(grasps) || !a.flag("resume")) {
      if (!quiet)
        std::cerr << "visgrab benchmark: baseline grasps into " << grasps.string() << "\n";
      const int n = writeBaselineGrasps(db, scenes, grasps, threads, quiet);
      times.stop(std::to_string(n) + " grasps");
    } else {
      times.stop("reused " + grasps.string());
    }
    graspSources = {grasps};
  } else {
    times.stop("not run (--grasps)");
  }
  runner::RunOptions options;
  options.database = db;
  options.grasps = graspSources;
  options.out = fs::path(*out) / "results";
  options.hand = handOption(a, data);
  options.engine = engineOption(a);
  options.scenes = scenes;
  options.threads = threads;
  options.resume = a.flag("resume");
  options.protocol = protocol.value_or(fs::path());
  times.start("trials");
  const auto done = runStoppable(options, quiet, "benchmark");
  if (!done) return rw::common::stopExitCode(rw::common::stopSignal());
  const runner::RunSummary& summary = *done;
  times.stop(std::to_string(summary.trials) + " trials run, " + std::to_string(summary.resumed) +
             " resumed");
  for (const auto& d : summary.rejected) std::cerr << d.format() << "\n";
  std::cout << summary.trials << " trials run, " << summary.resumed << " resumed, "
            << summary.rejected.size() << " grasps rejected\n";
  if (nothingRan(summary, "benchmark", false)) return 1;
  const fs::path reportDir = fs::path(*out) / "report";
  times.start("report");
  analysis::AnalysisOptions reportOptions;  // intervals with the default 2,000 resamples
  reportOptions.threads = threads;
  analysis::writeReport({results::readResults(options.out)}, reportDir, reportOptions,
                        pictureDrawer(a, threads, quiet));
  times.stop(a.flag("no-pictures") ? "without pictures" : "with pictures");
  std::cout << "report in " << (reportDir / "report.html").string() << "\n";
  // This invocation's stage times (a resumed run's earlier invocations are not in them).
  const fs::path timesFile = fs::path(*out) / "stages.csv";
  database::writeFileAtomically(timesFile, times.csv());
  std::cout << times.table() << "stage times in " << timesFile.string() << "\n";
  return 0;
}

}  // namespace

void addRunCommands(CommandLine& cli) {
  constexpr const char* kHandHelp =
      "The hand: its name in DATA/hands (sdh, pg70, ...), its folder or its grasp description "
      "(default: the SDH, DATA/hands/sdh)";
  constexpr const char* kResumeHelp =
      "Continue a killed run: keep the trials already in the results, run the rest";
  CLI::App& run = cli.addCommand(
      nullptr, "run",
      "Run every grasp of every scene through the simulator; each finished trial is written at "
      "once (RESULTS/trials.csv), so --resume continues a killed run.",
      guarded(runRun));
  run.add_option("--db", kDatabaseOptionHelp)->required()->type_name("DIR|MANIFEST");
  run.add_option("--grasps", "Grasp files or folders (docs/grasp-format.md); repeatable")
      ->required()
      ->type_name("FILE|DIR")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  run.add_option("--out", "The result folder to write")->required()->type_name("RESULTS");
  addThreadsOption(run);
  addFlag(run, "--resume", kResumeHelp);
  run.add_option("--hand", kHandHelp)->type_name("NAME|DIR|GRASP.xml");
  addEngineOption(run);
  addScenesOption(run);
  run.add_option("--shard",
                 "Run only shard K of the work cut into --of N shards (K from 1 to N): whole "
                 "scenes in database order in N contiguous blocks balanced by grasp count, the "
                 "same for any --threads; RESULTS/shard.txt says which shard of which run it "
                 "is and whether it finished; `visgrab merge` joins the N folders "
                 "(docs/cluster.md)")
      ->type_name("K")
      ->check(integerAtLeast(1));
  run.add_option("--of", "The number of shards the work is cut into (with --shard)")
      ->type_name("N")
      ->check(integerAtLeast(1));
  addRepeatOptions(run);
  addProtocolOption(run);
  run.add_option("--dt",
                 "ODE's time step in s for every scene instead of the scene's own (default: the "
                 "scenes' engine properties, 0.005); recorded in run.csv's engine settings")
      ->type_name("SECONDS");
  addDataOption(run);
  addQuietFlag(run);

  CLI::App& benchmark = cli.addCommand(
      nullptr, "benchmark",
      "Run and analyze in one: generate the database (default ./database) if it is missing, make "
      "the baseline's grasps (DIR/grasps/baseline.csv) unless --grasps gives a method's, run "
      "them (DIR/results), write the report with its pictures (DIR/report/report.html); print "
      "each stage's wall and CPU time at the end (also in DIR/stages.csv).",
      guarded(runBenchmarkCommand));
  benchmark.add_option("--out", "The folder to write (grasps/, results/, report/)")
      ->required()
      ->type_name("DIR");
  benchmark
      .add_option("--grasps",
                  "A method's grasp files or folders (default: the baseline's); repeatable")
      ->type_name("FILE|DIR")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  benchmark.add_option("--db", "The database folder; generated there when it is missing")
      ->type_name("DIR")
      ->default_str("database");
  addThreadsOption(benchmark);
  addFlag(benchmark, "--resume", kResumeHelp);
  benchmark.add_option("--hand", kHandHelp)->type_name("NAME|DIR|GRASP.xml");
  addEngineOption(benchmark);
  addProtocolOption(benchmark);
  addScenesOption(benchmark);
  addDataOption(benchmark);
  addFlag(benchmark, "--no-pictures", "Leave the report's pictures out");
  addQuietFlag(benchmark);

  CLI::App& analyze = cli.addCommand(
      nullptr, "analyze",
      "The paper's five analyses of one or more result folders (methods side by side), every "
      "estimate with a scene-bootstrap confidence interval, overall success rates, each pair of "
      "methods compared on their shared scenes, robust rates of runs with repeats: CSV tables, "
      "report.md, report.html with SVG plots and pictures of the best, a typical and a failed "
      "grasp per method and condition (REPORT/images; --no-pictures leaves them out).",
      guarded(runAnalyze));
  analyze.add_option("RESULTS", "Result folders of `visgrab run`, one per method")
      ->required()
      ->expected(1, CLI::detail::expected_max_vector_size)
      ->allow_extra_args()
      ->type_name("");
  analyze.add_option("--out", "The report folder to write")->required()->type_name("REPORT");
  analyze
      .add_option("--ci-level",
                  "Confidence level of the intervals (scene bootstrap; docs/report.md, \"Error "
                  "bars\")")
      ->type_name("L")
      ->default_str("0.95");
  analyze
      .add_option("--bootstrap",
                  "Bootstrap resamples behind every interval and comparison, at least 100; 0: "
                  "none (the report without intervals, overall success rates and comparisons)")
      ->type_name("B")
      ->default_str("2000")
      ->check(integerAtLeast(0));
  analyze
      .add_option("--seed",
                  "Seed of the bootstrap and permutation streams (the same seed gives the same "
                  "intervals with any --threads)")
      ->type_name("S")
      ->default_str("20120601")
      ->check(integerAtLeast(0));
  addThreadsOption(analyze);
  addFlag(analyze, "--no-pictures", "Leave the report's pictures out");
  addFlag(analyze, "--allow-unfinished",
          "Analyze a run that has not finished (its folder holds unfinished.txt: stopped, killed "
          "or failed, or still running) from the trials it has; the report says so. Without it "
          "such a folder is refused");
  addDataOption(analyze)->description(
      "The project's scene data, whose protocols/ the pictures of a run made with another "
      "protocol than the lift replay with (default: $VISGRAB_DATA, else the installed "
      "share/visgrab/scenes, else the source tree's scenes/)");
  addQuietFlag(analyze);
}

}  // namespace visgrab::app
