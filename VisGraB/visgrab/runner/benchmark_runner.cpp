#include "visgrab/runner/benchmark_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/results_writer.hpp"
#include "visgrab/session/grasp_order.hpp"
#include "visgrab/session/scene_loader.hpp"
#include "visgrab/session/scene_selection.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace visgrab::runner {

namespace {

namespace fs = std::filesystem;
using rw::common::Diagnostic;
using rwsim::simulator::GraspOutcome;

using session::RankedGrasp;
using session::SceneGraspList;

Diagnostic rejection(const grasp::GraspRequest& r, const std::string& message) {
  Diagnostic d;
  d.file = r.sourceFile;
  d.line = r.sourceLine;
  d.message = "grasp " + r.id + ": " + message;
  return d;
}

int objectIdOf(const rwsim::dynamics::DynamicWorkCell& dwc, int body) {
  if (body < 0) return 0;
  const std::string& name = dwc.bodies()[static_cast<std::size_t>(body)].name;
  return database::objectIdByName(name).value_or(0);
}

/// Runs one scene's pending grasps in its session; appends each trial as it finishes.
class SceneRunner {
 public:
  SceneRunner(const SceneGraspList& work, const session::SceneLoader& loader)
      : work_(&work), session_(loader, *work.entry) {}

  /// The trial record of `job`, or nullopt (and `rejected` set) for a grasp rejected as input.
  std::optional<results::TrialRecord> run(const RankedGrasp& job, Diagnostic& rejected) const {
    const grasp::GraspRequest& r = *job.request;
    const grasp::ResolvedGrasp resolved = session_.resolve(r);
    if (resolved.status == grasp::ResolveStatus::kInputError) {
      rejected = rejection(r, resolved.message);
      return std::nullopt;
    }
    results::TrialRecord record;
    record.sceneId = work_->entry->id;
    record.conditions = work_->entry->conditions;
    record.method = r.method;
    record.graspId = r.id;
    record.rank = job.rank;
    if (resolved.status == grasp::ResolveStatus::kInvalidContacts ||
        resolved.status == grasp::ResolveStatus::kInCollision) {
      // Nothing to simulate: the contact IK found no configuration, or the placement search
      // no collision-free placement (the message gives the least penetration).
      record.outcome = resolved.status == grasp::ResolveStatus::kInCollision
                           ? GraspOutcome::kInCollision
                           : GraspOutcome::kInvalidContacts;
      record.detail = resolved.message;
      return record;
    }
    const auto result = session_.trial().run(resolved.parameters, session_.initialState());
    record.outcome = result.outcome;
    record.qLift = result.qLift;
    record.qGws = result.qGws;
    record.qGwsUnit = result.qGwsUnit;
    record.object = objectIdOf(session_.dynamicWorkcell(), result.object);
    record.simulatedTime = result.simulatedTime;
    record.detail = result.detail;
    if (resolved.placement && resolved.placement->tests > 1) {
      record.detail += "; " + resolved.placement->describe();
    }
    return record;
  }

 private:
  const SceneGraspList* work_;
  session::SceneSession session_;
};

}  // namespace

