#include "render_commands.hpp"

#include <charconv>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "progress_reporter.hpp"
#include "protocol_option.hpp"
#include "rw/common/diagnostic.hpp"
#include "rwsim/engines/engine_registry.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/render/offscreen_renderer.hpp"
#include "visgrab/render/png_io.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/run_protocol.hpp"
#include "visgrab/session/grasp_order.hpp"
#include "visgrab/session/scene_loader.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/taskio/grasp_file.hpp"
#include "visgrab/view/grasp_pictures.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

/// --size WxH.
std::pair<int, int> sizeOption(const Arguments& a, int width, int height) {
  const auto text = a.option("size");
  if (!text) return {width, height};
  const auto x = text->find('x');
  int w = 0, h = 0;
  const char* begin = text->data();
  const char* end = begin + text->size();
  const bool ok = x != std::string::npos && std::from_chars(begin, begin + x, w).ptr == begin + x &&
                  std::from_chars(begin + x + 1, end, h).ptr == end && w >= 16 && h >= 16 &&
                  w <= 8192 && h <= 8192;
  if (!ok) {
    throw UsageError(
        "--size: expected WIDTHxHEIGHT in pixels (16..8192 each), e.g. 800x600; got '" + *text +
        "'");
  }
  return {w, h};
}

/// What `visgrab render` was asked for (its options, with the run's recorded inputs filled in).
struct RenderRequest {
  std::string sceneId;
  std::string out;
  bool montage = false;
  bool overlay = false;
  std::optional<std::string> graspSpec;
  std::string method;
  view::PictureOptions picture;
  /// --size as given (each picture kind has its own default).
  std::optional<std::pair<int, int>> montageSize, stripSize, sceneSize;
  int columns = 4;
  bool quiet = false;
  std::optional<results::RunResults> run;
  fs::path dbPath;
  std::vector<fs::path> graspFiles;
  fs::path handFile;
  /// The engine the trials replay on: --engine, else the run's (run.csv), else ODE.
  std::string engine;
  /// The protocol the trials replay with: the run's (results::replayProtocol), else --protocol,
  /// else the lift.
  rwsim::trial::TrialProtocol protocol;
};

/// The protocol of the trials render replays: with --results the run's (--protocol, if given,
/// must be it), else --protocol, else the lift.
/// @throws std::runtime_error naming the run when its protocol is not found or --protocol is
/// another; UsageError, rw::common::LoadError as protocolOption.
rwsim::trial::TrialProtocol replayedProtocol(const Arguments& a,
                                             const std::optional<results::RunResults>& run) {
  const std::optional<fs::path> given = protocolOption(a);
  if (!run) {
    return given ? rwsim::trial::loadTrialProtocol(*given) : rwsim::trial::TrialProtocol::lift();
  }
  try {
    return results::replayProtocol(run->sources, dataFolder(a), given);
  } catch (const rw::common::LoadError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot replay the trials of " + *a.option("results") + ": " +
                             e.what());
  }
}

