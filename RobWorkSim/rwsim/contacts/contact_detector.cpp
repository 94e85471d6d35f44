#include "rwsim/contacts/contact_detector.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/proximity/proximity_filter.hpp"
#include "rwsim/contacts/manifold.hpp"

namespace rwsim::contacts {
namespace {

using rw::geometry::Aabb;
using rw::kinematics::FrameId;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::BodyId;
using rwsim::dynamics::BodyKind;

/// A shape placed in its body's frame.
struct PlacedShape {
  std::shared_ptr<const ContactShape> shape;
  Transform3D X_body_shape = Transform3D::Identity();
  FrameId frame;
  bool unbounded = false;
  Vector3D center = Vector3D::Zero();  // of the local box, in the shape's frame
  Vector3D halfExtents = Vector3D::Zero();
};

/// A box in world coordinates; `unbounded` boxes overlap everything.
struct WorldBox {
  Vector3D center = Vector3D::Zero();
  Vector3D halfExtents = Vector3D::Zero();
  bool unbounded = false;
};

WorldBox worldBox(const PlacedShape& s, const Transform3D& X_W_shape) {
  WorldBox box;
  box.unbounded = s.unbounded;
  box.center = X_W_shape * s.center;
  box.halfExtents = X_W_shape.linear().cwiseAbs() * s.halfExtents;
  return box;
}

bool overlap(const WorldBox& a, const WorldBox& b, double margin) {
  if (a.unbounded || b.unbounded) return true;
  return ((a.center - b.center).cwiseAbs() - a.halfExtents - b.halfExtents).maxCoeff() <= margin;
}

/// The collision geometry of a body's frames, placed in the body frame by the default state
/// (the frames are rigidly attached); shapes are built once per Geometry.
std::vector<PlacedShape> placeShapes(
    const rw::models::WorkCell& wc, const rw::kinematics::FKTable& fk, const dynamics::Body& body,
    std::map<const rw::geometry::Geometry*, std::shared_ptr<const ContactShape>>& built) {
  std::vector<PlacedShape> shapes;
  const Transform3D X_body_W = fk.worldTransform(body.frame).inverse(Eigen::Isometry);
  for (const FrameId frame : body.geometryFrames) {
    const rw::models::Object* object = wc.findObject(frame);
    if (object == nullptr) continue;
    for (const rw::models::GeometryInstance& g : object->collision) {
      std::shared_ptr<const ContactShape>& shape = built[g.geometry.get()];
      if (!shape) shape = ContactShape::build(*g.geometry);
      PlacedShape placed;
      placed.shape = shape;
      placed.frame = frame;
      placed.X_body_shape = X_body_W * fk.worldTransform(frame) * g.X_frame_geometry;
      const Aabb box = shape->localBounds();
      placed.unbounded = !(box.min.allFinite() && box.max.allFinite());
      if (!placed.unbounded) {
        placed.center = 0.5 * (box.min + box.max);
        placed.halfExtents = 0.5 * (box.max - box.min);
      }
      shapes.push_back(std::move(placed));
    }
  }
  return shapes;
}

}  // namespace

struct ContactDetector::Impl {
  /// Pairs of shape indices (into the two bodies' shape lists) that may touch.
  struct BodyPair {
    BodyId a;
    BodyId b;
    std::vector<std::pair<std::size_t, std::size_t>> shapes;
  };
  std::vector<std::vector<PlacedShape>> bodies;
  std::vector<BodyPair> pairs;
};

ContactDetector::ContactDetector(const dynamics::DynamicWorkCell& dwc, ContactOptions options)
    : ContactDetector(dwc, options, {}) {}

ContactDetector::ContactDetector(const dynamics::DynamicWorkCell& dwc, ContactOptions options,
                                 const std::vector<std::pair<BodyId, BodyId>>& excluded)
    : options_(options), impl_(std::make_unique<Impl>()) {
  const rw::models::WorkCell& wc = dwc.workcell();
  const rw::kinematics::FKTable fk(wc.frames(), wc.defaultState());
  std::map<const rw::geometry::Geometry*, std::shared_ptr<const ContactShape>> built;
  for (const dynamics::Body& body : dwc.bodies()) {
    impl_->bodies.push_back(placeShapes(wc, fk, body, built));
  }
  const rw::proximity::ProximityFilter filter(wc);
  const auto& bodies = dwc.bodies();
  const auto isExcluded = [&](BodyId i, BodyId j) {
    return std::any_of(excluded.begin(), excluded.end(), [&](const std::pair<BodyId, BodyId>& e) {
      return std::min(e.first, e.second) == i && std::max(e.first, e.second) == j;
    });
  };
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      if (bodies[i].kind != BodyKind::kRigid && bodies[j].kind != BodyKind::kRigid) continue;
      Impl::BodyPair pair;
      pair.a = BodyId(i);
      pair.b = BodyId(j);
      if (isExcluded(pair.a, pair.b)) continue;
      const auto& sa = impl_->bodies[i];
      const auto& sb = impl_->bodies[j];
      for (std::size_t p = 0; p < sa.size(); ++p) {
        for (std::size_t q = 0; q < sb.size(); ++q) {
          if (sa[p].frame == sb[q].frame || !filter.contains(sa[p].frame, sb[q].frame)) continue;
          pair.shapes.emplace_back(p, q);
        }
      }
      if (!pair.shapes.empty()) impl_->pairs.push_back(std::move(pair));
    }
  }
}

