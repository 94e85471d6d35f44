#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"

namespace rwsim::contacts {

/// One contact point between two shapes, in world coordinates.
struct ContactPoint {
  /// Point midway between the two surfaces.
  rw::math::Vector3D position;
  /// Unit normal pointing from shape A towards shape B (the direction B is pushed).
  rw::math::Vector3D normal;
  /// Penetration depth in metres (> 0 overlapping, <= 0 separated by at most the margin).
  double depth = 0.0;
};

/// Tuning of contact generation.
struct ContactOptions {
  /// Shapes closer than this (m) already produce contacts (RobWork's MaxSepDistance).
  double margin = 0.0005;
  /// Most points kept per body pair and normal direction.
  int maxPointsPerManifold = 4;
};

/// Collision geometry prepared for contact generation: convex pieces (boxes, convex meshes),
/// round shapes (cylinders, cones, frusta as smooth surfaces), flat meshes and non-convex meshes
/// (as triangles in a hierarchy), half-spaces. Immutable,
/// shared between threads.
class ContactShape {
 public:
  /// How collide() treats a shape.
  enum class Kind {
    kHalfSpace,  ///< z <= 0 of its frame (a Plane)
    kSphere,     ///< a sphere about the origin
    kConvex,     ///< one or more convex polytopes (boxes, convex and flat meshes, tubes)
    kRound,      ///< a frustum about the z axis (cylinders, cones, frusta) with exact support
    kMesh,       ///< triangles under a bounding-volume hierarchy (non-convex meshes)
  };
  virtual ~ContactShape() = default;
  /// How collide() treats this shape.
  Kind kind() const { return kind_; }
  /// Prepares a geometry. @throws std::invalid_argument for an empty mesh.
  static std::shared_ptr<const ContactShape> build(const rw::geometry::Geometry& geometry);
  /// Bounding box in the shape's frame (infinite for half-spaces).
  virtual rw::geometry::Aabb localBounds() const = 0;

 protected:
  /// For the implementations.
  explicit ContactShape(Kind kind) : kind_(kind) {}

 private:
  Kind kind_;
};

/// Appends the contacts between two placed shapes to `out` (at most a few points per touching
/// region, deepest first, reduced to keep the contact area's extent). Deterministic; swapping
/// the shapes only flips the normals. Thread-safe; allocates nothing once the calling thread's
/// buffers have grown. Two half-spaces give no contacts.
void collide(const ContactShape& a, const rw::math::Transform3D& X_W_a, const ContactShape& b,
             const rw::math::Transform3D& X_W_b, const ContactOptions& options,
             std::vector<ContactPoint>& out);

/// The contacts between two bodies.
struct BodyContact {
  /// The first body (bodyA < bodyB).
  dynamics::BodyId bodyA;
  /// The second body.
  dynamics::BodyId bodyB;
  /// Points with normals from A towards B.
  std::vector<ContactPoint> points;
};

/// Finds contacts between the bodies of a dynamic workcell: body pairs allowed by the
/// workcell's proximity setup, never two non-moving bodies, never a body with itself.
/// Built once; detect() is const and thread-safe. detect() places each shape of a candidate
/// pair once per call (a fixed body's shapes once at construction, reused while the body is
/// given the pose it had there) and skips body pairs whose boxes (the union of their shapes'
/// boxes) are farther apart than the margin before looking at their shape pairs; the contacts
/// are bit for bit those of placing and testing every shape pair on its own.
class ContactDetector {
 public:
  /// Prepares every body's shapes and the allowed pairs.
  ContactDetector(const dynamics::DynamicWorkCell& dwc, ContactOptions options = {});
  /// Same, never checking the body pairs in `excluded` (in either order), e.g. links joined by
  /// a device joint, whose model geometry overlaps at the joint.
  ContactDetector(const dynamics::DynamicWorkCell& dwc, ContactOptions options,
                  const std::vector<std::pair<dynamics::BodyId, dynamics::BodyId>>& excluded);
  ~ContactDetector();
  ContactDetector(const ContactDetector&) = delete;
  ContactDetector& operator=(const ContactDetector&) = delete;

  /// Contacts for body poses X_W_body (poses of the body frames, one per body, indexed like
  /// bodies()); replaces `out`, reusing its vectors. Pairs come out sorted by (bodyA, bodyB),
  /// each pair's points merged over its geometries and reduced per normal cluster.
  /// @throws std::invalid_argument if X_W_body has the wrong size.
  void detect(const std::vector<rw::math::Transform3D>& X_W_body,
              std::vector<BodyContact>& out) const;
  /// The options in use.
  const ContactOptions& options() const { return options_; }
  /// The body pairs detect() checks, sorted (bodyA < bodyB): those with at least one rigid
  /// body and a pair of geometry frames the proximity setup lets touch.
  std::vector<std::pair<dynamics::BodyId, dynamics::BodyId>> candidatePairs() const;

 private:
  struct Impl;
  ContactOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rwsim::contacts
