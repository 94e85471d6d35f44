#include "visgrab/runner/benchmark_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "rw/common/stop_signals.hpp"
#include "rw/common/task_pool.hpp"
#include "rw/common/text_file.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/results_writer.hpp"
#include "visgrab/results/trial_columns.hpp"
#include "visgrab/runner/shard_record.hpp"
#include "visgrab/session/grasp_order.hpp"
#include "visgrab/session/scene_loader.hpp"
#include "visgrab/session/scene_selection.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace visgrab::runner {

namespace {

namespace fs = std::filesystem;
using rw::common::Diagnostic;
using rwsim::trial::GraspOutcome;

using session::RankedGrasp;
using session::SceneGraspList;

Diagnostic rejection(const grasp::GraspRequest& r, const std::string& message) {
  Diagnostic d;
  d.file = r.sourceFile;
  d.line = r.sourceLine;
  d.message = "grasp " + r.id + ": " + message;
  return d;
}

int objectIdOf(const rwsim::dynamics::DynamicWorkCell& dwc, rwsim::dynamics::BodyId body) {
  if (!body.valid()) return 0;
  const std::string& name = dwc.body(body).name;
  return database::objectIdByName(name).value_or(0);
}

/// Runs one scene's pending grasps in its session; appends each trial as it finishes.
class SceneRunner {
 public:
  SceneRunner(const SceneGraspList& work, const session::SceneLoader& loader)
      : work_(&work), session_(loader, *work.entry) {}

  /// The engine's version and settings in this scene (EngineFactory::settings()).
  std::string engineSettings() const { return session_.trial().engine().settings(); }

