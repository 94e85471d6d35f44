#include "visgrab/view/report_pictures.hpp"

#include <algorithm>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>

#include "rw/common/task_pool.hpp"
#include "rw/common/write_error.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/render/offscreen_renderer.hpp"
#include "visgrab/render/png_io.hpp"
#include "visgrab/results/run_protocol.hpp"
#include "visgrab/session/grasp_order.hpp"
#include "visgrab/session/scene_loader.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/taskio/grasp_file.hpp"
#include "visgrab/view/grasp_pictures.hpp"

namespace visgrab::view {

namespace {

namespace fs = std::filesystem;

/// What drawing one run's trials needs, opened once.
struct RunInputs {
  std::optional<database::Database> db;
  taskio::GraspFileContents grasps;
  std::unique_ptr<grasp::HandGraspSetup> hand;
  /// The run's scenes with its hand (set once `db` has its place).
  std::unique_ptr<session::SceneLoader> loader;
  /// Why the run's trials cannot be drawn (empty if they can).
  std::string problem;
};

RunInputs openInputs(const results::RunResults& run) {
  RunInputs in;
  const results::RunSources& s = run.sources;
  if (s.database.empty() || s.grasps.empty() || s.hand.empty()) {
    in.problem = "the run does not record its database, grasps and hand (run.csv of an older run)";
    return in;
  }
  if (std::string problem = database::recordedDatabaseProblem(s.database, s.databaseHash);
      !problem.empty()) {
    in.problem = std::move(problem);
    return in;
  }
  try {
    in.db = database::Database::openAny(s.database);
    in.grasps = taskio::readGraspSources(s.grasps);
    in.hand = grasp::loadHandGraspSetup(s.hand);
  } catch (const std::exception& e) {
    in.problem = std::string("cannot open the run's input: ") + e.what();
  }
  return in;
}

std::string fileName(const analysis::Showcase& s) {
  std::string name =
      "column" + std::to_string(s.column + 1) + "-" + s.groupKey + "-" + s.role + ".png";
  std::replace_if(
      name.begin(), name.end(), [](char c) { return c == '/' || c == ' ' || c == '\\'; }, '_');
  return name;
}

/// What one picture worker keeps between its showcases: its OpenGL context and the scene it
/// has loaded (jobs come in (run, scene) order, so a worker often keeps its scene).
struct PictureWorker {
  bool started = false;
  std::unique_ptr<render::OffscreenRenderer> offscreen;
  std::string contextProblem;
  std::string loadedScene;
  std::size_t loadedRun = 0;
  std::unique_ptr<session::SceneSession> session;
  std::unique_ptr<WorkcellDrawing> drawing;

