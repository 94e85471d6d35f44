#include "db_commands.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>

#include "rw/common/diagnostic.hpp"
#include "rw/common/stop_signals.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/generator/generator.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

database::SceneFilter parseFilter(const Arguments& a) {
  std::vector<std::string> texts;
  if (const auto f = a.option("scenes")) texts.push_back(*f);
  try {
    return database::SceneFilter::parse(texts);
  } catch (const database::FilterError& e) {
    throw UsageError(std::string("--scenes: ") + e.what());
  }
}

std::string duration(double seconds) {
  const int s = static_cast<int>(seconds + 0.5);
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%dh%02dm", s / 3600, (s / 60) % 60);
  } else {
    std::snprintf(text, sizeof text, "%dm%02ds", s / 60, s % 60);
  }
  return text;
}

void printProgress(const generator::GenerationProgress& p) {
  const double rate = p.elapsed > 0.0 ? p.done / p.elapsed : 0.0;
  const double left = rate > 0.0 ? (p.total - p.done) / rate : 0.0;
  const int width = 30;
  const int filled = p.total > 0 ? width * p.done / p.total : width;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(static_cast<std::size_t>(width), '.');
  std::fprintf(stderr, "\r[%s] %d/%d scenes  %.2f scenes/s  %s left  %-45s", bar.c_str(), p.done,
               p.total, rate, duration(left).c_str(), p.lastId.c_str());
  if (p.done == p.total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

int runGenerate(const std::vector<std::string>& args) {
  const Arguments a(args, {"quiet"});
  a.rejectUnknown({"out", "scenes", "threads", "seed", "data", "quiet"});
  a.requirePositionals(0, "no positional arguments");
  const auto out = a.option("out");
  if (!out) throw UsageError("--out DIR is required");
  const database::SceneFilter filter = parseFilter(a);
  std::vector<database::SceneConditions> scenes;
  for (const auto& s : database::enumerateScenes()) {
    if (filter.matches(database::sceneIdOf(s), &s)) scenes.push_back(s);
  }
  if (scenes.empty()) throw UsageError("--scenes selects no scene");
  generator::GeneratorOptions options;
  options.out = *out;
  const fs::path data = dataFolder(a);
  options.objectSpec = data / "objects" / "objects.xml";
  options.handFolder = data / "hands" / "sdh";
  options.materials = data / "materials.xml";
  options.threads = threadsOption(a);
  options.seed = static_cast<std::uint64_t>(integerOption(a, "seed", 1, 0));
  std::cerr << "visgrab db generate: " << scenes.size() << " scenes into " << *out << " with "
            << options.threads << " thread(s), seed " << options.seed << "\n";
  const bool quiet = a.flag("quiet");
  // SIGINT/SIGTERM: the scenes being made are finished and indexed, then it stops (exit 130/143);
  // running it again continues.
  rw::common::catchStopSignals();
  options.stop = &rw::common::stopSignalFlag();
  generator::GenerationReport report;
  try {
    report = generator::generateDatabase(
        scenes, options,
        quiet ? std::function<void(const generator::GenerationProgress&)>{} : printProgress);
  } catch (const rw::common::StopRequested& e) {
    std::cerr << "\nvisgrab db generate: " << rw::common::signalName(rw::common::stopSignal())
              << ": " << e.what() << "\n";
    return rw::common::stopExitCode(rw::common::stopSignal());
  }
  std::cout << report.generated << " scenes generated, " << report.skipped << " already complete, "
            << report.failures.size() << " failed\n";
  for (const auto& f : report.failures) std::cerr << "failed: " << f << "\n";
  return report.failures.empty() ? 0 : 1;
}

database::Database openDatabase(const Arguments& a) {
  const auto db = a.option("db");
  if (!db) throw UsageError("--db DIR (or an original VisGraB manifest) is required");
  return database::Database::openAny(*db);
}

int runList(const std::vector<std::string>& args) {
  const Arguments a(args, {});
  a.rejectUnknown({"db", "scenes"});
  a.requirePositionals(0, "no positional arguments");
  const database::SceneFilter filter = parseFilter(a);
  const database::Database db = openDatabase(a);
  const auto scenes = db.filter(filter);
  for (const auto* s : scenes) std::cout << database::Database::summaryLine(*s) << "\n";
  std::cerr << scenes.size() << " of " << db.list().size() << " scenes\n";
  return 0;
}

int runShow(const std::vector<std::string>& args) {
  const Arguments a(args, {});
  a.rejectUnknown({"db"});
  a.requirePositionals(1, "ID (a scene id, see visgrab db list)");
  const database::Database db = openDatabase(a);
  std::cout << database::Database::details(db.scene(a.positionals()[0]));
  return 0;
}

}  // namespace

std::vector<Command> databaseCommands() {
  return {
      {"db", "generate",
       "--out DIR [--scenes FILTER] [--threads N] [--seed S] [--data SCENES_DIR] [--quiet]",
       "Generate the scene database (or the scenes FILTER selects): objects, settled scenes, "
       "rendered stereo pairs, calibration, index. Resumes an interrupted run.",
       guarded(runGenerate)},
      {"db", "list", "--db DIR|MANIFEST [--scenes FILTER]",
       "List the scenes of a generated database or an original VisGraB manifest.",
       guarded(runList)},
      {"db", "show", "--db DIR|MANIFEST ID",
       "Show one scene: conditions, files, calibration and ground-truth poses.", guarded(runShow)},
  };
}

}  // namespace visgrab::app
