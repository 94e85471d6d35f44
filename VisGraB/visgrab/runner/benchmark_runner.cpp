#include "visgrab/runner/benchmark_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>

#include "rw/common/stop_signals.hpp"
#include "rw/common/task_pool.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/write_error.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/grasp_summary.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/results_writer.hpp"
#include "visgrab/results/statistics.hpp"
#include "visgrab/results/trial_columns.hpp"
#include "visgrab/runner/noise_model.hpp"
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

/// How the run repeats each grasp (RunOptions::repeats and the rest, checked and loaded).
struct RepeatPlan {
  /// Runs per grasp (1: none).
  int count = 1;
  /// The perturbations of repeats 1..count-1.
  NoiseModel noise;
  /// RunOptions::noiseSeed.
  std::uint64_t seed = 1;
  /// Adaptive: a grasp whose unperturbed trial and first decideAfter perturbed trials agree is
  /// decided; 0: every grasp runs all.
  int decideAfter = 0;
  /// What run.csv records.
  results::RunRepeats record;
};

RepeatPlan planRepeats(const RunOptions& options) {
  if (options.repeats < 1 || options.repeats > results::kMaxRepeats) {
    throw std::invalid_argument("repeats must be between 1 and " +
                                std::to_string(results::kMaxRepeats) + ", not " +
                                std::to_string(options.repeats));
  }
  RepeatPlan plan;
  plan.count = options.repeats;
  plan.seed = options.noiseSeed;
  if (options.repeats == 1) {
    if (!options.noise.empty()) {
      throw std::invalid_argument("a noise model (" + options.noise.string() +
                                  ") needs repeats: give --repeats N with N > 1");
    }
    if (options.adaptive) throw std::invalid_argument("adaptive repeats need --repeats N, N > 1");
    return plan;
  }
  plan.noise = options.noise.empty() ? defaultNoiseModel() : loadNoiseModel(options.noise);
  plan.record.count = options.repeats;
  plan.record.noise = describe(plan.noise) + "; seed " + std::to_string(options.noiseSeed);
  if (options.adaptive) {
    plan.decideAfter = results::repeatsToDecide(options.adaptiveAlpha, options.adaptiveMargin);
    const int needed =
        results::minimumAdaptiveRepeats(options.adaptiveAlpha, options.adaptiveMargin);
    if (options.repeats < needed) {
      throw std::invalid_argument(
          "the adaptive rule (alpha " + results::formatDouble(options.adaptiveAlpha) + ", margin " +
          results::formatDouble(options.adaptiveMargin) + ") decides after " +
          std::to_string(plan.decideAfter) + " agreeing perturbed trials, so with " +
          std::to_string(options.repeats) + " repeats it never stops a grasp early: give " +
          "--repeats " + std::to_string(needed) + " or more, or a larger margin");
    }
    plan.record.adaptive = "stop when the unperturbed and " + std::to_string(plan.decideAfter) +
                           " perturbed trials agree (alpha " +
                           results::formatDouble(options.adaptiveAlpha) + ", margin " +
                           results::formatDouble(options.adaptiveMargin) + ")";
  }
  return plan;
}

/// A run with repeats writes out/grasps.csv at its end: refuses a grasp file of that path, which
/// the summary would overwrite (the run's own input, named in run.csv).
void checkSummaryIsNoInput(const RunOptions& options, const RepeatPlan& plan) {
  if (!plan.record.repeated()) return;
  std::error_code ec;
  const fs::path summary = fs::weakly_canonical(options.out / results::kGraspsFileName, ec);
  for (const fs::path& source : options.grasps) {
    if (!ec && fs::weakly_canonical(source, ec) == summary && !ec) {
      throw std::runtime_error("the grasp file " + source.string() + " is where a run with " +
                               "repeats writes its per-grasp summary (" +
                               std::string(results::kGraspsFileName) +
                               "): move the grasps or choose another --out folder");
    }
  }
}

