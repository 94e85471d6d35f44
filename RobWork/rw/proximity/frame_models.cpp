#include "rw/proximity/frame_models.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "rw/proximity/proximity_queries.hpp"

namespace rw::proximity {

using rw::kinematics::FrameId;
using rw::math::Transform3D;
using rw::math::Vector3D;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Distance between two spheres' surfaces (negative when they overlap); -inf if one is infinite.
double sphereSeparation(const Vector3D& ca, double ra, const Vector3D& cb, double rb) {
  if (std::isinf(ra) || std::isinf(rb)) return -kInfinity;
  return (ca - cb).norm() - ra - rb;
}

}  // namespace

FrameModels::FrameModels(const rw::models::WorkCell& workcell) : frames_(workcell.frames().size()) {
  std::map<const rw::geometry::Geometry*, const ProximityModel*> built;
  std::vector<const rw::models::Object*> objects;
  for (const rw::models::Object& object : workcell.objects()) objects.push_back(&object);
  std::sort(objects.begin(), objects.end(),
            [](const auto* x, const auto* y) { return x->frame < y->frame; });
  for (const rw::models::Object* object : objects) {
    if (!object->frame.valid() || static_cast<std::size_t>(object->frame.index) >= frames_.size() ||
        object->collision.empty()) {
      continue;
    }
    FrameEntry& entry = frames_[static_cast<std::size_t>(object->frame.index)];
    entry.first = static_cast<std::int32_t>(placed_.size());
    for (const rw::models::GeometryInstance& instance : object->collision) {
      if (!instance.geometry) continue;
      const ProximityModel*& model = built[instance.geometry.get()];
      if (model == nullptr) {
        models_.push_back(std::make_unique<const ProximityModel>(*instance.geometry));
        model = models_.back().get();
      }
      placed_.push_back(PlacedModel{model, instance.X_frame_geometry});
    }
    entry.count = static_cast<std::int32_t>(placed_.size()) - entry.first;
    if (entry.count == 0) continue;
    // A sphere around the geometries' spheres, centred on the first one.
    const PlacedModel& head = placed_[static_cast<std::size_t>(entry.first)];
    entry.boundCenter = head.X_frame_geometry * head.model->boundCenter();
    for (std::int32_t k = entry.first; k < entry.first + entry.count; ++k) {
      const PlacedModel& p = placed_[static_cast<std::size_t>(k)];
      const Vector3D c = p.X_frame_geometry * p.model->boundCenter();
      entry.boundRadius =
          std::max(entry.boundRadius, (c - entry.boundCenter).norm() + p.model->boundRadius());
    }
  }
}

std::span<const PlacedModel> FrameModels::of(FrameId frame) const {
  if (!frame.valid() || static_cast<std::size_t>(frame.index) >= frames_.size()) return {};
  const FrameEntry& e = frames_[static_cast<std::size_t>(frame.index)];
  return {placed_.data() + e.first, static_cast<std::size_t>(e.count)};
}

double FrameModels::sphereGap(const FrameEntry& a, const Transform3D& X_W_a, const FrameEntry& b,
                              const Transform3D& X_W_b) const {
  return sphereSeparation(X_W_a * a.boundCenter, a.boundRadius, X_W_b * b.boundCenter,
                          b.boundRadius);
}

bool FrameModels::collides(FrameId a, const Transform3D& X_W_a, FrameId b,
                           const Transform3D& X_W_b) const {
  const std::span<const PlacedModel> ga = of(a);
  const std::span<const PlacedModel> gb = of(b);
  if (ga.empty() || gb.empty()) return false;
  if (sphereGap(frames_[static_cast<std::size_t>(a.index)], X_W_a,
                frames_[static_cast<std::size_t>(b.index)], X_W_b) > kContactTolerance) {
    return false;
  }
  for (const PlacedModel& pa : ga) {
    const Transform3D X_W_ga = X_W_a * pa.X_frame_geometry;
    for (const PlacedModel& pb : gb) {
      const Transform3D X_W_gb = X_W_b * pb.X_frame_geometry;
      if (sphereSeparation(X_W_ga * pa.model->boundCenter(), pa.model->boundRadius(),
                           X_W_gb * pb.model->boundCenter(),
                           pb.model->boundRadius()) > kContactTolerance) {
        continue;
      }
      if (rw::proximity::collides(*pa.model, X_W_ga, *pb.model, X_W_gb)) return true;
    }
  }
  return false;
}

DistanceResult FrameModels::distance(FrameId a, const Transform3D& X_W_a, FrameId b,
                                     const Transform3D& X_W_b, double upperBound) const {
  DistanceResult best;
  const std::span<const PlacedModel> ga = of(a);
  const std::span<const PlacedModel> gb = of(b);
  if (ga.empty() || gb.empty()) return best;
  if (sphereGap(frames_[static_cast<std::size_t>(a.index)], X_W_a,
                frames_[static_cast<std::size_t>(b.index)], X_W_b) >= upperBound) {
    return best;
  }
  double bound = upperBound;
  for (const PlacedModel& pa : ga) {
    const Transform3D X_W_ga = X_W_a * pa.X_frame_geometry;
    for (const PlacedModel& pb : gb) {
      const Transform3D X_W_gb = X_W_b * pb.X_frame_geometry;
      if (sphereSeparation(X_W_ga * pa.model->boundCenter(), pa.model->boundRadius(),
                           X_W_gb * pb.model->boundCenter(), pb.model->boundRadius()) >= bound) {
        continue;
      }
      const DistanceResult r = rw::proximity::distance(*pa.model, X_W_ga, *pb.model, X_W_gb, bound);
      if (r.distance < bound) {
        best = r;
        bound = r.distance;
      }
    }
  }
  return best;
}

std::vector<FramePair> pairsWithGeometry(const ProximityFilter& filter, const FrameModels& models) {
  std::vector<FramePair> pairs;
  for (const FramePair& p : filter.pairs()) {
    if (models.hasGeometry(p.first) && models.hasGeometry(p.second)) pairs.push_back(p);
  }
  return pairs;
}

}  // namespace rw::proximity
