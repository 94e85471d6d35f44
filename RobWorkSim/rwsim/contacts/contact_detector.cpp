#include "rwsim/contacts/contact_detector.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/proximity/proximity_filter.hpp"
#include "rwsim/contacts/convex_contact.hpp"
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

/// Slack (relative to the coordinates compared, and at least 1 nm) by which the body boxes'
/// test is looser than the shape boxes' test, so that rounding never lets it reject a body
/// pair with a shape pair that overlap() passes.
constexpr double kBroadSlack = 1e-9;

/// The union of a body's shape boxes (those in some candidate pair), as intervals.
struct BodyBox {
  Vector3D lo = Vector3D::Constant(std::numeric_limits<double>::infinity());
  Vector3D hi = Vector3D::Constant(-std::numeric_limits<double>::infinity());
  bool unbounded = false;

  void extend(const WorldBox& box) {
    unbounded = unbounded || box.unbounded;
    lo = lo.cwiseMin(box.center - box.halfExtents);
    hi = hi.cwiseMax(box.center + box.halfExtents);
  }
};

/// True only when the two body boxes are farther apart than the margin along an axis (by more
/// than kBroadSlack): then no pair of their shapes' boxes overlap() within the margin either.
/// Non-finite coordinates never count as apart, so they reach the shape tests as before.
bool apart(const BodyBox& a, const BodyBox& b, double margin) {
  if (a.unbounded || b.unbounded) return false;
  for (Eigen::Index i = 0; i < 3; ++i) {
    const double scale = 1.0 + std::max(std::max(std::abs(a.lo(i)), std::abs(a.hi(i))),
                                        std::max(std::abs(b.lo(i)), std::abs(b.hi(i))));
    const double reach = margin + kBroadSlack * scale;
    if (a.lo(i) - b.hi(i) > reach || b.lo(i) - a.hi(i) > reach) return true;
  }
  return false;
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

/// Per-thread buffers of detect() (grown once, then reused).
struct DetectScratch {
  /// World pose of each shape (indexed like Impl::shapes; those of moving bodies in pairs).
  std::vector<Transform3D> X_W_shape;
  /// Their inverses.
  std::vector<Transform3D> X_shape_W;
  /// Their world boxes.
  std::vector<WorldBox> boxes;
  /// Box of each body.
  std::vector<BodyBox> bodyBoxes;
  /// Per body: the arrays its shapes' poses, inverses and boxes are read from (this scratch's
  /// or the detector's, for fixed bodies at their construction pose).
  std::vector<const Transform3D*> posesOf;
  std::vector<const Transform3D*> inversesOf;
  std::vector<const WorldBox*> boxesOf;
  std::vector<const BodyBox*> bodyBoxOf;
  /// Points of one body pair before the reduction.
  std::vector<ContactPoint> gathered;
  detail::ReduceScratch reduce;
};

DetectScratch& threadScratch() {
  thread_local DetectScratch scratch;
  return scratch;
}

/// True when two poses hold the same doubles, bit for bit (a -0 is not a +0: the cached
/// placement must be the one the pose would give).
bool samePose(const Transform3D& x, const Transform3D& y) {
  for (Eigen::Index i = 0; i < x.matrix().size(); ++i) {
    if (std::bit_cast<std::uint64_t>(x.data()[i]) != std::bit_cast<std::uint64_t>(y.data()[i])) {
      return false;
    }
  }
  return true;
}

}  // namespace