// --scene and --out are required options of the CLI11 command (addRenderCommands).
RenderRequest parseRenderArguments(const Arguments& a) {
  const std::string sceneId = a.option("scene").value();
  const std::string out = a.option("out").value();
  if (fs::path(out).extension() != ".png") {
    throw UsageError("--out: the picture is written as PNG; give a file name ending in .png");
  }
  const bool montage = a.flag("montage");
  const bool overlay = a.flag("overlay");
  const auto graspSpec = a.option("grasp");
  if (montage && (overlay || graspSpec)) {
    throw UsageError(
        "--montage shows all grasps of the scene; it takes neither --grasp nor "
        "--overlay");
  }
  if (overlay && !graspSpec) throw UsageError("--overlay needs --grasp ID|N");
  view::PictureOptions options;
  if (const auto v = a.option("view")) {
    const auto preset = view::viewPresetFromName(*v);
    if (!preset) throw UsageError("--view: expected oblique, front, side or top; got '" + *v + "'");
    options.view = *preset;
  }
  options.contacts = !a.flag("no-contacts");
  const int columns = integerOption(a, "columns", 4, 1);
  const bool quiet = a.flag("quiet");

  // The run's inputs: explicit options first, else what the results folder recorded.
  std::optional<results::RunResults> run;
  if (const auto r = a.option("results")) {
    std::vector<rw::common::Diagnostic> warnings;
    run = results::readResults(*r, &warnings);
    for (const auto& w : warnings) std::cerr << w.format() << "\n";
  }
  fs::path dbPath;
  if (const auto d = a.option("db")) {
    dbPath = *d;
  } else if (run && !run->sources.database.empty()) {
    dbPath = run->sources.database;
  } else {
    throw UsageError("--db DIR is required (or --results of a run that recorded its database)");
  }
  // The trials replay in the database the run used, or not at all.
  if (run) database::requireRecordedDatabase(dbPath, run->sources.databaseHash);
  // ... and with the protocol the run used, or not at all (the scene alone needs none).
  rwsim::trial::TrialProtocol protocol;
  if (graspSpec || montage || a.option("protocol")) protocol = replayedProtocol(a, run);
  std::vector<fs::path> graspFiles;
  for (const auto& g : a.values("grasps")) graspFiles.emplace_back(g);
  if (graspFiles.empty() && run) {
    graspFiles = run->sources.grasps;
  }
  fs::path handFile = (dataFolder(a) / "hands/sdh/sdh.grasp.xml");
  if (const auto h = a.option("hand")) {
    handFile = *h;
  } else if (run && !run->sources.hand.empty()) {
    handFile = run->sources.hand;
  }
  if ((graspSpec || montage) && graspFiles.empty()) {
    throw UsageError(std::string(montage ? "--montage" : "--grasp") +
                     " needs the grasps: --grasps FILE|DIR, or --results of a run that recorded "
                     "them");
  }
  const std::string method = a.option("method").value_or("");

  RenderRequest request;
  request.sceneId = sceneId;
  request.out = out;
  request.montage = montage;
  request.overlay = overlay;
  request.graspSpec = graspSpec;
  request.method = method;
  request.picture = options;
  // The overlay has the stereo image's size; the other pictures read --size.
  if (montage) {
    request.montageSize = sizeOption(a, 320, 240);
  } else if (graspSpec && !overlay) {
    request.stripSize = sizeOption(a, 480, 360);
  } else if (!graspSpec) {
    request.sceneSize = sizeOption(a, 800, 600);
  }
  request.columns = columns;
  request.quiet = quiet;
  request.run = std::move(run);
  request.dbPath = dbPath;
  request.graspFiles = graspFiles;
  request.handFile = handFile;
  if (a.option("engine")) {
    request.engine = engineOption(a);
  } else {
    request.engine = request.run && !request.run->sources.engine.empty()
                         ? request.run->sources.engine
                         : std::string(rwsim::engines::kDefaultEngine);
  }
  request.protocol = std::move(protocol);
  return request;
}

/// The scene to draw, loaded with the hand as the benchmark runs it (its trials with the
/// request's engine and protocol), with its grasps in the benchmark's order (empty without grasp
/// files).
class RenderScene {
 public:
  explicit RenderScene(const RenderRequest& request)
      : db_(database::Database::openAny(request.dbPath)),
        entry_(&db_.scene(request.sceneId)),
        hand_(grasp::loadHandGraspSetup(request.handFile)),
        loader_(makeLoader(db_, *hand_, request)),
        session_(loader_, *entry_) {
    if (request.graspFiles.empty()) return;
    const auto contents = taskio::readGraspSources(request.graspFiles);
    for (const auto& d : contents.rejected) std::cerr << d.format() << "\n";
    grasps_ = session::sceneGrasps(db_, *entry_, contents, request.run ? &*request.run : nullptr);
  }

  const database::Database& database() const { return db_; }
  const database::SceneEntry& entry() const { return *entry_; }
  const grasp::HandGraspSetup& hand() const { return *hand_; }
  const session::SceneSession& session() const { return session_; }
  const std::vector<session::SceneGrasp>& grasps() const { return grasps_; }

 private:
  static session::SceneLoader makeLoader(const database::Database& db,
                                         const grasp::HandGraspSetup& hand,
                                         const RenderRequest& request) {
    session::SceneLoader loader(db, hand, request.engine);
    loader.setProtocol(request.protocol);
    return loader;
  }

  database::Database db_;
  const database::SceneEntry* entry_;
  std::unique_ptr<grasp::HandGraspSetup> hand_;
  session::SceneLoader loader_;
  session::SceneSession session_;
  std::vector<session::SceneGrasp> grasps_;
};

/// A finished picture and what it shows (for the closing line).
struct RenderedPicture {
  visual::RgbImage image;
  std::string summary;
};

/// The outcome of `g` for a montage tile: its trial record, else simulated again (reported on
/// `progress` unless it is null).
rwsim::trial::GraspOutcome tileOutcome(const RenderScene& scene, const session::SceneGrasp& g,
                                       const grasp::ResolvedGrasp& resolved, int n,
                                       ProgressReporter* progress) {
  if (g.record) return g.record->outcome;
  if (!resolved.placed()) return rwsim::trial::GraspOutcome::kInvalidContacts;
  if (progress) progress->update(n, static_cast<long>(scene.grasps().size()));
  const auto& s = scene.session();
  return s.trial().run(resolved.parameters, s.initialState()).outcome;
}

