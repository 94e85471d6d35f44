#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "visgrab/runner/shard_plan.hpp"

namespace visgrab::database {
class Database;
}  // namespace visgrab::database

/// The headless benchmark run: every grasp of every scene through the simulator.
namespace visgrab::runner {

/// What `visgrab run` needs.
struct RunOptions {
  /// A generated database folder or an original VisGraB manifest.
  std::filesystem::path database;
  /// Grasp files or folders of grasp files (any format taskio reads).
  std::vector<std::filesystem::path> grasps;
  /// The result folder (trials.csv, run.csv).
  std::filesystem::path out;
  /// The hand: its grasp description (e.g. scenes/hands/sdh/sdh.grasp.xml) or its folder
  /// (scenes/hands/pg70); see session::SceneLoader.
  std::filesystem::path hand;
  /// The physics engine ("ode", the default and the benchmark's; "mujoco" when built with it;
  /// rwsim::engines). Recorded in run.csv with its settings; resuming a folder of another
  /// engine is an error.
  std::string engine = "ode";
  /// ODE's integration step instead of each scene's own (`--dt`; session::SceneLoader::
  /// setTimeStep), for the time-step study; recorded in run.csv's engine settings.
  std::optional<double> timeStep;
  /// The trial protocol's XML file (`--protocol`; rwsim::trial::loadTrialProtocol); empty: the
  /// paper's lift. A protocol other than the lift is recorded in run.csv (its name and hash);
  /// resuming a folder of another protocol is an error.
  std::filesystem::path protocol;
  /// Only the scenes this filter selects (docs/database-format.md); empty: all.
  std::string scenes;
  /// Worker threads (each runs whole scenes; the results do not depend on the count).
  int threads = 1;
  /// Continue an interrupted run in `out` (without it, an existing trials.csv is an error).
  bool resume = false;
  /// Runs per grasp (`--repeats N`): repeat 0 is the unperturbed trial, repeats 1..N-1 run under
  /// seeded perturbations drawn from the noise model (docs/noise-model.md). 1: no repeats, the
  /// files exactly as without the option. N > 1: trials.csv gains the repeat and seed columns,
  /// run.csv the repeats and noise records, and grasps.csv (results::writeGraspSummary) is
  /// written beside them.
  int repeats = 1;
  /// The noise model's XML file (`--noise FILE`); empty: defaultNoiseModel(). Needs repeats > 1.
  std::filesystem::path noise;
  /// The base of the repeats' seeds (`--seed`): repeat r >= 1 of a grasp draws from
  /// repeatSeed(noiseSeed, scene, method, grasp id, r).
  std::uint64_t noiseSeed = 1;
  /// Stop repeating a grasp once its first repeats agree (`--adaptive`; the rule of
  /// results::repeatsToDecide with adaptiveAlpha and adaptiveMargin); a grasp whose repeats
  /// disagree runs all N. Needs repeats > 1.
  bool adaptive = false;
  /// The adaptive rule's error rate.
  double adaptiveAlpha = 0.05;
  /// The adaptive rule's margin: a grasp with P <= 1 - margin is declared always held with
  /// probability at most adaptiveAlpha (and P >= margin never held).
  double adaptiveMargin = 0.65;
  /// Run only this shard of the work (planShards over the selected scenes' grasp counts): its
  /// scenes in run.csv and trials.csv, and `out`/shard.txt (shard_record.hpp) saying which
  /// shard of which run it is, "running" until the shard has finished. The first shard also
  /// counts the grasps rejected before any scene runs (unparsable, unknown scene), so that
  /// mergeShards sums every rejection once. Nullopt: the whole run.
  std::optional<ShardSpec> shard;
  /// Set (by a SIGINT/SIGTERM handler, say: rw::common::catchStopSignals) to stop early: the
  /// running trials finish and are written, no new one starts, and runBenchmark throws
  /// rw::common::StopRequested; `resume` completes the run later. Null: never. Must outlive the
  /// call.
  const std::atomic<bool>* stop = nullptr;
};

/// Progress after each finished trial.
struct RunProgress {
  /// Scenes finished (all their grasps done).
  int scenesDone = 0;
  /// Scenes with grasps to run.
  int scenesTotal = 0;
  /// Trials finished in this run.
  std::int64_t trialsDone = 0;
  /// Trials this run has to do (without those found done when resuming).
  std::int64_t trialsTotal = 0;
  /// Seconds since the run started.
  double elapsed = 0.0;
};

/// What a run did.
struct RunSummary {
  /// Trials simulated (or classified as invalid contacts) in this run.
  int trials = 0;
  /// Trials found already done in `out` (resume).
  int resumed = 0;
  /// Grasps rejected before simulation: malformed input, unknown scenes or pre-shapes.
  std::vector<rw::common::Diagnostic> rejected;
  /// Trials per outcome name, this run and resumed together.
  std::map<std::string, int> outcomes;
  /// Scenes of the run and methods seen.
  int scenes = 0;
  /// Scenes of the run with a trial (this run's or resumed); the analyses count the others as
  /// scenes where a method suggested no grasp.
  int scenesWithTrials = 0;
  /// See scenes.
  int methods = 0;
};

/// Runs every grasp of `options.grasps` on its scene of the database, in `threads` worker
/// threads (rw::common::TaskPool, a scene per task), writing each finished trial to
/// out/trials.csv at once (so a killed run loses nothing and `resume` continues it), then
/// out/run.csv and the trials in canonical order. A failed write (disk full, the folder
/// deleted) or a scene file that cannot be read stops the run: the other workers finish their
/// current trial (written), no new one starts, and the first error is thrown; `resume` then
/// gives the same files as an uninterrupted run.
/// Per-grasp problems (bad input, unknown scene, unknown pre-shape) are rejected with a
/// diagnostic and counted in run.csv (per method; grasps the reader could not parse under their
/// file's name); the other grasps run. Deterministic whatever the thread count.
/// @throws rw::common::LoadError for an unreadable database, grasp file, hand description or
/// scene file, rw::common::WriteError (file and reason) for a failed write,
/// rw::common::StopRequested when options.stop ended the run early, std::runtime_error for an
/// existing result folder without `resume`, a result folder resumed with another engine or other
/// engine settings than its run.csv records, a shard folder of another shard or run, or a shard
/// folder resumed without `shard`,
/// std::invalid_argument for a shard outside 1..count, an engine this build lacks, repeats < 1,
/// a noise file or adaptive rule without repeats, or an adaptive alpha or margin outside (0, 1),
/// rw::common::LoadError (file:line) for a bad noise file.
RunSummary runBenchmark(const RunOptions& options,
                        const std::function<void(const RunProgress&)>& progress = {});

/// The seed of repeat `repeat` (>= 1) of a grasp: results::deriveSeed of `base`, the scene id,
/// method and grasp id (one text joined by line feeds) and the repeat, shifted right by one (63
/// bits, so that Python reads it as an int64).
std::uint64_t repeatSeed(std::uint64_t base, const std::string& scene, const std::string& method,
                         const std::string& graspId, int repeat);

/// Why a grasp of scene `sceneId`, which `db` does not hold, is rejected: "unknown scene \"ID\""
/// and the closest id as a "did you mean" (the runner's words; the Python module's check before a
/// run uses them too).
std::string unknownSceneReason(const database::Database& db, const std::string& sceneId);

}  // namespace visgrab::runner
