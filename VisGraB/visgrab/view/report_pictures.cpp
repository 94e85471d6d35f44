#include "visgrab/view/report_pictures.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>

#include "visgrab/database/database.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/render/offscreen_renderer.hpp"
#include "visgrab/render/png_io.hpp"
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

}  // namespace

void drawShowcases(std::vector<analysis::Showcase>& showcases,
                   const std::vector<results::RunResults>& runs, const fs::path& reportDir,
                   const ReportPictureOptions& options) {
  if (showcases.empty()) return;
  std::vector<RunInputs> inputs;
  inputs.reserve(runs.size());
  for (const auto& run : runs) inputs.push_back(openInputs(run));
  for (auto& in : inputs) {
    if (!in.problem.empty()) continue;
    try {
      in.loader = std::make_unique<session::SceneLoader>(*in.db, *in.hand);
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
  std::atomic<std::size_t> next{0};
  int done = 0;
  const int total = static_cast<int>(jobs.size());
  auto finished = [&] {
    const std::lock_guard lock(mutex);
    ++done;
    if (options.progress) options.progress(done, total);
  };
  auto worker = [&] {
    std::unique_ptr<render::OffscreenRenderer> offscreen;
    std::string contextProblem;
    try {
      offscreen = std::make_unique<render::OffscreenRenderer>();
    } catch (const std::exception& e) {
      contextProblem = std::string("no OpenGL context: ") + e.what();
    }
    std::string loadedScene;
    std::size_t loadedRun = runs.size();
    std::unique_ptr<session::SceneSession> scene;
    std::unique_ptr<WorkcellDrawing> drawing;
    for (std::size_t k = next++; k < jobs.size(); k = next++) {
      analysis::Showcase& s = showcases[jobs[k]];
      const std::size_t r = s.run;
      try {
        if (r >= inputs.size()) throw std::runtime_error("the showcase's run is not given");
        const RunInputs& in = inputs[r];
        if (!contextProblem.empty()) throw std::runtime_error(contextProblem);
        if (!in.problem.empty()) throw std::runtime_error(in.problem);
        const database::SceneEntry& entry = in.db->scene(s.trial.sceneId);
        if (entry.id != loadedScene || r != loadedRun) {
          loadedScene.clear();
          drawing.reset();
          scene.reset();
          // A fresh renderer per scene: GlRenderer keeps every mesh it was given. The old one
          // goes first: its destructor leaves no context current.
          offscreen.reset();
          offscreen = std::make_unique<render::OffscreenRenderer>();
          scene = std::make_unique<session::SceneSession>(*in.loader, entry);
          drawing = std::make_unique<WorkcellDrawing>(scene->workcell(), offscreen->renderer(),
                                                      in.hand->deviceName());
          loadedScene = entry.id;
          loadedRun = r;
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
            trialStrip(offscreen->renderer(), *drawing, *scene, *grasp, picture);
        const std::string name = fileName(s);
        render::writePng(reportDir / "images" / name, strip.image);
        s.image = "images/" + name;
        s.note = strip.note;
      } catch (const std::exception& e) {
        s.note = e.what();
      }
      finished();
    }
    drawing.reset();
    scene.reset();
  };
  const int threads = std::clamp(options.threads, 1, std::max(1, total));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

analysis::ShowcaseDrawer showcaseDrawer(ReportPictureOptions options) {
  return
      [options = std::move(options)](
          std::vector<analysis::Showcase>& showcases, const std::vector<results::RunResults>& runs,
          const fs::path& reportDir) { drawShowcases(showcases, runs, reportDir, options); };
}

}  // namespace visgrab::view
