#include "db_commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "json_writer.hpp"
#include "progress_reporter.hpp"
#include "rw/common/diagnostic.hpp"
#include "rw/common/number_text.hpp"
#include "rw/common/stop_signals.hpp"
#include "rw/math/rpy.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/database/stereo_accuracy.hpp"
#include "visgrab/generator/acronym_database.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/generator/scene_model.hpp"
#include "visgrab/importers/acronym.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

// --scenes for a database of `catalog`'s objects (names, ids and pair letters are its own).
database::SceneFilter parseFilter(const Arguments& a, const database::ObjectCatalog& catalog) {
  try {
    return database::SceneFilter::parse(a.values("scenes"), catalog);
  } catch (const database::FilterError& e) {
    throw UsageError(std::string("--scenes: ") + e.what());
  }
}

int runGenerate(const Arguments& a) {
  const auto out = a.option("out");
  generator::GeneratorOptions options;
  const fs::path data = dataFolder(a);
  options.objectSpec = data / "objects" / "objects.xml";
  if (const auto spec = a.option("objects")) {
    // Your own objects: their scenes, the tables from the spec or else the benchmark's.
    options.catalog = generator::objectCatalog(objects::loadObjectSpecs(*spec));
    options.tableSpec = options.objectSpec;
    options.objectSpec = *spec;
  }
  const database::SceneFilter filter = parseFilter(a, options.catalog);
  std::vector<database::SceneConditions> scenes;
  for (const auto& s : database::enumerateScenes(options.catalog)) {
    if (filter.matches(database::sceneIdOf(s, options.catalog), &s)) scenes.push_back(s);
  }
  if (scenes.empty()) throw UsageError("--scenes selects no scene");
  options.out = *out;
  options.handFolder = data / "hands" / "sdh";
  options.materials = data / "materials.xml";
  options.threads = threadsOption(a);
  options.seed = static_cast<std::uint64_t>(integerOption(a, "seed", 1, 0));
  try {
    options.camera =
        generator::findCameraProfile(a.option("camera").value_or("realistic"), data / "cameras");
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--camera: ") + e.what());
  }
  std::cerr << "visgrab db generate: " << scenes.size() << " scenes into " << *out << " with "
            << options.threads << " thread(s), seed " << options.seed << ", camera "
            << options.camera.name << "\n";
  std::optional<ProgressReporter> reporter;
  if (!a.flag("quiet")) reporter.emplace("db generate", "scenes");
  // SIGINT/SIGTERM: the scenes being made are finished and indexed, then it stops (exit 130/143);
  // running it again continues.
  rw::common::catchStopSignals();
  options.stop = &rw::common::stopSignalFlag();
  generator::GenerationReport report;
  try {
    report =
        generator::generateDatabase(scenes, options, [&](const generator::GenerationProgress& p) {
          if (reporter) reporter->update(p.done, p.total, p.lastId);
        });
  } catch (const rw::common::StopRequested& e) {
    reporter.reset();
    std::cerr << "\nvisgrab db generate: " << rw::common::signalName(rw::common::stopSignal())
              << ": " << e.what() << "\n";
    return rw::common::stopExitCode(rw::common::stopSignal());
  }
  reporter.reset();
  std::cout << report.generated << " scenes generated, " << report.skipped << " already complete, "
            << report.failures.size() << " failed\n";
  for (const auto& f : report.failures) std::cerr << "failed: " << f << "\n";
  return report.failures.empty() ? 0 : 1;
}

