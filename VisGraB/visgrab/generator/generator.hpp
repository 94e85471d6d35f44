#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "visgrab/database/scene_set.hpp"
#include "visgrab/generator/camera_profile.hpp"
#include "visgrab/generator/placement.hpp"
#include "visgrab/generator/settle.hpp"
#include "visgrab/render/render_result.hpp"

namespace visgrab::generator {

/// What `visgrab db generate` needs.
struct GeneratorOptions {
  /// The database folder to write (created; an existing generation with the same seed resumes).
  std::filesystem::path out;
  /// The object spec (scenes/objects/objects.xml, or your own: `db generate --objects SPEC`).
  std::filesystem::path objectSpec;
  /// Where the table surfaces come from when objectSpec has no <Table> of the name (empty:
  /// objectSpec only).
  std::filesystem::path tableSpec;
  /// The objects and pairs of the scenes (objectCatalog(spec) for your own objects).
  database::ObjectCatalog catalog = database::ObjectCatalog::benchmark();
  /// The hand's folder (scenes/hands/sdh), copied into the database.
  std::filesystem::path handFolder;
  /// The material map (scenes/materials.xml), copied into the database.
  std::filesystem::path materials;
  /// Seed of placements and sensor noise.
  std::uint64_t seed = 1;
  /// Worker threads (each with its own simulator and offscreen renderer).
  int threads = 1;
  /// Set (by a signal handler, say) to stop early: the scenes being made are finished and
  /// indexed, no new one starts, and generateDatabase throws rw::common::StopRequested. Null:
  /// never. Must outlive the call.
  const std::atomic<bool>* stop = nullptr;
  /// The camera profile: rig geometry and camera effects (default: the "ideal" profile;
  /// `visgrab db generate` loads scenes/cameras/realistic.xml unless told otherwise).
  CameraProfile camera;
  /// Placements.
  PlacementOptions placement;
  /// Settling.
  SettleOptions settle;
  /// Height objects are dropped from above their resting placement, m.
  double dropHeight = 0.003;
  /// Deepest penetration a settled scene may keep, m.
  double maxPenetration = 0.001;
  /// Placements tried per scene before it is reported as failed.
  int maxAttempts = 6;
  /// A placement still moving at SettleOptions::maxTime is settled once more with this ODE
  /// linear and angular damping (per step) on the objects, standing in for the rolling
  /// resistance the simulator does not model: a round object on a neutral equilibrium (a
  /// canister whose lid is wider than its body rolls in a circle) then comes to rest where it
  /// would. The scene files keep no damping; trials run without it. 0: no second settle.
  double rollingDamping = 0.05;
  /// Called with each made scene's id and the ground-truth render of its rectified left view
  /// (depth and instance ids: 1 the table, 10 + object id), before the scene is indexed; from
  /// the worker threads, concurrently. For tools and tests that measure the images against the
  /// truth. Empty: not called.
  std::function<void(const std::string&, const render::RenderResult&)> truthObserver;
};

/// Progress after each finished (or failed) scene.
struct GenerationProgress {
  /// Scenes finished or failed in this run.
  int done = 0;
  /// Scenes this run has to make.
  int total = 0;
  /// Scenes found complete from an earlier run (not made again).
  int skipped = 0;
  /// Id of the scene just finished.
  std::string lastId;
  /// Seconds since the run started.
  double elapsed = 0.0;
};

/// What a run did.
struct GenerationReport {
  /// Scenes made.
  int generated = 0;
  /// Scenes already complete.
  int skipped = 0;
  /// "id: reason" for each scene that could not be made.
  std::vector<std::string> failures;
};

/// Generates the scenes `scenes` (e.g. enumerateScenes() or a filtered subset) into
/// options.out: the shared assets (objects, tables, hand, materials) once, then per scene the
/// placement, settling (retried with new placements until every object is at rest and
/// penetrates less than maxPenetration), the scene files with the settled poses, the rendered
/// rectified stereo pair with sensor effects, the calibration, and the disparity, point cloud
/// and ground truth (depth, mask, poses; writeSceneProducts); each finished scene is added
/// to the index at once, so an interrupted run loses nothing and resumes. The same seed gives
/// byte-identical files whatever the thread count. A scene that fails is reported, not fatal;
/// a file that cannot be written (rw::common::WriteError: disk full, folder deleted) is: the
/// scenes already being made finish, then it is thrown.
/// @throws std::runtime_error (or rw::common::LoadError) for unusable inputs: the object spec,
/// the hand folder, an index with another seed, no OpenGL; rw::common::WriteError;
/// rw::common::StopRequested when options.stop ended it early.
GenerationReport generateDatabase(
    const std::vector<database::SceneConditions>& scenes, const GeneratorOptions& options,
    const std::function<void(const GenerationProgress&)>& progress = {});

}  // namespace visgrab::generator