/// True when the adaptive rule has decided a grasp whose first trials held as `held` says: the
/// unperturbed trial (repeat 0, not a random draw) and decideAfter perturbed ones all agree, so
/// that the rule's error rate is that of the perturbed trials alone (repeatsToDecide).
bool decided(const RepeatPlan& plan, const std::vector<bool>& held) {
  if (plan.decideAfter == 0 || static_cast<int>(held.size()) < 1 + plan.decideAfter) return false;
  return std::all_of(held.begin(), held.end(), [&](bool h) { return h == held.front(); });
}

/// Runs one scene's pending grasps in its session; appends each trial as it finishes.
class SceneRunner {
 public:
  SceneRunner(const SceneGraspList& work, const session::SceneLoader& loader)
      : work_(&work), session_(loader, *work.entry) {
    // The bodies the physics variation's mass scale applies to: the same objects move.
    for (const auto& body : session_.dynamicWorkcell().bodies()) {
      if (rwsim::trial::isVariedObject(body)) objects_.push_back(body.frame);
    }
  }

  /// The engine's version and settings in this scene (EngineFactory::settings()).
  std::string engineSettings() const { return session_.trial().engine().settings(); }

  /// The grasp as the benchmark places it (once per grasp, whatever its repeats).
  grasp::ResolvedGrasp resolve(const RankedGrasp& job) const {
    return session_.resolve(*job.request);
  }

  /// The trial record of repeat `repeat` of `job`, resolved as `resolved` (not an input error).
  results::TrialRecord run(const RankedGrasp& job, const grasp::ResolvedGrasp& resolved, int repeat,
                           const RepeatPlan& plan) const {
    const grasp::GraspRequest& r = *job.request;
    results::TrialRecord record;
    record.sceneId = work_->entry->id;
    record.conditions = work_->entry->conditions;
    record.method = r.method;
    record.graspId = r.id;
    record.rank = job.rank;
    record.repeat = repeat;
    record.seed = repeat == 0 ? 0 : repeatSeed(plan.seed, record.sceneId, r.method, r.id, repeat);
    // Nothing to simulate: the contact IK found no configuration (whatever the perturbation), or
    // the placement search no collision-free placement (the message gives the least
    // penetration; a perturbed repeat tries its placement in the trial).
    const bool inCollision = resolved.status == grasp::ResolveStatus::kInCollision;
    if (resolved.status == grasp::ResolveStatus::kInvalidContacts || (inCollision && repeat == 0)) {
      record.outcome = inCollision ? GraspOutcome::kInCollision : GraspOutcome::kInvalidContacts;
      record.detail = resolved.message;
      return record;
    }
    rwsim::simulator::GraspTrialResult result;
    if (repeat == 0) {
      result = session_.trial().run(resolved.parameters, session_.initialState());
    } else {
      const Perturbation p = samplePerturbation(plan.noise, record.seed);
      rwsim::simulator::GraspParameters grasp = resolved.parameters;
      grasp.X_W_tcp = grasp.X_W_tcp * p.X_tcp_perturbed;
      rwsim::trial::PhysicsVariation variation;
      variation.frictionScale = p.frictionScale;
      variation.objectMassScale = p.massScale;
      result = session_.trial().run(grasp, perturbedState(p), variation);
    }
    results::recordResult(result, objectIdOf(session_.dynamicWorkcell(), result.object), record);
    if (resolved.placement && resolved.placement->tests > 1) {
      record.detail += "; " + resolved.placement->describe();
    }
    return record;
  }