int runFromAcronym(const Arguments& a) {
  const std::vector<std::string> files = a.positionals();
  if (files.empty()) throw UsageError("expected one or more ACRONYM files (FILE.h5)");
  const fs::path meshRoot = a.option("mesh-root").value();
  std::vector<generator::AcronymObjectSource> sources;
  for (const std::string& file : files) {
    const importers::AcronymObject object = importers::readAcronymObject(file);
    generator::AcronymObjectSource s;
    s.file = fs::path(file).filename().string();
    s.mesh = meshRoot / object.file;
    std::error_code ec;
    if (!fs::is_regular_file(s.mesh, ec)) {
      throw std::runtime_error(file + ": its mesh object/file = \"" + object.file +
                               "\" is not under --mesh-root " + meshRoot.string() + " (no file " +
                               s.mesh.string() + ")");
    }
    s.scale = object.scale;
    s.mass = object.mass;
    s.friction = object.friction;
    s.com = object.com;
    s.inertia = object.inertia;
    sources.push_back(std::move(s));
  }
  const fs::path data = dataFolder(a);
  generator::AcronymDatabaseOptions options;
  options.handFolder = data / "hands" / "sdh";
  options.materials = data / "materials.xml";
  options.maxPieces = integerOption(a, "max-pieces", 64, 1);
  const std::string collision = a.option("collision").value_or("mesh");
  if (collision == "pieces") {
    options.collision = generator::AcronymCollision::kPieces;
  } else if (collision != "mesh") {
    throw UsageError("--collision: \"" + collision + "\" is neither mesh nor pieces");
  }
  std::optional<ProgressReporter> reporter;
  if (!a.flag("quiet")) reporter.emplace("db from-acronym", "scenes");
  long done = 0;
  options.onScene = [&](const std::string& id) {
    if (reporter) reporter->update(++done, static_cast<long>(sources.size()), id);
  };
  const fs::path out = a.option("out").value();
  const generator::AcronymDatabaseReport report =
      generator::generateAcronymDatabase(sources, out, options);
  reporter.reset();
  for (const std::string& note : report.notes) std::cerr << "note: " << note << "\n";
  std::cout << report.scenes.size() << " scenes in " << out.string() << ":\n";
  for (std::size_t i = 0; i < report.scenes.size(); ++i) {
    std::cout << "  " << report.scenes[i] << "  (" << sources[i].file << ")\n";
  }
  return 0;
}

database::Database openDatabase(const Arguments& a) {
  return database::Database::openAny(a.option("db").value());
}

// A scene's conditions as JSON (null when unknown).
void writeConditionsJson(JsonWriter& j, const database::SceneEntry& s,
                         const database::ObjectCatalog& catalog) {
  j.key("conditions");
  if (!s.conditions) {
    j.null();
    return;
  }
  const auto& c = *s.conditions;
  j.beginObject().key("texture").value(std::string(database::toString(c.texture)));
  j.key("kind").value(std::string(database::toString(c.kind)));
  j.key("arrangement").value(std::string(database::toString(c.arrangement())));
  j.key("objects").beginArray();
  for (const int o : c.objects) {
    j.beginObject().key("id").value(o);
    j.key("name").value(std::string(catalog.name(o))).endObject();
  }
  j.endArray().key("pose").value(c.pose);
  j.key("description").value(database::describe(c, catalog)).endObject();
}

// One scene of `db list --json` (and the start of `db show --json`'s).
void writeSceneJson(JsonWriter& j, const database::SceneEntry& s,
                    const database::ObjectCatalog& catalog) {
  j.key("id").value(s.id).key("original_id").value(s.originalId);
  writeConditionsJson(j, s, catalog);
}

int runList(const Arguments& a) {
  const database::Database db = openDatabase(a);
  const database::SceneFilter filter = parseFilter(a, db.catalog());
  const auto scenes = db.filter(filter);
  if (a.flag("json")) {
    JsonWriter j(std::cout);
    j.beginObject().key("schema").value("visgrab/db-list/1");
    j.key("database").value(db.root().string());
    j.key("total").value(db.list().size()).key("scenes").beginArray();
    for (const auto* s : scenes) {
      j.beginObject();
      writeSceneJson(j, *s, db.catalog());
      j.endObject();
    }
    j.endArray().endObject().finish();
  } else {
    for (const auto* s : scenes) {
      std::cout << database::Database::summaryLine(*s, db.catalog()) << "\n";
    }
  }
  std::cerr << scenes.size() << " of " << db.list().size() << " scenes\n";
  return 0;
}

// A file of `db show --json`: its path and whether it exists (null when the scene has none).
void writeFileJson(JsonWriter& j, const char* name, const fs::path& file) {
  j.key(name);
  if (file.empty()) {
    j.null();
    return;
  }
  std::error_code ec;
  j.beginObject().key("path").value(file.string());
  j.key("exists").value(fs::exists(file, ec)).endObject();
}