struct ContactDetector::Impl {
  /// A body's shapes: shapes[first, first + count).
  struct BodyShapes {
    std::size_t first = 0;
    std::size_t count = 0;
    /// Whether some shape of the body is in a candidate pair (its pose is needed).
    bool active = false;
    /// A fixed body: its shapes' poses and boxes are kept for the pose X_W_body0.
    bool fixed = false;
    Transform3D X_W_body0 = Transform3D::Identity();
  };
  /// Pairs of shape indices (into `shapes`) that may touch.
  struct BodyPair {
    BodyId a;
    BodyId b;
    std::vector<std::pair<std::size_t, std::size_t>> shapes;
  };
  std::vector<PlacedShape> shapes;
  /// Whether each shape is in some candidate pair.
  std::vector<char> shapeActive;
  std::vector<BodyShapes> bodies;
  std::vector<BodyPair> pairs;
  /// Fixed bodies' shapes at X_W_body0 (indexed like shapes; unused entries are identities).
  std::vector<Transform3D> fixedPoses;
  std::vector<Transform3D> fixedInverses;
  std::vector<WorldBox> fixedBoxes;
  /// Fixed bodies' boxes (indexed like bodies).
  std::vector<BodyBox> fixedBodyBoxes;

  /// World poses, inverses and boxes of body `b`'s active shapes at X_W_body, and its box.
  void placeBody(std::size_t b, const Transform3D& X_W_body, Transform3D* poses,
                 Transform3D* inverses, WorldBox* boxes, BodyBox& bodyBox) const {
    const BodyShapes& body = bodies[b];
    bodyBox = BodyBox();
    for (std::size_t s = body.first; s < body.first + body.count; ++s) {
      if (shapeActive[s] == 0) continue;
      poses[s] = X_W_body * shapes[s].X_body_shape;
      inverses[s] = poses[s].inverse(Eigen::Isometry);
      boxes[s] = worldBox(shapes[s], poses[s]);
      bodyBox.extend(boxes[s]);
    }
  }
};

ContactDetector::ContactDetector(const dynamics::DynamicWorkCell& dwc, ContactOptions options)
    : ContactDetector(dwc, options, {}) {}