ContactDetector::~ContactDetector() = default;

std::vector<std::pair<BodyId, BodyId>> ContactDetector::candidatePairs() const {
  std::vector<std::pair<BodyId, BodyId>> out;
  for (const Impl::BodyPair& p : impl_->pairs) out.emplace_back(p.a, p.b);
  return out;
}

void ContactDetector::detect(const std::vector<rw::math::Transform3D>& X_W_body,
                             std::vector<BodyContact>& out) const {
  if (X_W_body.size() != impl_->bodies.size()) {
    throw std::invalid_argument("ContactDetector::detect: expected " +
                                std::to_string(impl_->bodies.size()) + " body poses, got " +
                                std::to_string(X_W_body.size()));
  }
  thread_local std::vector<ContactPoint> gathered;
  thread_local detail::ReduceScratch scratch;
  std::size_t used = 0;
  for (const Impl::BodyPair& pair : impl_->pairs) {
    const auto& shapesA = impl_->bodies[pair.a.index()];
    const auto& shapesB = impl_->bodies[pair.b.index()];
    const Transform3D& X_W_a = X_W_body[pair.a.index()];
    const Transform3D& X_W_b = X_W_body[pair.b.index()];
    gathered.clear();
    for (const auto& [p, q] : pair.shapes) {
      const PlacedShape& sa = shapesA[p];
      const PlacedShape& sb = shapesB[q];
      const Transform3D X_W_sa = X_W_a * sa.X_body_shape;
      const Transform3D X_W_sb = X_W_b * sb.X_body_shape;
      if (!overlap(worldBox(sa, X_W_sa), worldBox(sb, X_W_sb), options_.margin)) continue;
      collide(*sa.shape, X_W_sa, *sb.shape, X_W_sb, options_, gathered);
    }
    if (gathered.empty()) continue;
    if (used == out.size()) out.emplace_back();
    BodyContact& contact = out[used++];
    contact.bodyA = pair.a;
    contact.bodyB = pair.b;
    contact.points.clear();
    if (pair.shapes.size() == 1) {
      contact.points.assign(gathered.begin(), gathered.end());
    } else {
      detail::clusterAndReduce(gathered, options_.maxPointsPerManifold, contact.points, scratch);
    }
  }
  out.resize(used);
}

}  // namespace rwsim::contacts
