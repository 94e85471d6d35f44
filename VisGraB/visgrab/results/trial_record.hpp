#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rwsim/trial/grasp_outcome.hpp"
#include "visgrab/database/scene_set.hpp"

/// Results of a benchmark run: one record per simulated (or rejected) grasp.
namespace visgrab::results {

/// What happened to one grasp of one scene.
struct TrialRecord {
  /// Scene id (our spelling, e.g. "textured/single/cocacola/03").
  std::string sceneId;
  /// The scene's conditions (nullopt for an original-database scene whose conditions are unknown).
  std::optional<database::SceneConditions> conditions;
  /// What the analyses compare: the grasp type or the grasp file's name.
  std::string method;
  /// The grasp's id within its scene and method.
  std::string graspId;
  /// Position of the grasp among its scene's grasps of this method, 0-based, in the order the
  /// user gave them (the analyses' "attempts").
  int rank = 0;
  /// Which run of the grasp this is (`visgrab run --repeats N`): 0 is the unperturbed trial (the
  /// paper's analyses use it alone), 1..N-1 ran under seeded perturbations (Part 17's noise
  /// model). Only a repeated run writes the repeat and seed columns.
  int repeat = 0;
  /// The seed of the repeat's perturbation, below 2^63 (0 for repeat 0: none).
  std::uint64_t seed = 0;
  /// Outcome (kInvalidContacts when the grasp utilities rejected the contacts).
  rwsim::trial::GraspOutcome outcome = rwsim::trial::GraspOutcome::kSimulationFailure;
  /// Paper eq. 5 (0 unless held).
  double qLift = 0.0;
  /// Paper eq. 6-7 as the paper's tables computed it: cones on the measured contact forces (0
  /// unless held; GraspTrialResult::qGws); NaN (not computed) when read from a version 1
  /// trials.csv, whose q_gws column was the unit-force value (now qGwsUnit).
  double qGws = 0.0;
  /// Unit normal forces on the contact normals (0 unless held; GraspTrialResult::qGwsUnit).
  double qGwsUnit = 0.0;
  /// Id (1..18) of the object the hand held or touched most (in a pair: the one grasped, as the
  /// paper reports "the object closest to the hand"); 0 when no object was touched.
  int object = 0;
  /// Simulated time, s.
  double simulatedTime = 0.0;
  /// The closing ran into the trial's closing time limit with the fingers still moving: the grasp
  /// was judged as it stood (GraspTrialResult::closingCapped).
  bool closingCapped = false;
  /// Free text (failure details).
  std::string detail;
};

/// True for the outcomes the paper counts as a successful grasp (§2.4: "stable grasp" or
/// "object slipped": the object is in the hand after lifting).
inline bool isSuccess(rwsim::trial::GraspOutcome outcome) { return rwsim::trial::isHeld(outcome); }

/// A scene that was part of a run, with or without grasps (a method that suggests no grasp for
/// a scene is part of the analyses: the paper's grey "no grasp suggested" share).
struct RunScene {
  /// Scene id.
  std::string id;
  /// Conditions (nullopt when unknown).
  std::optional<database::SceneConditions> conditions;
};

/// Where a run's input came from (absolute paths, as the run saw them): what a tool needs to
/// simulate one of its trials again, e.g. to draw it (`visgrab render --results`).
struct RunSources {
  /// The scene database (folder or original manifest); empty if unknown.
  std::filesystem::path database;
  /// database::indexHash of the database when the run started (16 hex digits); empty if
  /// unknown (runs before the record). Replays check it: a database generated again or replaced
  /// at the same path is an error, not a wrong picture.
  std::string databaseHash;
  /// The grasp files or folders.
  std::vector<std::filesystem::path> grasps;
  /// The hand's grasp description; empty if unknown.
  std::filesystem::path hand;
  /// The physics engine the trials ran on ("ode", "mujoco"; empty in files older than the
  /// record: those runs were ODE's).
  std::string engine;
  /// The engine's version and settings (EngineFactory::settings()); empty if unknown.
  std::string engineSettings;
  /// The trial protocol's name (`visgrab run --protocol`); empty for the paper's lift (the
  /// default: run.csv then has no protocol records).
  std::string protocol;
  /// rwsim::trial::protocolHash of the protocol (16 hex digits); empty for the lift.
  std::string protocolHash;
  /// The protocol's file as the run was given it (absolute); empty for the lift and in files
  /// older than the record. Replays fall back on it when the data folder has no protocol of the
  /// recorded name and hash (results::replayProtocol).
  std::filesystem::path protocolFile;
};

/// How a run repeated its grasps (`visgrab run --repeats N`; run.csv's repeats, noise and
/// adaptive records, written only when count > 1).
struct RunRepeats {
  /// Runs per grasp: repeat 0 unperturbed, 1..count-1 perturbed (1: no repeats).
  int count = 1;
  /// The noise model of the perturbed repeats (runner::describe of it; empty without repeats).
  std::string noise;
  /// The adaptive stopping rule (runner's description of it; empty: every grasp runs all
  /// count repeats).
  std::string adaptive;
  /// True when the run repeats its grasps (count > 1).
  bool repeated() const { return count > 1; }
  /// Same count, noise and rule.
  bool operator==(const RunRepeats&) const = default;
};

/// Everything a run produced: the analyses' input.
struct RunResults {
  /// The scenes the run covered, in database order.
  std::vector<RunScene> scenes;
  /// The methods compared, in the order first seen.
  std::vector<std::string> methods;
  /// One record per grasp, in (scene, method, rank) order.
  std::vector<TrialRecord> trials;
  /// Grasps rejected before simulation because their input was malformed (bad numbers, unknown
  /// scene or pre-shape, ...), per method.
  std::vector<std::pair<std::string, int>> rejected;
  /// The run's input files (run.csv records database, grasps, hand; empty for older files).
  RunSources sources;
  /// How the run repeated its grasps (count 1: not repeated).
  RunRepeats repeats;
  /// Name of the run when several are compared side by side (readResults: the folder's name);
  /// may be empty.
  std::string label;
  /// False when the folder read holds kUnfinishedFileName (results_file.hpp): the run was
  /// stopped, killed or failed, or is still running, so its trials are only part of it.
  bool finished = true;
};

}  // namespace visgrab::results
