#include "run_commands.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <thread>

#include "baseline_commands.hpp"
#include "rw/common/diagnostic.hpp"
#include "rw/common/stop_signals.hpp"
#include "visgrab/analysis/report.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/view/report_pictures.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

std::string clock(double seconds) {
  const int s = static_cast<int>(seconds + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%dm%02ds", s / 60, s % 60);
  return text;
}

void printProgress(const runner::RunProgress& p) {
  const double rate = p.elapsed > 0.0 ? p.trialsDone / p.elapsed : 0.0;
  const double left = rate > 0.0 ? (p.trialsTotal - p.trialsDone) / rate : 0.0;
  const int width = 30;
  const int filled = p.trialsTotal > 0 ? width * p.trialsDone / p.trialsTotal : width;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(static_cast<std::size_t>(width), '.');
  std::fprintf(stderr, "\r[%s] scenes %d/%d  trials %d/%d  %.1f trials/s  %s left   ", bar.c_str(),
               p.scenesDone, p.scenesTotal, p.trialsDone, p.trialsTotal, rate, clock(left).c_str());
  if (p.scenesDone == p.scenesTotal && p.trialsDone == p.trialsTotal) std::fputc('\n', stderr);
  std::fflush(stderr);
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
    return runner::runBenchmark(
        options, quiet ? std::function<void(const runner::RunProgress&)>{} : printProgress);
  } catch (const rw::common::StopRequested& e) {
    stoppedBySignal(e, command);
    return std::nullopt;
  }
}

int runRun(const std::vector<std::string>& args) {
  Arguments a(args, {"resume", "quiet"});
  a.rejectUnknown({"db", "grasps", "out", "threads", "resume", "hand", "scenes", "data", "quiet"});
  a.requirePositionals(0, "no positional arguments (grasp files go after --grasps)");
  runner::RunOptions options;
  const auto db = a.option("db");
  const auto grasps = a.values("grasps");
  const auto out = a.option("out");
  if (!db) throw UsageError("--db DIR (a generated database or an original manifest) is required");
  if (grasps.empty()) throw UsageError("--grasps FILE|DIR is required");
  if (!out) throw UsageError("--out RESULTS is required");
  options.database = *db;
  options.grasps.assign(grasps.begin(), grasps.end());
  options.out = *out;
  options.hand = a.option("hand").value_or((dataFolder(a) / "hands/sdh/sdh.grasp.xml").string());
  options.scenes = a.option("scenes").value_or("");
  options.threads = threadsOption(a);
  options.resume = a.flag("resume");
  const bool quiet = a.flag("quiet");
  const auto done = runStoppable(options, quiet, "run");
  if (!done) return rw::common::stopExitCode(rw::common::stopSignal());
  const runner::RunSummary& summary = *done;
  for (const auto& d : summary.rejected) std::cerr << d.format() << "\n";
  std::cout << summary.trials << " trials run, " << summary.resumed << " resumed, "
            << summary.rejected.size() << " grasps rejected; " << summary.scenes << " scenes, "
            << summary.methods << " methods\n";
  for (const auto& [outcome, n] : summary.outcomes)
    std::cout << "  " << outcome << " " << n << "\n";
  std::cout << "results in " << options.out.string() << "\n";
  return 0;
}