 private:
  /// The scene's initial state with every object moved by the perturbation's planar motion
  /// (about the vertical through the mean of the objects' origins), so that they stay on the
  /// table and keep their places relative to each other.
  rw::kinematics::State perturbedState(const Perturbation& p) const {
    rw::kinematics::State state = session_.initialState();
    if (objects_.empty() || (p.objectDx == 0.0 && p.objectDy == 0.0 && p.objectYaw == 0.0)) {
      return state;
    }
    const auto& tree = session_.workcell().frames();
    const rw::kinematics::FKTable fk(tree, state);
    rw::math::Vector3D centre = rw::math::Vector3D::Zero();
    for (const auto frame : objects_) centre += fk.worldTransform(frame).translation();
    centre /= static_cast<double>(objects_.size());
    centre.z() = 0.0;
    const rw::math::Transform3D motion =
        Eigen::Translation3d(centre + rw::math::Vector3D(p.objectDx, p.objectDy, 0.0)) *
        Eigen::AngleAxisd(p.objectYaw, rw::math::Vector3D::UnitZ()) * Eigen::Translation3d(-centre);
    for (const auto frame : objects_) {
      const auto& f = tree.frame(frame);
      const rw::math::Transform3D X_W_parent = fk.worldTransform(f.parent());
      f.setMovableTransform(state, X_W_parent.inverse() * motion * fk.worldTransform(frame));
    }
    return state;
  }