RunSummary runBenchmark(const RunOptions& options,
                        const std::function<void(const RunProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const database::Database db = database::Database::openAny(options.database);
  const auto selected = session::selectScenes(db, options.scenes);
  const auto hand = grasp::loadHandGraspSetup(options.hand);
  const session::SceneLoader loader(db, *hand);
  const taskio::GraspFileContents grasps = taskio::readGraspSources(options.grasps);
  if (!options.resume && fs::exists(options.out / results::kTrialsFileName)) {
    throw std::runtime_error(options.out.string() +
                             " already holds results; resume them (--resume) or choose another "
                             "folder");
  }

  RunSummary summary;
  summary.rejected = grasps.rejected;
  std::map<std::string, int> rejectedPerMethod;
  // Grasps the reader could not parse have no reliable method: they count under their file.
  for (const auto& d : grasps.rejected) ++rejectedPerMethod[fs::path(d.file).filename().string()];
  results::RunResults run;
  run.sources.database = fs::absolute(options.database).lexically_normal();
  for (const auto& g : options.grasps) {
    run.sources.grasps.push_back(fs::absolute(g).lexically_normal());
  }
  run.sources.hand = fs::absolute(options.hand).lexically_normal();
  for (const auto* s : selected) run.scenes.push_back({s->id, s->conditions});
  const session::GraspOrder order = session::benchmarkOrder(db, selected, grasps.requests);
  run.methods = order.methods;
  for (const auto* r : order.unknownScene) {
    const auto close = db.closestIds(r->sceneId);
    std::string hint = close.empty() ? "" : " (did you mean " + close.front() + "?)";
    summary.rejected.push_back(rejection(*r, "unknown scene \"" + r->sceneId + "\"" + hint));
    ++rejectedPerMethod[r->method];
  }

  results::ResultsWriter writer(options.out);
  summary.resumed = static_cast<int>(writer.resumedCount());
  std::vector<const SceneGraspList*> pending;
  RunProgress state;
  for (const auto& w : order.scenes) {
    const auto left = std::count_if(w.grasps.begin(), w.grasps.end(), [&](const RankedGrasp& j) {
      return !writer.contains(w.entry->id, j.request->method, j.request->id);
    });
    if (left == 0) continue;
    pending.push_back(&w);
    state.trialsTotal += static_cast<int>(left);
  }
  state.scenesTotal = static_cast<int>(pending.size());
  for (const auto& [method, n] : rejectedPerMethod) run.rejected.emplace_back(method, n);
  writer.writeRun(run);

  // A hand that does not fit (a missing dynamics file, a device or controller the scene's
  // dynamics lack) fails every scene: report it once, as the run's error, not per grasp.
  if (!pending.empty()) {
    try {
      SceneRunner probe(*pending.front(), loader);
    } catch (const rw::common::LoadError&) {
      throw;
    } catch (const std::exception& e) {
      throw std::runtime_error("the hand " + options.hand.string() + " cannot run in scene " +
                               pending.front()->entry->id + ": " + e.what());
    }
  }

  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  auto report = [&]() {
    state.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(state);
  };
  auto worker = [&]() {
    for (std::size_t i = next++; i < pending.size(); i = next++) {
      const SceneGraspList& w = *pending[i];
      std::unique_ptr<SceneRunner> runner;
      std::string failure;
      try {
        runner = std::make_unique<SceneRunner>(w, loader);
      } catch (const std::exception& e) {
        failure = e.what();
      }
      for (const RankedGrasp& job : w.grasps) {
        const auto& r = *job.request;
        if (writer.contains(w.entry->id, r.method, r.id)) continue;
        Diagnostic rejected;
        std::optional<results::TrialRecord> record;
        if (runner) {
          record = runner->run(job, rejected);
        } else {
          rejected = rejection(r, "scene " + w.entry->id + " cannot be simulated: " + failure);
        }
        if (record) writer.append(*record);
        const std::lock_guard lock(mutex);
        if (!record) {
          summary.rejected.push_back(rejected);
          ++rejectedPerMethod[r.method];
        }
        ++state.trialsDone;
        report();
      }
      const std::lock_guard lock(mutex);
      ++state.scenesDone;
      report();
    }
  };
  const int threads = std::max(
      1,
      std::min<int>(options.threads, static_cast<int>(std::max<std::size_t>(1, pending.size()))));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();

  run.rejected.clear();
  for (const auto& [method, n] : rejectedPerMethod) run.rejected.emplace_back(method, n);
  writer.writeRun(run);
  writer.finalize();
  for (const auto& t : writer.trials()) {
    ++summary.outcomes[std::string(rwsim::simulator::outcomeName(t.outcome))];
    ++summary.trials;
  }
  summary.trials -= summary.resumed;
  summary.scenes = static_cast<int>(run.scenes.size());
  summary.methods = static_cast<int>(run.methods.size());
  std::stable_sort(summary.rejected.begin(), summary.rejected.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     return std::tie(a.file, a.line) < std::tie(b.file, b.line);
                   });
  return summary;
}

}  // namespace visgrab::runner