  /// The trial record of `job`, or nullopt (and `rejected` set) for a grasp rejected as input.
  std::optional<results::TrialRecord> run(const RankedGrasp& job, Diagnostic& rejected) const {
    const grasp::GraspRequest& r = *job.request;
    const grasp::ResolvedGrasp resolved = session_.resolve(r);
    if (resolved.status == grasp::ResolveStatus::kInputError) {
      rejected = rejection(r, resolved.reason);
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
    results::recordResult(result, objectIdOf(session_.dynamicWorkcell(), result.object), record);
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

namespace {

/// What a run reads before it starts.
struct RunInputs {
  database::Database db;
  std::vector<const database::SceneEntry*> selected;
  std::unique_ptr<grasp::HandGraspSetup> hand;
  taskio::GraspFileContents grasps;
};

/// The run's work: its scenes and methods (run.csv), the grasps per scene in benchmark order and
/// the grasps rejected so far.
struct RunPlan {
  results::RunResults run;
  session::GraspOrder order;
  std::vector<Diagnostic> rejected;
  /// Rejected grasps per method (per file for grasps the reader could not parse).
  std::map<std::string, int> rejectedPerMethod;
};

/// The scenes with trials left to run, and the progress counters of the run.
struct PendingWork {
  std::vector<const SceneGraspList*> scenes;
  RunProgress progress;
};

/// Opens the database, the hand and the grasp files; refuses a result folder that holds
/// results unless resuming.
RunInputs openInputs(const RunOptions& options) {
  RunInputs in{database::Database::openAny(options.database), {}, {}, {}};
  in.selected = session::selectScenes(in.db, options.scenes);
  in.hand = grasp::loadHandGraspSetup(options.hand);
  in.grasps = taskio::readGraspSources(options.grasps);
  if (!options.resume && fs::exists(options.out / results::kTrialsFileName)) {
    throw std::runtime_error(options.out.string() +
                             " already holds results; resume them (--resume) or choose another "
                             "folder");
  }
  return in;
}

/// Groups the grasps by selected scene (database order), ranks them per (scene, method) in file
/// order and orders each scene's by (method first seen, rank); rejects grasps of unknown scenes.
RunPlan planRun(const RunOptions& options, const RunInputs& in) {
  RunPlan plan;
  plan.rejected = in.grasps.rejected;
  // Grasps the reader could not parse have no reliable method: they count under their file.
  for (const auto& d : in.grasps.rejected) {
    ++plan.rejectedPerMethod[fs::path(d.file).filename().string()];
  }
  results::RunResults& run = plan.run;
  run.sources.database = fs::absolute(options.database).lexically_normal();
  run.sources.databaseHash = database::indexHash(options.database);
  for (const auto& g : options.grasps) {
    run.sources.grasps.push_back(fs::absolute(g).lexically_normal());
  }
  run.sources.hand = fs::absolute(options.hand).lexically_normal();
  run.sources.engine = options.engine;
  for (const auto* s : in.selected) run.scenes.push_back({s->id, s->conditions});
  plan.order = session::benchmarkOrder(in.db, in.selected, in.grasps.requests);
  run.methods = plan.order.methods;
  for (const auto* r : plan.order.unknownScene) {
    plan.rejected.push_back(rejection(*r, unknownSceneReason(in.db, r->sceneId)));
    ++plan.rejectedPerMethod[r->method];
  }
  return plan;
}

/// Keeps only `shard`'s scenes in `plan` (planShards over every selected scene's grasp count);
/// the grasps rejected before the run (unparsable, unknown scene) stay with the first shard.
void restrictToShard(RunPlan& plan, const ShardSpec& shard) {
  std::vector<std::size_t> counts;
  counts.reserve(plan.order.scenes.size());
  for (const auto& s : plan.order.scenes) counts.push_back(s.grasps.size());
  const SceneBlock block =
      planShards(counts, shard.count)[static_cast<std::size_t>(shard.index - 1)];
  const auto first = static_cast<std::ptrdiff_t>(block.begin);
  const auto last = static_cast<std::ptrdiff_t>(block.end);
  plan.order.scenes = {plan.order.scenes.begin() + first, plan.order.scenes.begin() + last};
  plan.run.scenes = {plan.run.scenes.begin() + first, plan.run.scenes.begin() + last};
  if (shard.index != 1) {
    plan.rejected.clear();
    plan.rejectedPerMethod.clear();
  }
}

/// The record of the shard `options` runs, written "running" into options.out; a resumed shard
/// folder must hold the same shard of the same run.
ShardRecord startShard(const RunOptions& options) {
  ShardRecord record;
  record.shard = *options.shard;
  record.inputs = fingerprintRun(options.database, options.grasps, options.hand, options.scenes);
  if (options.resume && fs::exists(options.out / kShardRecordFileName)) {
    const ShardRecord old = readShardRecord(options.out);
    if (old.shard.index != record.shard.index || old.shard.count != record.shard.count) {
      throw std::runtime_error(options.out.string() + " holds " + describe(old.shard) + ", not " +
                               describe(record.shard) + "; give each shard its own folder");
    }
    if (old.inputs != record.inputs) {
      throw std::runtime_error(options.out.string() + " holds " + describe(old.shard) +
                               " of another run (" + describeDifference(old.inputs, record.inputs) +
                               " differ); choose another folder");
    }
  }
  writeShardRecord(options.out, record);
  return record;
}

/// Marks the shard finished, with the hashes of its finished files.
void finishShard(const fs::path& out, ShardRecord record, std::size_t trials) {
  record.finished = true;
  record.trials = trials;
  record.trialsHash = contentHash(rw::common::readTextFileOrThrow(out / results::kTrialsFileName));
  record.runHash = contentHash(rw::common::readTextFileOrThrow(out / results::kRunFileName));
  writeShardRecord(out, record);
}

/// The scenes with trials not yet in `writer` (resume) and how many trials they hold.
PendingWork pendingScenes(const std::vector<SceneGraspList>& work,
                          const results::ResultsWriter& writer) {
  PendingWork pending;
  for (const auto& w : work) {
    const auto left = std::count_if(w.grasps.begin(), w.grasps.end(), [&](const RankedGrasp& j) {
      return !writer.contains(w.entry->id, j.request->method, j.request->id);
    });
    if (left == 0) continue;
    pending.scenes.push_back(&w);
    pending.progress.trialsTotal += static_cast<int>(left);
  }
  pending.progress.scenesTotal = static_cast<int>(pending.scenes.size());
  return pending;
}

/// The inputs run.csv records when `options` resumes a folder that has one.
std::optional<results::RunSources> previousSources(const RunOptions& options) {
  const fs::path file = options.out / results::kRunFileName;
  if (!options.resume || !fs::exists(file)) return std::nullopt;
  return results::parseRunFile(rw::common::readTextFileOrThrow(file), file.string()).sources;
}

/// A resumed folder's trials must come from the same database (run.csv's index hash; a run.csv
/// without one is not checked).
void checkSameDatabase(const RunOptions& options,
                       const std::optional<results::RunSources>& previous,
                       const results::RunSources& current) {
  if (!previous || previous->databaseHash.empty() ||
      previous->databaseHash == current.databaseHash) {
    return;
  }
  throw std::runtime_error(
      options.out.string() + " holds trials on a database whose index hash was " +
      previous->databaseHash + "; " + options.database.string() + " now has " +
      current.databaseHash + " (generated again or replaced): choose another folder");
}

/// A resumed folder's trials must come from the same engine with the same settings (a run.csv
/// without an engine record is ODE's). `current` gets the previous settings when this run
/// simulates nothing (it could not ask the engine).
void checkSameEngine(const RunOptions& options, const std::optional<results::RunSources>& previous,
                     results::RunSources& current) {
  if (!previous) return;
  const std::string before = previous->engine.empty() ? "ode" : previous->engine;
  if (before != options.engine) {
    throw std::runtime_error(options.out.string() + " holds trials of engine '" + before +
                             "'; this run is on engine '" + options.engine +
                             "': resume it with --engine " + before + " or choose another folder");
  }
  if (current.engineSettings.empty()) current.engineSettings = previous->engineSettings;
  if (!previous->engineSettings.empty() && previous->engineSettings != current.engineSettings) {
    throw std::runtime_error(options.out.string() + " holds trials of engine '" + before +
                             "' with the settings \"" + previous->engineSettings +
                             "\"; this run's are \"" + current.engineSettings +
                             "\": choose another folder");
  }
}

/// Writes run.csv with the plan's scenes, methods and rejected counts so far.
void writeRunFile(RunPlan& plan, results::ResultsWriter& writer) {
  plan.run.rejected.clear();
  for (const auto& [method, n] : plan.rejectedPerMethod) plan.run.rejected.emplace_back(method, n);
  writer.writeRun(plan.run);
}

/// A hand that does not fit (a missing dynamics file, a device or controller the scene's
/// dynamics lack) fails every scene: reported once, as the run's error, not per grasp. The probe
/// is the first pending scene, else (a finished run resumed) the run's first. Returns the
/// engine's settings in that scene (empty for a run without scenes).
std::string checkHandFits(const PendingWork& pending, const RunPlan& plan,
                          const session::SceneLoader& loader, const fs::path& handFile) {
  const SceneGraspList* scene = !pending.scenes.empty()      ? pending.scenes.front()
                                : !plan.order.scenes.empty() ? &plan.order.scenes.front()
                                                             : nullptr;
  if (scene == nullptr) return {};
  try {
    const SceneRunner probe(*scene, loader);
    return probe.engineSettings();
  } catch (const rw::common::LoadError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error("the hand " + handFile.string() + " cannot run in scene " +
                             scene->entry->id + ": " + e.what());
  }
}

/// What a scene reports per grasp done: the grasp, and its rejection if it was rejected as input.
using TrialDone = std::function<void(const grasp::GraspRequest&, const std::optional<Diagnostic>&)>;

/// Runs one scene's trials that are not in `writer` yet, appending each as it finishes;
/// `trialDone` gets each grasp done and its rejection if it was rejected as input (nullopt for
/// a trial). Returns false early, between trials, once `stopping` says so. A scene file that
/// cannot be read throws rw::common::LoadError; a scene the hand cannot be put in rejects its
/// grasps.
bool runScene(const SceneGraspList& w, const session::SceneLoader& loader,
              results::ResultsWriter& writer, const std::function<bool()>& stopping,
              const TrialDone& trialDone) {
  std::unique_ptr<SceneRunner> runner;
  std::string failure;
  try {
    runner = std::make_unique<SceneRunner>(w, loader);
  } catch (const rw::common::LoadError&) {
    throw;  // an unreadable or broken scene file: the run stops (and resumes once it is mended)
  } catch (const std::exception& e) {
    failure = e.what();
  }
  for (const RankedGrasp& job : w.grasps) {
    if (stopping()) return false;
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
    trialDone(r, record ? std::nullopt : std::optional<Diagnostic>(rejected));
  }
  return true;
}

/// Runs the pending scenes on options.threads workers (a scene per task), counting rejections
/// into `plan`. A set options.stop, or an error in any scene (a scene file that cannot be read,
/// a failed write), ends every scene after its current trial; no new scene starts; the first
/// error is thrown.
void runScenes(const RunOptions& options, const session::SceneLoader& loader, PendingWork& pending,
               RunPlan& plan, results::ResultsWriter& writer, const std::function<void()>& report) {
  std::mutex mutex;
  std::atomic<bool> failing{false};
  const auto stopping = [&] {
    return failing.load() || (options.stop != nullptr && options.stop->load());
  };
  const auto trialDone = [&](const grasp::GraspRequest& r,
                             const std::optional<Diagnostic>& rejected) {
    const std::lock_guard lock(mutex);
    if (rejected) {
      plan.rejected.push_back(*rejected);
      ++plan.rejectedPerMethod[r.method];
    }
    ++pending.progress.trialsDone;
    report();
  };
  const rw::common::TaskPool pool(
      std::min<int>(options.threads, static_cast<int>(pending.scenes.size())), options.stop);
  pool.run(pending.scenes.size(), [&](std::size_t i, int /*worker*/) {
    bool complete = false;
    try {
      complete = runScene(*pending.scenes[i], loader, writer, stopping, trialDone);
    } catch (...) {
      failing = true;
      throw;
    }
    if (!complete) return;
    const std::lock_guard lock(mutex);
    ++pending.progress.scenesDone;
    report();
  });
}

/// Rewrites run.csv with the final rejected counts, puts trials.csv in canonical order and sums
/// the run up.
RunSummary finishRun(RunPlan& plan, results::ResultsWriter& writer) {
  writeRunFile(plan, writer);
  writer.finalize();
  RunSummary summary;
  summary.resumed = static_cast<int>(writer.resumedCount());
  for (const auto& t : writer.trials()) {
    ++summary.outcomes[std::string(rwsim::trial::outcomeName(t.outcome))];
    ++summary.trials;
  }
  summary.trials -= summary.resumed;
  summary.scenes = static_cast<int>(plan.run.scenes.size());
  summary.methods = static_cast<int>(plan.run.methods.size());
  summary.rejected = std::move(plan.rejected);
  std::stable_sort(summary.rejected.begin(), summary.rejected.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     return std::tie(a.file, a.line) < std::tie(b.file, b.line);
                   });
  return summary;
}

}  // namespace

std::string unknownSceneReason(const database::Database& db, const std::string& sceneId) {
  const auto close = db.closestIds(sceneId);
  return "unknown scene \"" + sceneId + "\"" +
         (close.empty() ? "" : " (did you mean " + close.front() + "?)");
}

RunSummary runBenchmark(const RunOptions& options,
                        const std::function<void(const RunProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  if (options.shard) {
    checkShardSpec(*options.shard);
  } else if (options.resume && fs::exists(options.out / kShardRecordFileName)) {
    // A shard's folder resumed as a whole run would mix the two.
    const ShardSpec s = readShardRecord(options.out).shard;
    throw std::runtime_error(options.out.string() + " holds " + describe(s) +
                             " of a run; resume it with --shard " + std::to_string(s.index) +
                             " --of " + std::to_string(s.count));
  }
  const RunInputs in = openInputs(options);
  // After openInputs: the loader keeps the address of in.db.
  const session::SceneLoader loader(in.db, *in.hand, options.engine);
  const std::optional<results::RunSources> previous = previousSources(options);
  RunPlan plan = planRun(options, in);
  std::optional<ShardRecord> shard;
  if (options.shard) {
    restrictToShard(plan, *options.shard);
    shard = startShard(options);
  }
  results::ResultsWriter writer(options.out);
  PendingWork pending = pendingScenes(plan.order.scenes, writer);
  plan.run.sources.engineSettings = checkHandFits(pending, plan, loader, options.hand);
  checkSameDatabase(options, previous, plan.run.sources);
  checkSameEngine(options, previous, plan.run.sources);
  writeRunFile(plan, writer);
  runScenes(options, loader, pending, plan, writer, [&] {
    pending.progress.elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(pending.progress);
  });
  if (pending.progress.trialsDone < pending.progress.trialsTotal) {
    // Only a stop request leaves trials undone (errors throw): trials.csv keeps the finished
    // ones in the order they finished; --resume runs the rest and puts them in order.
    throw rw::common::StopRequested(
        "stopped after " + std::to_string(pending.progress.trialsDone) + " of " +
        std::to_string(pending.progress.trialsTotal) + " trials; the finished ones are in " +
        (options.out / results::kTrialsFileName).string() + "; --resume continues the run");
  }
  RunSummary summary = finishRun(plan, writer);
  if (shard) {
    finishShard(options.out, *shard, static_cast<std::size_t>(summary.trials + summary.resumed));
  }
  return summary;
}

}  // namespace visgrab::runner