  /// Drops the drawing, the session and the context, in that order, on the worker's thread.
  void release() {
    drawing.reset();
    session.reset();
    offscreen.reset();
  }
};

/// Draws showcase `s` into reportDir/images (sets its image and note) with worker `w`.
/// @throws std::exception whose message becomes the note when it cannot be drawn.
void drawShowcase(analysis::Showcase& s, std::size_t runCount, const std::vector<RunInputs>& inputs,
                  const fs::path& reportDir, const ReportPictureOptions& options,
                  PictureWorker& w) {
  if (!w.started) {
    w.started = true;
    w.loadedRun = runCount;
    try {
      w.offscreen = std::make_unique<render::OffscreenRenderer>();
    } catch (const std::exception& e) {
      w.contextProblem = std::string("no OpenGL context: ") + e.what();
    }
  }
  const std::size_t r = s.run;
  if (r >= inputs.size()) throw std::runtime_error("the showcase's run is not given");
  const RunInputs& in = inputs[r];
  if (!w.contextProblem.empty()) throw std::runtime_error(w.contextProblem);
  if (!in.problem.empty()) throw std::runtime_error(in.problem);
  const database::SceneEntry& entry = in.db->scene(s.trial.sceneId);
  if (entry.id != w.loadedScene || r != w.loadedRun) {
    w.loadedScene.clear();
    w.drawing.reset();
    w.session.reset();
    // A fresh renderer per scene: GlRenderer keeps every mesh it was given. The old one goes
    // first: its destructor leaves no context current.
    w.offscreen.reset();
    w.offscreen = std::make_unique<render::OffscreenRenderer>();
    w.session = std::make_unique<session::SceneSession>(*in.loader, entry);
    w.drawing = std::make_unique<WorkcellDrawing>(w.session->workcell(), w.offscreen->renderer(),
                                                  in.hand->deviceName());
    w.loadedScene = entry.id;
    w.loadedRun = r;
  }
  // The showcase's request, with the showcase's own trial as its record.
  std::optional<session::SceneGrasp> grasp;
  for (const auto& q : in.grasps.requests) {
    if (q.method == s.trial.method && q.id == s.trial.graspId && in.db->contains(q.sceneId) &&
        in.db->scene(q.sceneId).id == entry.id) {
      grasp = session::SceneGrasp{q, s.trial.rank, s.trial};
      break;
    }
  }
  if (!grasp) {
    throw std::runtime_error("grasp " + s.trial.graspId + " is not in the run's grasp files");
  }
  PictureOptions picture;
  picture.width = options.width;
  picture.height = options.height;
  const TrialPicture strip =
      trialStrip(w.offscreen->renderer(), *w.drawing, *w.session, *grasp, picture);
  const std::string name = fileName(s);
  render::writePng(reportDir / "images" / name, strip.image);
  s.image = "images/" + name;
  s.note = strip.note;
}

}  // namespace

void drawShowcases(std::vector<analysis::Showcase>& showcases,
                   const std::vector<results::RunResults>& runs, const fs::path& reportDir,
                   const ReportPictureOptions& options) {
  if (showcases.empty()) return;
  std::vector<RunInputs> inputs;
  inputs.reserve(runs.size());
  for (const auto& run : runs) inputs.push_back(openInputs(run));
  for (std::size_t r = 0; r < inputs.size(); ++r) {
    RunInputs& in = inputs[r];
    if (!in.problem.empty()) continue;
    const results::RunSources& sources = runs[r].sources;
    // The trials replay with the protocol that ran them, or are not drawn.
    rwsim::trial::TrialProtocol protocol;
    if (!sources.protocol.empty() && options.data.empty()) {
      in.problem = "the run's trials ran the protocol \"" + sources.protocol +
                   "\" and no data folder is given to find it in, so none are drawn";
      continue;
    }
    try {
      protocol = results::replayProtocol(sources, options.data);
    } catch (const results::ProtocolNotFoundError& e) {
      in.problem = "the run's trials ran the protocol \"" + e.name() + "\" (hash " + e.hash() +
                   "), which cannot be found: " + e.reason() + "; none are drawn";
      continue;
    }
    try {
      // The trials replay on the engine that ran them (run.csv; older runs were ODE's).
      const std::string& engine = sources.engine;
      in.loader =
          std::make_unique<session::SceneLoader>(*in.db, *in.hand, engine.empty() ? "ode" : engine);
      in.loader->setProtocol(std::move(protocol));
    } catch (const std::exception& e) {
      in.problem = std::string("cannot open the run's input: ") + e.what();
    }
  }
  // Jobs in (run, scene) order, so that a worker often keeps its scene loaded.
  std::vector<std::size_t> jobs(showcases.size());
  for (std::size_t i = 0; i < jobs.size(); ++i) jobs[i] = i;
  std::stable_sort(jobs.begin(), jobs.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(showcases[a].run, showcases[a].trial.sceneId) <
           std::tie(showcases[b].run, showcases[b].trial.sceneId);
  });
  fs::create_directories(reportDir / "images");
  std::mutex mutex;
  int done = 0;
  const int total = static_cast<int>(jobs.size());
  const rw::common::TaskPool pool(std::min(options.threads, std::max(1, total)));
  std::vector<PictureWorker> workers(static_cast<std::size_t>(pool.threads()));
  pool.run(
      jobs.size(),
      [&](std::size_t k, int id) {
        PictureWorker& w = workers[static_cast<std::size_t>(id)];
        analysis::Showcase& s = showcases[jobs[k]];
        try {
          drawShowcase(s, runs.size(), inputs, reportDir, options, w);
        } catch (const rw::common::WriteError&) {
          throw;  // disk full, folder gone: the report cannot be written either
        } catch (const std::exception& e) {
          s.note = e.what();
        }
        const std::lock_guard lock(mutex);
        ++done;
        if (options.progress) options.progress(done, total);
      },
      [&](int id) { workers[static_cast<std::size_t>(id)].release(); });
}

analysis::ShowcaseDrawer showcaseDrawer(ReportPictureOptions options) {
  return
      [options = std::move(options)](
          std::vector<analysis::Showcase>& showcases, const std::vector<results::RunResults>& runs,
          const fs::path& reportDir) { drawShowcases(showcases, runs, reportDir, options); };
}

}  // namespace visgrab::view
