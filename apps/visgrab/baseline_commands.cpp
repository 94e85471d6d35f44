#include "baseline_commands.hpp"

#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <optional>

#include "progress_reporter.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/request/grasp_request.hpp"
#include "visgrab/taskio/grasp_list.hpp"
#include "visgrab/vision/baseline.hpp"

namespace visgrab::app {
namespace {

namespace fs = std::filesystem;

std::vector<const database::SceneEntry*> selectScenes(const database::Database& db,
                                                      const std::string& filter) {
  if (filter.empty()) return db.filter(database::SceneFilter());
  try {
    return db.filter(database::SceneFilter::parse(filter));
  } catch (const database::FilterError& e) {
    throw UsageError(std::string("--scenes: ") + e.what());
  }
}

// Runs the baseline and writes the grasp list; the shared part of `baseline` and `benchmark`.
int runAndWrite(const fs::path& dbPath, const std::string& filter, const fs::path& out,
                const vision::BaselineOptions& options, bool quiet,
                const std::string& preshape = {}) {
  const auto db = database::Database::openAny(dbPath);
  const auto scenes = selectScenes(db, filter);
  if (scenes.empty()) throw UsageError("--scenes selects no scene of " + dbPath.string());
  std::optional<ProgressReporter> reporter;
  if (!quiet) reporter.emplace("baseline", "scenes");
  const auto results =
      vision::baselineGrasps(db, scenes, options, [&](const vision::BaselineProgress& p) {
        if (reporter) reporter->update(p.done, p.total, p.lastId);
      });
  reporter.reset();
  std::vector<grasp::GraspRequest> all;
  std::map<std::string, int> perType;
  int failed = 0;
  for (const auto& r : results) {
    if (!r.error.empty()) {
      ++failed;
      std::cerr << "baseline: " << r.sceneId << ": no grasps: " << r.error << "\n";
    }
    for (const auto& g : r.grasps) {
      if (preshape.empty()) {
        ++perType[g.method];
        all.push_back(g);
      } else if (auto p = grasp::preshapeFromContacts(g, preshape)) {
        // Two-contact grasps only: the same plan for every two-finger hand.
        ++perType[p->method];
        all.push_back(std::move(*p));
      }
    }
  }
  if (out.has_parent_path()) fs::create_directories(out.parent_path());
  database::writeFileAtomically(out, taskio::formatGraspList(all));
  if (!quiet) {
    std::cerr << "baseline: " << all.size() << " grasps for " << scenes.size() << " scenes (";
    bool first = true;
    for (const auto& [type, n] : perType) {
      std::cerr << (first ? "" : ", ") << type << " " << n;
      first = false;
    }
    std::cerr << ")" << (failed ? ", " + std::to_string(failed) + " scenes failed" : "") << "\n";
  }
  return static_cast<int>(all.size());
}

int runBaseline(const Arguments& a) {
  const auto db = a.option("db");
  const auto out = a.option("out");
  vision::BaselineOptions options;
  options.threads = threadsOption(a);
  options.grasps.perType = integerOption(a, "per-type", options.grasps.perType, 1);
  const std::string filter = scenesFilter(a);
  if (const auto debug = a.option("debug")) {
    // Pictures of what the baseline saw, one per scene (sequential: meant for a few scenes).
    const auto database = database::Database::openAny(*db);
    for (const auto* scene : selectScenes(database, filter)) {
      const auto seg = vision::analyzeScene(database, *scene, options);
      const auto grasps = vision::generateGrasps(seg, options.grasps);
      std::string name = scene->id;
      for (char& c : name) c = c == '/' ? '_' : c;
      const fs::path file = fs::path(*debug) / (name + ".png");
      fs::create_directories(*debug);
      database::writeImageAtomically(
          file, vision::drawSegmentation(database.leftImage(scene->id), seg, grasps,
                                         database.calibration(scene->id)));
      std::cerr << file.string() << ": " << seg.clusters.size() << " objects, "
                << seg.patches.size() << " patches, " << grasps.size() << " grasps\n";
    }
  }
  const std::string preshape = a.option("preshape").value_or("");
  if (a.option("preshape") && preshape.empty()) throw UsageError("--preshape: give a name");
  const int n = runAndWrite(*db, filter, *out, options, a.flag("quiet"), preshape);
  std::cout << n << " grasps in " << *out << "\n";
  return 0;
}

}  // namespace

int writeBaselineGrasps(const fs::path& db, const std::string& filter, const fs::path& out,
                        int threads, bool quiet) {
  vision::BaselineOptions options;
  options.threads = threads;
  return runAndWrite(db, filter, out, options, quiet);
}

void addBaselineCommands(CommandLine& cli) {
  CLI::App& baseline = cli.addCommand(
      nullptr, "baseline",
      "The paper's baseline method: stereo point cloud, table plane, object clusters, surface "
      "patches and the grasp types s2EGA1, s2EGA3, s3EGA1 as contact grasps in one grasp list.",
      guarded(runBaseline));
  baseline.add_option("--db", kDatabaseOptionHelp)->required()->type_name("DIR|MANIFEST");
  baseline.add_option("--out", "The grasp list file to write (docs/grasp-format.md)")
      ->required()
      ->type_name("GRASPS");
  addScenesOption(baseline);
  baseline.add_option("--per-type", "At most N grasps of each type per scene")
      ->type_name("N")
      ->default_str(std::to_string(vision::BaselineOptions().grasps.perType))
      ->check(integerAtLeast(1));
  addThreadsOption(baseline);
  baseline
      .add_option("--preshape",
                  "Write the two-contact grasps as pre-shape grasps with this pre-shape (TCP "
                  "between the contacts, z along the approach, x across: one plan for any "
                  "two-finger hand)")
      ->type_name("NAME");
  baseline
      .add_option("--debug",
                  "Write a picture per scene of what the baseline saw into DIR (sequential: "
                  "meant for a few scenes)")
      ->type_name("DIR");
  addQuietFlag(baseline);
}

}  // namespace visgrab::app