// The report's pictures (a few trials per method and condition, simulated again and drawn),
// unless --no-pictures.
analysis::ShowcaseDrawer pictureDrawer(const Arguments& a, int threads, bool quiet) {
  if (a.flag("no-pictures")) return {};
  view::ReportPictureOptions options;
  options.threads = threads;
  if (!quiet) {
    options.progress = [](int done, int total) {
      std::fprintf(stderr, "\rreport pictures: %d/%d   ", done, total);
      if (done == total) std::fputc('\n', stderr);
      std::fflush(stderr);
    };
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

int runAnalyze(const std::vector<std::string>& args) {
  Arguments a(args, {"no-pictures", "quiet"});
  a.rejectUnknown({"out", "no-pictures", "threads", "quiet"});
  const auto out = a.option("out");
  if (!out) throw UsageError("--out REPORT is required");
  if (a.positionals().empty()) throw UsageError("at least one RESULTS folder is required");
  std::vector<results::RunResults> runs;
  for (const auto& dir : a.positionals()) {
    std::vector<rw::common::Diagnostic> warnings;
    runs.push_back(results::readResults(dir, &warnings));
    for (const auto& w : warnings) std::cerr << w.format() << "\n";
  }
  analysis::writeReport(runs, *out, {}, pictureDrawer(a, threadsOption(a), a.flag("quiet")));
  std::cout << "report in " << *out << " (report.html, report.md, CSV tables)\n";
  return 0;
}

void printGenerationProgress(const generator::GenerationProgress& p) {
  std::fprintf(stderr, "\rgenerating the database: %d/%d scenes  %s  ", p.done, p.total,
               p.lastId.c_str());
  if (p.done == p.total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

// Generates the database at `dir` (the scenes `filter` selects) unless its index exists.
void ensureDatabase(const fs::path& dir, const std::string& filter, int threads,
                    const fs::path& data, bool quiet) {
  if (fs::exists(dir / "index.xml")) return;
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
  rw::common::catchStopSignals();
  options.stop = &rw::common::stopSignalFlag();
  const auto report = generator::generateDatabase(
      scenes, options,
      quiet ? std::function<void(const generator::GenerationProgress&)>{}
            : printGenerationProgress);
  for (const auto& f : report.failures) std::cerr << "failed: " << f << "\n";
  if (!report.failures.empty()) throw std::runtime_error("the database could not be generated");
}

int runBenchmarkCommand(const std::vector<std::string>& args) {
  Arguments a(args, {"resume", "quiet", "no-pictures"});
  a.rejectUnknown({"db", "grasps", "out", "threads", "resume", "hand", "scenes", "data", "quiet",
                   "no-pictures"});
  a.requirePositionals(0, "no positional arguments (grasp files go after --grasps)");
  const auto out = a.option("out");
  if (!out) throw UsageError("--out DIR is required");
  const fs::path data = dataFolder(a);
  const fs::path db = a.option("db").value_or("database");
  const int threads = threadsOption(a);
  const bool quiet = a.flag("quiet");
  const std::string scenes = a.option("scenes").value_or("");
  try {
    ensureDatabase(db, scenes, threads, data, quiet);
  } catch (const rw::common::StopRequested& e) {
    return stoppedBySignal(e, "benchmark");
  }
  std::vector<fs::path> graspSources;
  for (const auto& g : a.values("grasps")) graspSources.emplace_back(g);
  if (graspSources.empty()) {
    // No method given: the baseline's grasps, made once (an existing file is complete: it is
    // written atomically) and reused by --resume.
    const fs::path grasps = fs::path(*out) / "grasps" / "baseline.csv";
    if (!fs::exists(grasps) || !a.flag("resume")) {
      if (!quiet)
        std::cerr << "visgrab benchmark: baseline grasps into " << grasps.string() << "\n";
      writeBaselineGrasps(db, scenes, grasps, threads, quiet);
    }
    graspSources = {grasps};
  }
  runner::RunOptions options;
  options.database = db;
  options.grasps = graspSources;
  options.out = fs::path(*out) / "results";
  options.hand = a.option("hand").value_or((data / "hands/sdh/sdh.grasp.xml").string());
  options.scenes = scenes;
  options.threads = threads;
  options.resume = a.flag("resume");
  const auto done = runStoppable(options, quiet, "benchmark");
  if (!done) return rw::common::stopExitCode(rw::common::stopSignal());
  const runner::RunSummary& summary = *done;
  for (const auto& d : summary.rejected) std::cerr << d.format() << "\n";
  std::cout << summary.trials << " trials run, " << summary.resumed << " resumed, "
            << summary.rejected.size() << " grasps rejected\n";
  const fs::path reportDir = fs::path(*out) / "report";
  analysis::writeReport({results::readResults(options.out)}, reportDir, {},
                        pictureDrawer(a, threads, quiet));
  std::cout << "report in " << (reportDir / "report.html").string() << "\n";
  return 0;
}

}  // namespace

std::vector<Command> runCommands() {
  return {
      {"run", "",
       "--db DIR|MANIFEST --grasps FILE|DIR [--grasps ...] --out RESULTS [--threads N] [--resume] "
       "[--hand DIR|GRASP.xml] [--scenes FILTER] [--quiet]",
       "Run every grasp of every scene through the simulator; each finished trial is written at "
       "once (RESULTS/trials.csv), so --resume continues a killed run.",
       guarded(runRun)},
      {"benchmark", "",
       "--out DIR [--grasps FILE|DIR] [--db DIR] [--threads N] [--resume] [--hand DIR|GRASP.xml] "
       "[--scenes FILTER] [--no-pictures] [--quiet]",
       "Run and analyze in one: generate the database (default ./database) if it is missing, make "
       "the baseline's grasps (DIR/grasps/baseline.csv) unless --grasps gives a method's, run "
       "them (DIR/results), write the report with its pictures (DIR/report/report.html).",
       guarded(runBenchmarkCommand)},
      {"analyze", "", "RESULTS... --out REPORT [--threads N] [--no-pictures] [--quiet]",
       "The paper's five analyses of one or more result folders (methods side by side): CSV "
       "tables, report.md, report.html with SVG plots and pictures of the best, a typical and a "
       "failed grasp per method and condition (REPORT/images; --no-pictures leaves them out).",
       guarded(runAnalyze)},
  };
}

}  // namespace visgrab::app