/// --montage: every grasp of the scene (of --method) as a tile coloured by its outcome.
RenderedPicture renderMontage(const RenderRequest& request, const RenderScene& scene,
                              render::OffscreenRenderer& offscreen,
                              const view::WorkcellDrawing& drawing) {
  view::PictureOptions options = request.picture;
  std::tie(options.width, options.height) = *request.montageSize;
  const std::string& method = request.method;
  std::vector<view::MontageTile> tiles;
  std::optional<ProgressReporter> progress;
  if (!request.quiet) progress.emplace("simulating grasp", "grasps");
  int n = 0;
  for (const auto& g : scene.grasps()) {
    if (!method.empty() && g.request.method != method) continue;
    ++n;  // as --grasp N counts (with --method, among that method's grasps)
    view::MontageTile tile;
    tile.label = std::to_string(n) + "  " + g.request.method + " " + g.request.id;
    const auto resolved = scene.session().resolve(g.request);
    if (resolved.status == grasp::ResolveStatus::kInputError) {
      std::cerr << "visgrab render: grasp " << g.request.id << " (" << g.request.method
                << ") left out: " << resolved.message << "\n";
      continue;
    }
    if (resolved.placed()) tile.grasp = resolved.parameters;
    tile.outcome = tileOutcome(scene, g, resolved, n, progress ? &*progress : nullptr);
    tiles.push_back(std::move(tile));
  }
  progress.reset();
  const std::string& id = scene.entry().id;
  if (tiles.empty()) {
    throw UsageError("the grasp files have no grasp for scene " + id +
                     (method.empty() ? "" : " and method " + method));
  }
  const std::string title = id + "   " + std::to_string(tiles.size()) + " grasps" +
                            (method.empty() ? "" : " of " + method);
  return {view::graspMontage(offscreen.renderer(), drawing, scene.session(), tiles, title, options,
                             request.columns),
          std::to_string(tiles.size()) + " grasps"};
}

/// The grasp --grasp names (session::selectGrasp: the N-th in trials.csv's order).
const session::SceneGrasp& chosenGrasp(const RenderRequest& request, const RenderScene& scene) {
  try {
    return session::selectGrasp(scene.grasps(), *request.graspSpec, request.method);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--grasp: ") + e.what());
  }
}

/// --grasp --overlay: the grasp over the left stereo image; nullopt (after saying why) when the
/// grasp cannot be placed.
std::optional<RenderedPicture> renderOverlay(const RenderScene& scene,
                                             const session::SceneGrasp& chosen,
                                             render::OffscreenRenderer& offscreen,
                                             const view::WorkcellDrawing& drawing) {
  const auto& s = scene.session();
  const auto resolved = s.resolve(chosen.request);
  if (!resolved.placed()) {
    std::cerr << "visgrab render: grasp " << chosen.request.id
              << " cannot be placed: " << resolved.message << "\n";
    return std::nullopt;
  }
  const auto outcome = chosen.record ? chosen.record->outcome
                                     : s.trial().run(resolved.parameters, s.initialState()).outcome;
  const database::SceneEntry& entry = scene.entry();
  const visual::RgbImage left = render::readImage(entry.leftImage);
  return RenderedPicture{
      view::graspOverlay(offscreen.renderer(), drawing,
                         s.trial().placedState(resolved.parameters, s.initialState()),
                         resolved.parameters.X_W_tcp, left, scene.database().calibration(entry.id),
                         outcome,
                         entry.id + "   " + chosen.request.method + " " + chosen.request.id),
      std::string(rwsim::trial::outcomeName(outcome))};
}

/// --grasp: the trial's three moments; nullopt (after saying why) for a grasp the hand cannot
/// take.
std::optional<RenderedPicture> renderTrial(const RenderRequest& request, const RenderScene& scene,
                                           const session::SceneGrasp& chosen,
                                           render::OffscreenRenderer& offscreen,
                                           const view::WorkcellDrawing& drawing) {
  view::PictureOptions options = request.picture;
  std::tie(options.width, options.height) = *request.stripSize;
  view::TrialPicture picture;
  try {
    picture = view::trialStrip(offscreen.renderer(), drawing, scene.session(), chosen, options);
  } catch (const std::invalid_argument& e) {
    std::cerr << "visgrab render: " << e.what() << "\n";
    return std::nullopt;
  }
  if (!picture.note.empty()) std::cerr << "visgrab render: " << picture.note << "\n";
  return RenderedPicture{picture.image, std::string(rwsim::trial::outcomeName(picture.outcome))};
}