ContactDetector::ContactDetector(const dynamics::DynamicWorkCell& dwc, ContactOptions options,
                                 const std::vector<std::pair<BodyId, BodyId>>& excluded)
    : options_(options), impl_(std::make_unique<Impl>()) {
  const rw::models::WorkCell& wc = dwc.workcell();
  const rw::kinematics::FKTable fk(wc.frames(), wc.defaultState());
  std::map<const rw::geometry::Geometry*, std::shared_ptr<const ContactShape>> built;
  Impl& impl = *impl_;
  for (const dynamics::Body& body : dwc.bodies()) {
    Impl::BodyShapes entry;
    entry.first = impl.shapes.size();
    for (PlacedShape& s : placeShapes(wc, fk, body, built)) impl.shapes.push_back(std::move(s));
    entry.count = impl.shapes.size() - entry.first;
    entry.fixed = body.kind == BodyKind::kFixed;
    if (entry.fixed) entry.X_W_body0 = fk.worldTransform(body.frame);
    impl.bodies.push_back(entry);
  }
  impl.shapeActive.assign(impl.shapes.size(), 0);
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
      const Impl::BodyShapes& ba = impl.bodies[i];
      const Impl::BodyShapes& bb = impl.bodies[j];
      for (std::size_t p = ba.first; p < ba.first + ba.count; ++p) {
        for (std::size_t q = bb.first; q < bb.first + bb.count; ++q) {
          const PlacedShape& sa = impl.shapes[p];
          const PlacedShape& sb = impl.shapes[q];
          if (sa.frame == sb.frame || !filter.contains(sa.frame, sb.frame)) continue;
          pair.shapes.emplace_back(p, q);
          impl.shapeActive[p] = 1;
          impl.shapeActive[q] = 1;
        }
      }
      if (!pair.shapes.empty()) impl.pairs.push_back(std::move(pair));
    }
  }
  for (const Impl::BodyPair& pair : impl.pairs) {
    impl.bodies[pair.a.index()].active = true;
    impl.bodies[pair.b.index()].active = true;
  }
  impl.fixedPoses.assign(impl.shapes.size(), Transform3D::Identity());
  impl.fixedInverses.assign(impl.shapes.size(), Transform3D::Identity());
  impl.fixedBoxes.assign(impl.shapes.size(), WorldBox());
  impl.fixedBodyBoxes.assign(impl.bodies.size(), BodyBox());
  for (std::size_t b = 0; b < impl.bodies.size(); ++b) {
    if (!impl.bodies[b].fixed || !impl.bodies[b].active) continue;
    impl.placeBody(b, impl.bodies[b].X_W_body0, impl.fixedPoses.data(), impl.fixedInverses.data(),
                   impl.fixedBoxes.data(), impl.fixedBodyBoxes[b]);
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
  const Impl& impl = *impl_;
  if (X_W_body.size() != impl.bodies.size()) {
    throw std::invalid_argument("ContactDetector::detect: expected " +
                                std::to_string(impl.bodies.size()) + " body poses, got " +
                                std::to_string(X_W_body.size()));
  }
  DetectScratch& scratch = threadScratch();
  detail::Workspace& ws = detail::threadWorkspace();
  const std::size_t shapeCount = impl.shapes.size();
  const std::size_t bodyCount = impl.bodies.size();
  // Each shape in a candidate pair is placed once per call; fixed bodies at their
  // construction pose reuse the placement made then.
  scratch.X_W_shape.resize(shapeCount);
  scratch.X_shape_W.resize(shapeCount);
  scratch.boxes.resize(shapeCount);
  scratch.bodyBoxes.resize(bodyCount);
  scratch.posesOf.assign(bodyCount, nullptr);
  scratch.inversesOf.assign(bodyCount, nullptr);
  scratch.boxesOf.assign(bodyCount, nullptr);
  scratch.bodyBoxOf.assign(bodyCount, nullptr);
  for (std::size_t b = 0; b < bodyCount; ++b) {
    const Impl::BodyShapes& body = impl.bodies[b];
    if (!body.active) continue;
    if (body.fixed && samePose(X_W_body[b], body.X_W_body0)) {
      scratch.posesOf[b] = impl.fixedPoses.data();
      scratch.inversesOf[b] = impl.fixedInverses.data();
      scratch.boxesOf[b] = impl.fixedBoxes.data();
      scratch.bodyBoxOf[b] = &impl.fixedBodyBoxes[b];
      continue;
    }
    impl.placeBody(b, X_W_body[b], scratch.X_W_shape.data(), scratch.X_shape_W.data(),
                   scratch.boxes.data(), scratch.bodyBoxes[b]);
    scratch.posesOf[b] = scratch.X_W_shape.data();
    scratch.inversesOf[b] = scratch.X_shape_W.data();
    scratch.boxesOf[b] = scratch.boxes.data();
    scratch.bodyBoxOf[b] = &scratch.bodyBoxes[b];
  }
  std::vector<ContactPoint>& gathered = scratch.gathered;
  const double margin = options_.margin;
  std::size_t used = 0;
  for (const Impl::BodyPair& pair : impl.pairs) {
    const std::size_t a = pair.a.index();
    const std::size_t b = pair.b.index();
    if (apart(*scratch.bodyBoxOf[a], *scratch.bodyBoxOf[b], margin)) continue;
    const Transform3D* posesA = scratch.posesOf[a];
    const Transform3D* posesB = scratch.posesOf[b];
    const Transform3D* inversesA = scratch.inversesOf[a];
    const Transform3D* inversesB = scratch.inversesOf[b];
    const WorldBox* boxesA = scratch.boxesOf[a];
    const WorldBox* boxesB = scratch.boxesOf[b];
    gathered.clear();
    for (const auto& [p, q] : pair.shapes) {
      if (!overlap(boxesA[p], boxesB[q], margin)) continue;
      detail::collidePlaced(*impl.shapes[p].shape, posesA[p], inversesA[p], *impl.shapes[q].shape,
                            posesB[q], inversesB[q], options_, ws, gathered);
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
      detail::clusterAndReduce(gathered, options_.maxPointsPerManifold, contact.points,
                               scratch.reduce);
    }
  }
  out.resize(used);
}

}  // namespace rwsim::contacts