void printShowJson(const database::SceneEntry& s, const database::ObjectCatalog& catalog) {
  JsonWriter j(std::cout);
  j.beginObject().key("schema").value("visgrab/db-show/2");
  writeSceneJson(j, s, catalog);
  j.key("files").beginObject();
  writeFileJson(j, "left_image", s.leftImage);
  writeFileJson(j, "right_image", s.rightImage);
  writeFileJson(j, "calibration", s.calibration);
  writeFileJson(j, "workcell", s.workcell);
  writeFileJson(j, "dynamic_workcell", s.dynamicWorkcell);
  writeFileJson(j, "raw_left_image", s.rawLeftImage);
  writeFileJson(j, "raw_right_image", s.rawRightImage);
  writeFileJson(j, "disparity", s.disparity);
  writeFileJson(j, "point_cloud", s.pointCloud);
  writeFileJson(j, "depth", s.depth);
  writeFileJson(j, "mask", s.mask);
  writeFileJson(j, "poses", s.poses);
  writeFileJson(j, "collision_mesh", s.collision);
  j.endObject().key("ground_truth").beginArray();
  for (const database::ObjectPose& o : s.groundTruth) {
    const Eigen::Vector3d p = o.X_WO.translation();
    const Eigen::Quaterniond q(o.X_WO.linear());
    const Eigen::Vector3d rpy = rw::math::rotationToRpy(o.X_WO.linear());
    j.beginObject().key("object").value(o.object);
    j.key("name").value(std::string(catalog.name(o.object)));
    j.key("position").numbers({p.x(), p.y(), p.z()});
    j.key("quaternion").numbers({q.w(), q.x(), q.y(), q.z()});
    j.key("rpy").numbers({rpy.x(), rpy.y(), rpy.z()}).endObject();
  }
  j.endArray().endObject().finish();
}

int runShow(const Arguments& a) {
  const database::Database db = openDatabase(a);
  const database::SceneEntry& scene = db.scene(a.positionals().at(0));
  if (a.flag("json")) {
    printShowJson(scene, db.catalog());
  } else {
    std::cout << database::Database::details(scene, db.catalog());
  }
  return 0;
}

// How much of the objects the database's disparity maps recover within 5 mm, per scene and in
// all (docs/database-format.md, "Realism").
int runStereoAccuracy(const Arguments& a) {
  const database::Database db = openDatabase(a);
  const database::SceneFilter filter = parseFilter(a, db.catalog());
  constexpr double kTolerance = 0.005;
  int scenes = 0;
  long objects = 0, found = 0, within = 0;
  double sum = 0.0, lo = 1.0, hi = 0.0;
  std::cout << "scene  within 5 mm / object pixels  (share)  of the pixels with a disparity\n";
  for (const database::SceneEntry* s : db.filter(filter)) {
    if (s->disparity.empty() || s->depth.empty() || s->mask.empty()) {
      std::cout << s->id << ": no disparity, depth or mask (index format 1?), skipped\n";
      continue;
    }
    const database::StereoAccuracy r = database::stereoAccuracy(db, s->id, kTolerance);
    std::cout << s->id << ": " << r.within << " / " << r.objectPixels << "  ("
              << rw::common::shortestText(std::round(1000.0 * r.shareOfObjects()) / 10.0) << " %)  "
              << rw::common::shortestText(std::round(1000.0 * r.shareOfFound()) / 10.0) << " %\n";
    ++scenes;
    objects += r.objectPixels;
    found += r.withDisparity;
    within += r.within;
    sum += r.shareOfObjects();
    lo = std::min(lo, r.shareOfObjects());
    hi = std::max(hi, r.shareOfObjects());
  }
  if (scenes == 0) throw std::runtime_error("no scene of the selection has a disparity map");
  const auto percent = [](double x) {
    return rw::common::shortestText(std::round(1000.0 * x) / 10.0) + " %";
  };
  std::cout << scenes << " scenes: mean " << percent(sum / scenes)
            << " of the object pixels within "
            << "5 mm (per scene " << percent(lo) << " - " << percent(hi) << "; pooled "
            << percent(static_cast<double>(within) / std::max(1L, objects)) << "), "
            << percent(static_cast<double>(within) / std::max(1L, found))
            << " of those with a disparity\n";
  return 0;
}

}  // namespace

