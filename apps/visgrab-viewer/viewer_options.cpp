#include "viewer_options.hpp"

#include <charconv>
#include <cstdlib>

#include "cli_common/cli_errors.hpp"
#include "cli_common/data_folder.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/run_protocol.hpp"

namespace visgrab::viewer {

namespace {

namespace fs = std::filesystem;

constexpr int kMinViewSide = 16;
constexpr int kMaxViewSide = 8192;

// "WxH" (or "WXH") into width and height; an error message, empty when it is fine.
std::string parseSize(const std::string& text, ViewerOptions& options) {
  const std::size_t x = text.find_first_of("xX");
  int w = 0;
  int h = 0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  const bool ok = x != std::string::npos && std::from_chars(begin, begin + x, w).ptr == begin + x &&
                  std::from_chars(begin + x + 1, end, h).ptr == end && x > 0 &&
                  x + 1 < text.size() && w >= kMinViewSide && w <= kMaxViewSide &&
                  h >= kMinViewSide && h <= kMaxViewSide;
  if (!ok) {
    return "needs WIDTHxHEIGHT in pixels, each " + std::to_string(kMinViewSide) + ".." +
           std::to_string(kMaxViewSide) + " (e.g. 1024x768), got '" + text + "'";
  }
  options.width = w;
  options.height = h;
  return {};
}

// The project's scene data folder: $VISGRAB_DATA, else the installed share/visgrab/scenes next
// to the program, else the source tree's scenes/ folder.
fs::path dataFolder() {
  if (const char* env = std::getenv("VISGRAB_DATA"); env != nullptr && *env != '\0') return env;
  return visgrab::cli::defaultDataFolder(VISGRAB_SCENES_DIR);
}

}  // namespace

std::unique_ptr<CLI::App> makeViewerApp(ViewerOptions& options) {
  auto app = std::make_unique<CLI::App>(
      "Browse the scenes of a database, their grasps and outcomes; replay a grasp's trial.",
      "visgrab-viewer");
  app->formatter(cli::makeHelpFormatter());
  // The same rules as visgrab: `--name=value` or `--name value`; an option given twice is a
  // mistake unless its help says repeatable.
  app->add_option("--db", options.database,
                  "Scene database: a generated folder or an original VisGraB manifest (default: "
                  "the results' database, else ./database)")
      ->type_name("DIR|MANIFEST");
  app->add_option("--scene", options.scene, "The scene shown first (default: the first one)")
      ->type_name("ID");
  app->add_option("--results", options.results,
                  "A run's result folder: outcomes in the grasp table; its run.csv gives the "
                  "default database, grasp files and hand")
      ->type_name("RESULTS");
  app->add_option("--grasps", options.grasps,
                  "Grasp files or folders (docs/grasp-format.md); repeatable")
      ->type_name("FILE|DIR")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app->add_option("--hand", options.hand,
                  "The hand: its folder or grasp description (default: the results' hand, else "
                  "the data folder's hands/sdh/sdh.grasp.xml: $VISGRAB_DATA, the installed "
                  "share/visgrab/scenes or the source tree's scenes/)")
      ->type_name("DIR|GRASP.xml");
  app->add_option("--grasp", options.grasp,
                  "Replay this grasp of --scene: its id, or N for the scene's N-th grasp")
      ->type_name("ID|N");
  app->add_option("--method", options.method, "Count --grasp among method M's grasps only")
      ->type_name("M");
  app->add_option("--protocol", options.protocol,
                  "The trial protocol replays use: lift, a protocol of the data folder's "
                  "protocols/ or a file (default: the one the results recorded, found in the "
                  "data folder's protocols/ by its name and hash, else the lift); with --results "
                  "it must have the run's protocol_hash")
      ->type_name("lift|NAME|FILE");
  app->add_option("--screenshot", options.screenshot,
                  "Render the 3-D view once (with --grasp: after lifting), save it as a PNG and "
                  "exit")
      ->type_name("FILE.png");
  app->add_option_function<std::string>(
         "--size",
         [&options](const std::string& text) {
           const std::string problem = parseSize(text, options);
           if (!problem.empty()) throw CLI::ValidationError("--size", problem);
         },
         "Size of the 3-D view in pixels, 16..8192 each")
      ->type_name("WxH")
      ->default_str(std::to_string(options.width) + "x" + std::to_string(options.height));
  app->footer(
      "Mouse: left-drag orbits, right- or middle-drag pans, the wheel zooms; double-click or F\n"
      "frames the objects and the hand; keys 1-4 choose the oblique, front, side and top views;\n"
      "space plays and pauses a replay; Ctrl+S saves a screenshot. See docs/viewer.md.\n"
      "Options: '--name value' and '--name=value' are the same; an option given twice is an\n"
      "error unless its help says 'repeatable'.\n"
      "Exit codes: 0 success, 1 unreadable input, 2 a command-line mistake.");
  return app;
}

std::string usageLine() {
  ViewerOptions options;
  const auto app = makeViewerApp(options);
  return cli::makeHelpFormatter()->make_usage(app.get(), app->get_name()) +
         "run 'visgrab-viewer --help' for the options\n";
}

ViewerOptions parseViewerOptions(const std::vector<std::string>& args) {
  ViewerOptions options;
  const auto app = makeViewerApp(options);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app->parse(reversed);
  } catch (const CLI::CallForHelp&) {
    options.help = true;
    options.helpText = app->help();
    return options;
  } catch (const CLI::ParseError& e) {
    throw UsageError(cli::describeParseError(e, *app));
  }
  if (options.grasp && !options.scene) {
    throw UsageError("--grasp needs --scene ID (the scene whose grasp it is)");
  }
  if (app->count("--method") > 0 && options.method.empty()) {
    throw UsageError("--method: expected a method name, got ''");
  }
  if (!options.method.empty() && !options.grasp) {
    throw UsageError("--method only chooses among the grasps for --grasp; give --grasp too");
  }
  if (options.screenshot && options.screenshot->extension() != ".png") {
    throw UsageError("--screenshot: expected a file name ending in .png, got '" +
                     options.screenshot->string() + "'");
  }
  return options;
}

