#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "rw/kinematics/frame.hpp"
#include "rw/math/types.hpp"
#include "rw/models/workcell.hpp"
#include "rw/proximity/distance_result.hpp"
#include "rw/proximity/proximity_filter.hpp"
#include "rw/proximity/proximity_model.hpp"

namespace rw::proximity {

/// One collision geometry of a frame, ready for queries.
struct PlacedModel {
  /// The model (owned by the FrameModels that hands it out).
  const ProximityModel* model = nullptr;
  /// Pose of the geometry in its frame.
  rw::math::Transform3D X_frame_geometry = rw::math::Transform3D::Identity();
};

/// The proximity models of the collision geometry of every frame of a workcell, built once;
/// a Geometry shared by several frames gets one model. Immutable; queried from many threads.
class FrameModels {
 public:
  /// Builds the models of all objects of `workcell`.
  /// @throws std::invalid_argument for a mesh without triangles or with a bad vertex index.
  explicit FrameModels(const rw::models::WorkCell& workcell);

  /// The collision geometry of `frame` (empty when it has none or is unknown).
  std::span<const PlacedModel> of(rw::kinematics::FrameId frame) const;
  /// True when `frame` has collision geometry.
  bool hasGeometry(rw::kinematics::FrameId frame) const { return !of(frame).empty(); }
  /// Number of distinct models.
  std::size_t modelCount() const { return models_.size(); }

  /// True when some geometry of frame `a` (at X_W_a) and some of frame `b` (at X_W_b) collide.
  bool collides(rw::kinematics::FrameId a, const rw::math::Transform3D& X_W_a,
                rw::kinematics::FrameId b, const rw::math::Transform3D& X_W_b) const;
  /// The closest pair of geometries of frames `a` and `b` (pointA on a); distance +infinity
  /// when a frame has no geometry or the distance is at least `upperBound`.
  DistanceResult distance(rw::kinematics::FrameId a, const rw::math::Transform3D& X_W_a,
                          rw::kinematics::FrameId b, const rw::math::Transform3D& X_W_b,
                          double upperBound = std::numeric_limits<double>::infinity()) const;

 private:
  struct FrameEntry {
    std::int32_t first = 0;
    std::int32_t count = 0;
    rw::math::Vector3D boundCenter = rw::math::Vector3D::Zero();
    double boundRadius = 0.0;
  };
  // Lower bound on the distance between the frames' bounding spheres.
  double sphereGap(const FrameEntry& a, const rw::math::Transform3D& X_W_a, const FrameEntry& b,
                   const rw::math::Transform3D& X_W_b) const;

  std::vector<std::unique_ptr<const ProximityModel>> models_;
  std::vector<PlacedModel> placed_;
  std::vector<FrameEntry> frames_;
};

/// The pairs of `filter` whose frames both have geometry in `models`, in filter order.
std::vector<FramePair> pairsWithGeometry(const ProximityFilter& filter, const FrameModels& models);

}  // namespace rw::proximity