void addDatabaseCommands(CommandLine& cli) {
  CLI::App& db = cli.addGroup("db", "The scene database: generate it, list and show its scenes.");
  CLI::App& generate = cli.addCommand(
      &db, "generate",
      "Generate the scene database (or the scenes --scenes selects): objects, settled scenes, "
      "rendered stereo pairs, calibration, index. Resumes an interrupted run.",
      guarded(runGenerate));
  generate.add_option("--out", "The database folder to write (or complete)")
      ->required()
      ->type_name("DIR");
  addScenesOption(generate);
  addThreadsOption(generate);
  generate
      .add_option("--objects",
                  "Your own object spec (meshes, pairs; docs/database-format.md, \"Your own "
                  "objects\"): a database of its objects and pairs instead of the benchmark's")
      ->type_name("SPEC");
  generate.add_option("--seed", "Seed of the scenes' random placements")
      ->type_name("S")
      ->default_str("1")
      ->check(integerAtLeast(0));
  generate
      .add_option("--camera",
                  "Camera profile: a name from the data folder's cameras/ (ideal, realistic) or "
                  "a profile file")
      ->type_name("NAME|FILE")
      ->default_str("realistic");
  addDataOption(generate);
  addQuietFlag(generate);

  CLI::App& fromAcronym = cli.addCommand(
      &db, "from-acronym",
      "A database of one scene per ACRONYM grasp file: the object floating where its mesh frame "
      "says (no table), its scale, mass, centre of mass, inertia and friction from the file, its "
      "collision geometry the mesh itself (or its convex decomposition: --collision pieces); no "
      "images (docs/database-format.md, \"Scenes "
      "from objects alone\"). Import the file's grasps with `visgrab import acronym`.",
      guarded(runFromAcronym));
  fromAcronym.add_option("FILES", "ACRONYM grasp files (.h5), one scene each, in this order")
      ->required()
      ->expected(1, CLI::detail::expected_max_vector_size)
      ->allow_extra_args()
      ->type_name("FILE.h5...");
  fromAcronym
      .add_option("--mesh-root",
                  "The folder the files' object/file paths are relative to (ACRONYM's data "
                  "folder, which holds meshes/)")
      ->required()
      ->type_name("DIR");
  fromAcronym.add_option("--out", "The database folder to write (or complete)")
      ->required()
      ->type_name("DIR");
  fromAcronym
      .add_option("--collision",
                  "The objects' collision geometry: mesh (the mesh itself, non-convex) or pieces "
                  "(its convex decomposition)")
      ->type_name("mesh|pieces")
      ->default_str("mesh");
  fromAcronym
      .add_option("--max-pieces",
                  "With --collision pieces: the convex decomposition's budget of pieces per "
                  "object")
      ->type_name("N")
      ->default_str("64")
      ->check(integerAtLeast(1));
  addDataOption(fromAcronym);
  addQuietFlag(fromAcronym);

  CLI::App& list = cli.addCommand(
      &db, "list", "List the scenes of a generated database or an original VisGraB manifest.",
      guarded(runList));
  list.add_option("--db", kDatabaseOptionHelp)->required()->type_name("DIR|MANIFEST");
  addScenesOption(list);
  addFlag(list, "--json", "Print JSON instead (docs/schemas/db-list.schema.json)");

  CLI::App& show = cli.addCommand(
      &db, "show", "Show one scene: conditions, files, calibration and ground-truth poses.",
      guarded(runShow));
  show.add_option("ID", "A scene id (see visgrab db list)")->required()->type_name("");
  show.add_option("--db", kDatabaseOptionHelp)->required()->type_name("DIR|MANIFEST");
  addFlag(show, "--json",
          "Print JSON instead (docs/schemas/db-show.schema.json; poses in m and rad)");

  CLI::App& accuracy = cli.addCommand(
      &db, "stereo-accuracy",
      "How much of the objects each scene's disparity map (disparity.png) recovers: the share of "
      "the object pixels (mask.png) whose depth from the disparity lies within 5 mm of the "
      "ground truth (depth.png).",
      guarded(runStereoAccuracy));
  accuracy.add_option("--db", "A generated database folder (index format 2)")
      ->required()
      ->type_name("DIR");
  addScenesOption(accuracy);
}

}  // namespace visgrab::app
