#include "viewer_options.hpp"

#include <charconv>
#include <cstdlib>
#include <string_view>
#include <system_error>

#include "rw/common/diagnostic.hpp"
#include "visgrab/results/results_file.hpp"

namespace visgrab::viewer {

namespace {

namespace fs = std::filesystem;

constexpr int kMinViewSide = 16;
constexpr int kMaxViewSide = 8192;

// A positive integer in [kMinViewSide, kMaxViewSide], or nullopt.
std::optional<int> viewSide(std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  if (value < kMinViewSide || value > kMaxViewSide) return std::nullopt;
  return value;
}

// "--size WxH" into width and height. @throws UsageError.
void parseSize(const std::string& text, ViewerOptions& options) {
  const std::size_t x = text.find_first_of("xX");
  const auto w =
      x == std::string::npos ? std::nullopt : viewSide(std::string_view(text).substr(0, x));
  const auto h =
      x == std::string::npos ? std::nullopt : viewSide(std::string_view(text).substr(x + 1));
  if (!w || !h) {
    throw UsageError("--size: expected WIDTHxHEIGHT in pixels, each " +
                     std::to_string(kMinViewSide) + ".." + std::to_string(kMaxViewSide) +
                     " (e.g. 1024x768), got '" + text + "'");
  }
  options.width = *w;
  options.height = *h;
}

// The project's scene data folder: $VISGRAB_DATA, else the source tree's scenes/ folder.
fs::path dataFolder() {
  if (const char* env = std::getenv("VISGRAB_DATA"); env != nullptr && *env != '\0') return env;
  return VISGRAB_SCENES_DIR;
}

}  // namespace

std::string usageLine() {
  return "usage: visgrab-viewer [--db DIR|MANIFEST] [--scene ID] [--results RESULTS]\n"
         "                      [--grasps FILE|DIR]... [--hand DIR|GRASP.xml] [--grasp ID|N]\n"
         "                      [--method M] [--screenshot FILE.png] [--size WxH]\n"
         "       visgrab-viewer --help\n";
}

std::string usageText() {
  return usageLine() +
         "\n"
         "Browse the scenes of a database, their grasps and outcomes; replay a grasp's trial.\n"
         "\n"
         "  --db DIR|MANIFEST    scene database (default: the results' database, else ./database)\n"
         "  --scene ID           the scene shown first (default: the first one)\n"
         "  --results RESULTS    a run's result folder: outcomes in the grasp table; its run.csv\n"
         "                       gives the default database, grasp files and hand\n"
         "  --grasps FILE|DIR    grasp files (docs/grasp-format.md); may be repeated\n"
         "  --hand DIR|GRASP.xml the hand: its folder or grasp description (default: the results' "
         "hand, else\n"
         "                       $VISGRAB_DATA or the source tree's "
         "scenes/hands/sdh/sdh.grasp.xml)\n"
         "  --grasp ID|N         replay this grasp of --scene (its id, or N for the N-th grasp)\n"
         "  --method M           count --grasp among method M's grasps only\n"
         "  --screenshot FILE    render the 3-D view once (with --grasp: after lifting), save it\n"
         "                       as a PNG and exit\n"
         "  --size WxH           size of the 3-D view in pixels (default 960x720)\n"
         "\n"
         "Mouse: left-drag orbits, right- or middle-drag pans, the wheel zooms; double-click or F\n"
         "frames the objects and the hand; keys 1-4 choose the oblique, front, side and top "
         "views;\n"
         "space plays and pauses a replay; Ctrl+S saves a screenshot. See docs/viewer.md.\n"
         "Exit codes: 0 success, 1 unreadable input, 2 a command-line mistake.\n";
}

ViewerOptions parseViewerOptions(const std::vector<std::string>& args) {
  ViewerOptions options;
  bool sizeGiven = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--help" || arg == "-h") {
      options.help = true;
      continue;
    }
    if (arg.rfind("--", 0) != 0) {
      throw UsageError("unexpected argument '" + arg + "' (options start with --; see --help)");
    }
    const auto value = [&](const char* what) {
      if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) {
        throw UsageError(arg + ": expected " + what + " after it");
      }
      return args[++i];
    };
    const auto once = [&](bool given) {
      if (given) throw UsageError(arg + " is given twice");
    };
    if (arg == "--db") {
      once(options.database.has_value());
      options.database = value("a database folder or manifest");
    } else if (arg == "--scene") {
      once(options.scene.has_value());
      options.scene = value("a scene id");
    } else if (arg == "--results") {
      once(options.results.has_value());
      options.results = value("a result folder");
    } else if (arg == "--grasps") {
      options.grasps.emplace_back(value("a grasp file or folder"));
    } else if (arg == "--hand") {
      once(options.hand.has_value());
      options.hand = value("a hand's grasp description (.grasp.xml)");
    } else if (arg == "--grasp") {
      once(options.grasp.has_value());
      options.grasp = value("a grasp id or number");
    } else if (arg == "--method") {
      once(!options.method.empty());
      options.method = value("a method name");
      if (options.method.empty()) throw UsageError("--method: expected a method name, got ''");
    } else if (arg == "--screenshot") {
      once(options.screenshot.has_value());
      options.screenshot = value("a PNG file to write");
    } else if (arg == "--size") {
      once(sizeGiven);
      sizeGiven = true;
      parseSize(value("WIDTHxHEIGHT"), options);
    } else {
      throw UsageError("unknown option '" + arg + "' (see --help)");
    }
  }
  if (options.help) return options;
  if (options.grasp && !options.scene) {
    throw UsageError("--grasp needs --scene ID (the scene whose grasp it is)");
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
  }

  data.databasePath =
      options.database.value_or(sources.database.empty() ? fs::path("database") : sources.database);
  if (!fs::exists(data.databasePath)) {
    throw std::runtime_error("no scene database at '" + data.databasePath.string() +
                             "' (give --db DIR or MANIFEST)");
  }
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
  return data;
}

}  // namespace visgrab::viewer
