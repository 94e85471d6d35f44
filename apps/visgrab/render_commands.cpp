#include "render_commands.hpp"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/render/offscreen_renderer.hpp"
#include "visgrab/render/png_io.hpp"
#include "visgrab/results/results_file.hpp"
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

int runRender(const Arguments& a) {
  const auto sceneId = a.option("scene");
  const auto out = a.option("out");
  if (!sceneId) throw UsageError("--scene ID is required");
  if (!out) throw UsageError("--out FILE.png is required");
  if (fs::path(*out).extension() != ".png") {
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

  const auto db = database::Database::openAny(dbPath);
  const database::SceneEntry& entry = db.scene(*sceneId);
  const auto hand = grasp::loadHandGraspSetup(handFile);
  const view::SceneSession session(entry, *hand);
  std::vector<view::SceneGrasp> grasps;
  if (!graspFiles.empty()) {
    const auto contents = taskio::readGraspSources(graspFiles);
    for (const auto& d : contents.rejected) std::cerr << d.format() << "\n";
    grasps = view::sceneGrasps(db, entry, contents, run ? &*run : nullptr);
  }
  const std::string method = a.option("method").value_or("");

  render::OffscreenRenderer offscreen;
  const view::WorkcellDrawing drawing(session.workcell(), offscreen.renderer(), hand->deviceName());
  for (const auto& w : drawing.warnings()) std::cerr << "visgrab render: " << w << "\n";
  visual::RgbImage image;
  std::string summary;
  if (montage) {
    std::tie(options.width, options.height) = sizeOption(a, 320, 240);
    std::vector<view::MontageTile> tiles;
    int n = 0;
    for (const auto& g : grasps) {
      if (!method.empty() && g.request.method != method) continue;
      ++n;  // as --grasp N counts (with --method, among that method's grasps)
      view::MontageTile tile;
      tile.label = std::to_string(n) + "  " + g.request.method + " " + g.request.id;
      const auto resolved = session.resolve(g.request);
      if (resolved.status == grasp::ResolveStatus::kInputError) {
        std::cerr << "visgrab render: grasp " << g.request.id << " (" << g.request.method
                  << ") left out: " << resolved.message << "\n";
        continue;
      }
      if (resolved.placed()) tile.grasp = resolved.parameters;
      if (g.record) {
        tile.outcome = g.record->outcome;
      } else if (!resolved.placed()) {
        tile.outcome = rwsim::simulator::GraspOutcome::kInvalidContacts;
      } else {
        if (!quiet) std::fprintf(stderr, "\rsimulating grasp %d/%zu   ", n, grasps.size());
        tile.outcome = session.trial().run(resolved.parameters, session.initialState()).outcome;
      }
      tiles.push_back(std::move(tile));
    }
    if (!quiet) std::fputc('\n', stderr);
    if (tiles.empty()) {
      throw UsageError("the grasp files have no grasp for scene " + entry.id +
                       (method.empty() ? "" : " and method " + method));
    }
    image = view::graspMontage(offscreen.renderer(), drawing, session, tiles,
                               entry.id + "   " + std::to_string(tiles.size()) + " grasps" +
                                   (method.empty() ? "" : " of " + method),
                               options, columns);
    summary = std::to_string(tiles.size()) + " grasps";
  } else if (graspSpec) {
    const view::SceneGrasp* chosen = nullptr;
    try {
      chosen = &view::selectGrasp(grasps, *graspSpec, method);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--grasp: ") + e.what());
    }
    if (overlay) {
      const auto resolved = session.resolve(chosen->request);
      if (!resolved.placed()) {
        std::cerr << "visgrab render: grasp " << chosen->request.id
                  << " cannot be placed: " << resolved.message << "\n";
        return 1;
      }
      const auto outcome =
          chosen->record ? chosen->record->outcome
                         : session.trial().run(resolved.parameters, session.initialState()).outcome;
      const visual::RgbImage left = render::readImage(entry.leftImage);
      image = view::graspOverlay(
          offscreen.renderer(), drawing,
          session.trial().placedState(resolved.parameters, session.initialState()),
          resolved.parameters.X_W_tcp, left, db.calibration(entry.id), outcome,
          entry.id + "   " + chosen->request.method + " " + chosen->request.id);
      summary = std::string(rwsim::simulator::outcomeName(outcome));
    } else {
      std::tie(options.width, options.height) = sizeOption(a, 480, 360);
      view::TrialPicture picture;
      try {
        picture = view::trialStrip(offscreen.renderer(), drawing, session, *chosen, options);
      } catch (const std::invalid_argument& e) {
        std::cerr << "visgrab render: " << e.what() << "\n";
        return 1;
      }
      if (!picture.note.empty()) std::cerr << "visgrab render: " << picture.note << "\n";
      image = picture.image;
      summary = std::string(rwsim::simulator::outcomeName(picture.outcome));
    }
  } else {
    if (overlay) throw UsageError("--overlay needs --grasp ID|N");
    std::tie(options.width, options.height) = sizeOption(a, 800, 600);
    const auto& initial = session.initialState();
    const view::Orbit orbit = view::framed(view::presetOrbit(options.view),
                                           view::objectsBox(session, drawing, initial, 0.05),
                                           options.width, options.height);
    image = view::renderState(offscreen.renderer(), drawing, initial, {},
                              view::DrawStyle{false, true, std::nullopt}, orbit, options);
    summary = "scene";
  }
  render::writePng(*out, image);
  std::cout << "wrote " << *out << " (" << image.width << "x" << image.height << ", " << summary
            << ", hand " << hand->deviceName() << ")\n";
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
      "run.",
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
  addDataOption(render);
  addQuietFlag(render);
}

}  // namespace visgrab::app