/// No --grasp: the scene alone, framed on its objects.
RenderedPicture renderScenePicture(const RenderRequest& request, const RenderScene& scene,
                                   render::OffscreenRenderer& offscreen,
                                   const view::WorkcellDrawing& drawing) {
  view::PictureOptions options = request.picture;
  std::tie(options.width, options.height) = *request.sceneSize;
  const auto& initial = scene.session().initialState();
  const view::Orbit orbit = view::framed(view::presetOrbit(options.view),
                                         view::objectsBox(scene.session(), drawing, initial, 0.05),
                                         options.width, options.height);
  return {view::renderState(offscreen.renderer(), drawing, initial, {},
                            view::DrawStyle{false, true, std::nullopt}, orbit, options),
          "scene"};
}

int runRender(const Arguments& a) {
  const RenderRequest request = parseRenderArguments(a);
  const RenderScene scene(request);
  render::OffscreenRenderer offscreen;
  const view::WorkcellDrawing drawing(scene.session().workcell(), offscreen.renderer(),
                                      scene.hand().deviceName());
  for (const auto& w : drawing.warnings()) std::cerr << "visgrab render: " << w << "\n";
  std::optional<RenderedPicture> picture;
  if (request.montage) {
    picture = renderMontage(request, scene, offscreen, drawing);
  } else if (request.graspSpec) {
    const session::SceneGrasp& chosen = chosenGrasp(request, scene);
    picture = request.overlay ? renderOverlay(scene, chosen, offscreen, drawing)
                              : renderTrial(request, scene, chosen, offscreen, drawing);
  } else {
    picture = renderScenePicture(request, scene, offscreen, drawing);
  }
  if (!picture) return 1;
  render::writePng(request.out, picture->image);
  std::cout << "wrote " << request.out << " (" << picture->image.width << "x"
            << picture->image.height << ", " << picture->summary << ", hand "
            << scene.hand().deviceName() << ")\n";
  return 0;
}

}  // namespace

void addRenderCommands(CommandLine& cli) {
  CLI::App& render = cli.addCommand(
      nullptr, "render",
      "Draw a scene (headless, EGL): alone; with --grasp the trial's three moments (placed, "
      "closed, lifted) labelled with the outcome and qualities, contact forces as arrows; "
      "--overlay the grasp over the left stereo image; --montage every grasp of the scene "
      "coloured by outcome. --results takes the database, grasps, hand and outcomes from a "
      "run; its trials replay with the run's engine and protocol.",
      guarded(runRender));
  render.add_option("--scene", "The scene to draw")->required()->type_name("ID");
  render.add_option("--out", "The picture to write (PNG)")->required()->type_name("FILE.png");
  render.add_option("--db", "The database (default: the one --results recorded)")
      ->type_name("DIR|MANIFEST");
  render.add_option("--results", "A run's result folder: database, grasps, hand and outcomes")
      ->type_name("RESULTS");
  render
      .add_option("--grasps",
                  "Grasp files or folders (default: the ones --results recorded); repeatable")
      ->type_name("FILE|DIR")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  render
      .add_option("--hand",
                  "The hand: its folder or grasp description (default: the one --results "
                  "recorded, else the SDH)")
      ->type_name("DIR|GRASP.xml");
  render
      .add_option("--grasp",
                  "The grasp to draw: its id, or N for the scene's N-th grasp in the benchmark's "
                  "order")
      ->type_name("ID|N");
  addFlag(render, "--overlay", "Draw --grasp over the left stereo image");
  render.add_option("--method", "Count --grasp (and --montage) among method M's grasps only")
      ->type_name("M");
  addFlag(render, "--montage", "Every grasp of the scene, one tile each, coloured by outcome");
  render.add_option("--columns", "Tiles per row of --montage")
      ->type_name("N")
      ->default_str("4")
      ->check(integerAtLeast(1));
  render.add_option("--view", "The camera: oblique, front, side or top")
      ->type_name("VIEW")
      ->default_str("oblique");
  render
      .add_option("--size",
                  "Picture (tile) size in pixels, 16..8192 each (default: 800x600 for a scene, "
                  "480x360 per moment, 320x240 per montage tile)")
      ->type_name("WxH");
  addFlag(render, "--no-contacts", "Leave the contact forces out");
  addEngineOption(render)->description(
      "The physics engine the trials replay on (default: the one the --results run recorded, "
      "else ode): ode or mujoco (when built)");
  addProtocolOption(render)->description(
      "The trial protocol the trials replay with: lift, a protocol of the data folder's "
      "protocols/ or a file. Default: the one the --results run recorded (the lift, or its "
      "protocols/NAME.xml when that has the recorded hash), else the lift. With --results it "
      "must have the run's protocol_hash; a run whose protocol is not in protocols/ needs the "
      "file it ran with");
  addDataOption(render);
  addQuietFlag(render);
}

}  // namespace visgrab::app
