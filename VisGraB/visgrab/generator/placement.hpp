#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rw/math/types.hpp"
#include "rw/proximity/convex_shape.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/objects/object_model.hpp"

/// Making the benchmark's scenes: placing, settling and rendering them.
namespace visgrab::generator {

/// A deterministic random stream (splitmix64): the same seed gives the same numbers on every
/// platform and standard library, unlike std::uniform_real_distribution.
class Random {
 public:
  /// A stream for `seed`.
  explicit Random(std::uint64_t seed) : state_(seed) {}
  /// A stream for `seed` and a text such as a scene id (each id its own stream).
  Random(std::uint64_t seed, std::string_view key);
  /// The next 64 random bits.
  std::uint64_t next();
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi);
  /// Standard normal (Box-Muller).
  double normal();

 private:
  std::uint64_t state_;
};

/// Where the objects of a scene start before they are dropped and settled.
struct Placement {
  /// Pose of each object's model frame in the table frame (z = 0 the table top), in the order
  /// of SceneConditions::objects, resting on the table (lowest collision point at z = 0).
  std::vector<rw::math::Transform3D> X_TO;
};

/// Tuning of the placements.
struct PlacementOptions {
  /// Objects' footprint centres stay within this square about the table centre, m.
  double spread = 0.05;
  /// Gap between the two objects of an "apart" scene, m (drawn from [min, max)).
  double apartGapMin = 0.04;
  /// See apartGapMin.
  double apartGapMax = 0.09;
  /// Gap left between the two objects of a "close" scene before settling, m.
  double closeGap = 0.001;
};

/// Places the objects of a scene: a single object stands (poses 1-4, turned by 90 degrees
/// steps plus a random angle) or lies (poses 5-8, cycling through the model's lying poses,
/// turned by 45 degree steps plus a random angle); a pair stands upright side by side along a
/// direction that turns with the pose: apart (poses 1-4) with a gap drawn from
/// [apartGapMin, apartGapMax) between the collision geometry's extents along that direction,
/// or close (5-8), moved together along it until their distance is closeGap.
/// `models` holds the scene's objects in the order of `scene.objects`. Deterministic in
/// (seed, scene id, attempt).
/// @throws std::invalid_argument if the models do not match the scene or lack resting poses.
Placement placeObjects(const database::SceneConditions& scene,
                       const std::vector<const objects::ObjectModel*>& models, std::uint64_t seed,
                       int attempt = 0, const PlacementOptions& options = {});

/// The scene id of `scene` spelled with the models' names (sceneIdOf(scene) for the benchmark's
/// objects; works for your own objects too).
std::string sceneIdOf(const database::SceneConditions& scene,
                      const std::vector<const objects::ObjectModel*>& models);

/// Lowest and highest extent of a model's collision geometry along unit direction `d` in the
/// table frame, for the model at X_TO.
std::pair<double, double> extentAlong(const objects::ObjectModel& model,
                                      const rw::math::Transform3D& X_TO,
                                      const rw::math::Vector3D& d);

/// The exact convex shape of a collision piece in the piece's geometry frame (a cylinder or
/// frustum for a round piece, else the hull of the mesh; the shape borrows the piece's vertices).
rw::proximity::ConvexShape convexShapeOf(const objects::CollisionPiece& piece);

/// Distance between two models' collision geometry, exact for round pieces (0 when they
/// overlap), m.
double distanceBetween(const objects::ObjectModel& a, const rw::math::Transform3D& X_TA,
                       const objects::ObjectModel& b, const rw::math::Transform3D& X_TB);

}  // namespace visgrab::generator