  const SceneGraspList* work_;
  session::SceneSession session_;
  std::vector<rw::kinematics::FrameId> objects_;
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

/// The scenes with trials not yet in `writer` (resume) and how many trials they hold (every
/// repeat not yet run; the adaptive rule may leave some out later).
PendingWork pendingScenes(const std::vector<SceneGraspList>& work,
                          const results::ResultsWriter& writer, int repeats) {
  PendingWork pending;
  for (const auto& w : work) {
    std::ptrdiff_t left = 0;
    for (const RankedGrasp& j : w.grasps) {
      for (int k = 0; k < repeats; ++k) {
        left += writer.contains(w.entry->id, j.request->method, j.request->id, k) ? 0 : 1;
      }
    }
    if (left == 0) continue;
    pending.scenes.push_back(&w);
    pending.progress.trialsTotal += static_cast<std::int64_t>(left);
  }
  pending.progress.scenesTotal = static_cast<int>(pending.scenes.size());
  return pending;
}

/// What run.csv records when `options` resumes a folder that has one.
std::optional<results::RunResults> previousRun(const RunOptions& options) {
  const fs::path file = options.out / results::kRunFileName;
  if (!options.resume || !fs::exists(file)) return std::nullopt;
  return results::parseRunFile(rw::common::readTextFileOrThrow(file), file.string());
}

/// A resumed folder's trials must have been repeated in the same way (count, noise, seed, rule).
void checkSameRepeats(const RunOptions& options, const std::optional<results::RunResults>& previous,
                      const results::RunRepeats& current) {
  if (!previous || previous->repeats == current) return;
  const auto what = [](const results::RunRepeats& r) {
    if (!r.repeated()) return std::string("no repeats");
    return std::to_string(r.count) + " repeats (" + r.noise +
           (r.adaptive.empty() ? "" : "; adaptive: " + r.adaptive) + ")";
  };
  throw std::runtime_error(options.out.string() + " holds trials of a run with " +
                           what(previous->repeats) + "; this run has " + what(current) +
                           ": resume it with the same options or choose another folder");
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

/// A resumed folder must cover the same scenes (the same --scenes selection of the same
/// database): resuming with another selection would widen or narrow the run the analyses read.
void checkSameScenes(const RunOptions& options, const std::optional<results::RunResults>& previous,
                     const std::vector<results::RunScene>& current) {
  if (!previous || previous->scenes.empty()) return;
  const auto sameIds = [](const results::RunScene& a, const results::RunScene& b) {
    return a.id == b.id;
  };
  if (std::equal(previous->scenes.begin(), previous->scenes.end(), current.begin(), current.end(),
                 sameIds)) {
    return;
  }
  throw std::runtime_error(
      options.out.string() + " holds a run of " + std::to_string(previous->scenes.size()) +
      " scenes; this run selects " + std::to_string(current.size()) +
      (options.scenes.empty() ? " (no --scenes)" : " (--scenes " + options.scenes + ")") +
      ": resume it with the --scenes it was started with, or choose another folder");
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

/// The run's protocol (RunOptions::protocol loaded; the lift without one), and its run.csv records
/// in `sources` (name, hash and file; none for the lift).
rwsim::trial::TrialProtocol loadProtocol(const RunOptions& options, results::RunSources& sources) {
  if (options.protocol.empty()) return rwsim::trial::TrialProtocol::lift();
  rwsim::trial::TrialProtocol protocol = rwsim::trial::loadTrialProtocol(options.protocol);
  try {
    rwsim::trial::checkProtocol(protocol);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(options.protocol.string() + ": " + e.what());
  }
  if (!protocol.isLift()) {
    sources.protocol = protocol.name;
    sources.protocolHash = rwsim::trial::protocolHash(protocol);
    sources.protocolFile = fs::absolute(options.protocol).lexically_normal();
  }
  return protocol;
}

/// A resumed folder's trials must come from the same protocol (run.csv's protocol records; none:
/// the lift).
void checkSameProtocol(const RunOptions& options,
                       const std::optional<results::RunSources>& previous,
                       const results::RunSources& current) {
  if (!previous ||
      (previous->protocol == current.protocol && previous->protocolHash == current.protocolHash)) {
    return;
  }
  const auto what = [](const results::RunSources& s) {
    return s.protocol.empty() ? std::string("the lift protocol (the default)")
                              : "protocol '" + s.protocol + "' (hash " + s.protocolHash + ")";
  };
  throw std::runtime_error(options.out.string() + " holds trials of " + what(*previous) +
                           "; this run has " + what(current) +
                           ": resume it with the same --protocol or choose another folder");
}

/// Writes run.csv with the plan's scenes, methods and rejected counts so far.
void writeRunFile(RunPlan& plan, results::ResultsWriter& writer) {
  plan.run.rejected.clear();
  for (const auto& [method, n] : plan.rejectedPerMethod) plan.run.rejected.emplace_back(method, n);
  writer.writeRun(plan.run);
}

/// The scene a fresh run of the whole work (every shard) probes first: its first scene with
/// grasps, else its first scene; null for a run without scenes.
std::optional<SceneGraspList> wholeRunProbe(const RunPlan& plan) {
  for (const SceneGraspList& s : plan.order.scenes) {
    if (!s.grasps.empty()) return SceneGraspList{s.entry, {}};
  }
  if (plan.order.scenes.empty()) return std::nullopt;
  return SceneGraspList{plan.order.scenes.front().entry, {}};
}

/// A hand that does not fit (a missing dynamics file, a device or controller the scene's
/// dynamics lack) fails every scene: reported once, as the run's error, not per grasp. The probe
/// is the first pending scene, else (a finished run resumed, a shard without grasps or without
/// scenes) `wholeRun`, the scene a fresh run of the whole work probes: so a shard without work
/// records the engine settings that the other shards and one run of the whole work record, and
/// fails, as they do, for a hand that cannot run. Returns the engine's settings in that scene
/// (empty for a run without scenes).
std::string checkHandFits(const PendingWork& pending, const std::optional<SceneGraspList>& wholeRun,
                          const session::SceneLoader& loader, const fs::path& handFile) {
  const SceneGraspList* scene = !pending.scenes.empty() ? pending.scenes.front()
                                : wholeRun              ? &*wholeRun
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

/// What a scene reports: a trial done (with the grasp's rejection if it was rejected as input,
/// nullopt for a trial), and trials the run will not do after all (`skipped`: repeats the
/// adaptive rule left out, or the repeats of a rejected grasp).
struct SceneReport {
  std::function<void(const grasp::GraspRequest&, const std::optional<Diagnostic>&)> trialDone;
  std::function<void(int skipped)> skipped;
};

/// Runs one scene's trials that are not in `writer` yet (each grasp's repeats in order),
/// appending each as it finishes. Returns false early, between trials, once `stopping` says so.
/// A scene file that cannot be read throws rw::common::LoadError; a scene the hand cannot be put
/// in rejects its grasps.
bool runScene(const SceneGraspList& w, const session::SceneLoader& loader, const RepeatPlan& plan,
              results::ResultsWriter& writer, const std::function<bool()>& stopping,
              const SceneReport& report) {
  std::unique_ptr<SceneRunner> runner;
  std::string failure;
  try {
    runner = std::make_unique<SceneRunner>(w, loader);
  } catch (const rw::common::LoadError&) {
    throw;  // an unreadable or broken scene file: the run stops (and resumes once it is mended)
  } catch (const std::exception& e) {
    failure = e.what();
  }
  const std::string& scene = w.entry->id;
  for (const RankedGrasp& job : w.grasps) {
    const auto& r = *job.request;
    std::vector<bool> held;
    std::optional<grasp::ResolvedGrasp> resolved;
    for (int k = 0; k < plan.count; ++k) {
      if (decided(plan, held)) {
        int left = 0;
        for (int rest = k; rest < plan.count; ++rest) {
          left += writer.contains(scene, r.method, r.id, rest) ? 0 : 1;
        }
        report.skipped(left);
        break;
      }
      if (const auto done = writer.outcomeOf(scene, r.method, r.id, k)) {
        held.push_back(results::isSuccess(*done));
        continue;
      }
      if (stopping()) return false;
      if (!resolved) {
        resolved = runner ? runner->resolve(job) : grasp::ResolvedGrasp{};
        if (!runner) {
          resolved->reason = "scene " + scene + " cannot be simulated: " + failure;
        }
      }
      if (resolved->status == grasp::ResolveStatus::kInputError) {
        report.trialDone(r, rejection(r, resolved->reason));
        report.skipped(plan.count - 1);
        break;
      }
      const results::TrialRecord record = runner->run(job, *resolved, k, plan);
      writer.append(record);
      held.push_back(results::isSuccess(record.outcome));
      report.trialDone(r, std::nullopt);
    }
  }
  return true;
}

/// Runs the pending scenes on options.threads workers (a scene per task), counting rejections
/// into `plan`. A set options.stop, or an error in any scene (a scene file that cannot be read,
/// a failed write), ends every scene after its current trial; no new scene starts; the first
/// error is thrown.
void runScenes(const RunOptions& options, const session::SceneLoader& loader,
               const RepeatPlan& repeats, PendingWork& pending, RunPlan& plan,
               results::ResultsWriter& writer, const std::function<void()>& report) {
  std::mutex mutex;
  std::atomic<bool> failing{false};
  const auto stopping = [&] {
    return failing.load() || (options.stop != nullptr && options.stop->load());
  };
  SceneReport sceneReport;
  sceneReport.trialDone = [&](const grasp::GraspRequest& r,
                              const std::optional<Diagnostic>& rejected) {
    const std::lock_guard lock(mutex);
    if (rejected) {
      plan.rejected.push_back(*rejected);
      ++plan.rejectedPerMethod[r.method];
    }
    ++pending.progress.trialsDone;
    report();
  };
  sceneReport.skipped = [&](int skipped) {
    const std::lock_guard lock(mutex);
    pending.progress.trialsTotal -= skipped;
  };
  const rw::common::TaskPool pool(
      std::min<int>(options.threads, static_cast<int>(pending.scenes.size())), options.stop);
  pool.run(pending.scenes.size(), [&](std::size_t i, int /*worker*/) {
    bool complete = false;
    try {
      complete = runScene(*pending.scenes[i], loader, repeats, writer, stopping, sceneReport);
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

/// Rewrites run.csv with the final rejected counts, puts trials.csv in canonical order, writes
/// grasps.csv for a run with repeats and sums the run up.
RunSummary finishRun(RunPlan& plan, results::ResultsWriter& writer) {
  writeRunFile(plan, writer);
  writer.finalize();
  if (plan.run.repeats.repeated()) {
    results::RunResults run = plan.run;
    run.trials = writer.trials();
    results::writeGraspSummary(writer.dir(), run);
  }
  RunSummary summary;
  summary.resumed = static_cast<int>(writer.resumedCount());
  std::set<std::string> scenesWithTrials;
  for (const auto& t : writer.trials()) {
    ++summary.outcomes[std::string(rwsim::trial::outcomeName(t.outcome))];
    ++summary.trials;
    scenesWithTrials.insert(t.sceneId);
  }
  summary.scenesWithTrials = static_cast<int>(scenesWithTrials.size());
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

std::uint64_t repeatSeed(std::uint64_t base, const std::string& scene, const std::string& method,
                         const std::string& graspId, int repeat) {
  const std::uint64_t grasp = results::deriveSeed(base, scene + "\n" + method + "\n" + graspId);
  return results::deriveSeed(grasp, static_cast<std::uint64_t>(repeat)) >> 1U;
}

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
  const RepeatPlan repeats = planRepeats(options);
  checkSummaryIsNoInput(options, repeats);
  const RunInputs in = openInputs(options);
  // After openInputs: the loader keeps the address of in.db.
  session::SceneLoader loader(in.db, *in.hand, options.engine);
  loader.setTimeStep(options.timeStep);
  results::RunSources protocolRecord;
  loader.setProtocol(loadProtocol(options, protocolRecord));
  const std::optional<results::RunResults> previousRecord = previousRun(options);
  checkSameRepeats(options, previousRecord, repeats.record);
  const std::optional<results::RunSources> previous =
      previousRecord ? std::optional(previousRecord->sources) : std::nullopt;
  RunPlan plan = planRun(options, in);
  plan.run.repeats = repeats.record;
  plan.run.sources.protocol = protocolRecord.protocol;
  plan.run.sources.protocolHash = protocolRecord.protocolHash;
  plan.run.sources.protocolFile = protocolRecord.protocolFile;
  std::optional<ShardRecord> shard;
  const std::optional<SceneGraspList> wholeRun = wholeRunProbe(plan);
  if (options.shard) {
    restrictToShard(plan, *options.shard);
    shard = startShard(options);
  }
  results::ResultsWriter::Options writerOptions;
  writerOptions.repeated = repeats.record.repeated();
  // A new folder is marked before the writer makes its trials.csv: checks below that fail leave
  // a folder that says it holds no finished run.
  if (!fs::exists(options.out / results::kTrialsFileName)) {
    std::error_code made;
    fs::create_directories(options.out, made);
    if (made) throw rw::common::WriteError(options.out, made);
    results::markUnfinished(options.out);
  }
  results::ResultsWriter writer(options.out, writerOptions);
  PendingWork pending = pendingScenes(plan.order.scenes, writer, repeats.count);
  plan.run.sources.engineSettings = checkHandFits(pending, wholeRun, loader, options.hand);
  checkSameScenes(options, previousRecord, plan.run.scenes);
  checkSameDatabase(options, previous, plan.run.sources);
  checkSameEngine(options, previous, plan.run.sources);
  checkSameProtocol(options, previous, plan.run.sources);
  // From here the folder holds part of a run until finishRun has written it whole; a refused
  // resume above leaves its folder without the mark it did not have.
  results::markUnfinished(options.out);
  writeRunFile(plan, writer);
  runScenes(options, loader, repeats, pending, plan, writer, [&] {
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
  results::markFinished(options.out);
  if (shard) {
    finishShard(options.out, *shard, static_cast<std::size_t>(summary.trials + summary.resumed));
  }
  return summary;
}

}  // namespace visgrab::runner