ViewerData loadViewerData(const ViewerOptions& options) {
  ViewerData data;
  results::RunSources sources;
  if (options.results) {
    std::vector<rw::common::Diagnostic> warnings;
    data.results = results::readResults(*options.results, &warnings);
    for (const auto& w : warnings) data.warnings.push_back(w.format());
    sources = data.results->sources;
    if (!sources.engine.empty()) data.engine = sources.engine;
  }

  data.databasePath =
      options.database.value_or(sources.database.empty() ? fs::path("database") : sources.database);
  if (!fs::exists(data.databasePath)) {
    throw std::runtime_error("no scene database at '" + data.databasePath.string() +
                             "' (give --db DIR or MANIFEST)");
  }
  database::requireRecordedDatabase(data.databasePath, sources.databaseHash);
  data.database =
      std::make_unique<database::Database>(database::Database::openAny(data.databasePath));
  for (const auto& w : data.database->warnings()) data.warnings.push_back(w.format());

  const fs::path hand = options.hand.value_or(
      sources.hand.empty() ? dataFolder() / "hands/sdh/sdh.grasp.xml" : sources.hand);
  data.hand = grasp::loadHandGraspSetup(hand);

  const std::vector<fs::path> graspFiles = options.grasps.empty() ? sources.grasps : options.grasps;
  data.haveGraspFiles = !graspFiles.empty();
  if (options.grasp && !data.haveGraspFiles) {
    throw UsageError("--grasp needs grasp files: give --grasps FILE|DIR or --results RESULTS");
  }
  if (data.haveGraspFiles) {
    data.grasps = taskio::readGraspSources(graspFiles);
    for (const auto& d : data.grasps.rejected) data.warnings.push_back(d.format());
    for (const auto& d : data.grasps.warnings) data.warnings.push_back(d.format());
  }

  // Replays use the run's protocol, or none: a replay with another would show other trials.
  std::optional<fs::path> protocol;
  if (options.protocol) {
    try {
      protocol = cli::protocolPath(*options.protocol, dataFolder());
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--protocol: ") + e.what());
    }
  }
  if (data.results) {
    try {
      data.protocol = results::replayProtocol(sources, dataFolder(), protocol);
    } catch (const results::ProtocolNotFoundError& e) {
      data.replayProblem = e.what();
    }
  } else if (protocol) {
    data.protocol = rwsim::trial::loadTrialProtocol(*protocol);
    rwsim::trial::checkProtocol(data.protocol);
  }
  return data;
}

}  // namespace visgrab::viewer
