#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "rw/math/types.hpp"

namespace rw::geometry {

/// An indexed triangle mesh in metres; triangles wind counter-clockwise seen from outside.
struct TriMesh {
  /// Vertex positions.
  std::vector<rw::math::Vector3D> vertices;
  /// Vertex indices of each triangle.
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Axis-aligned bounding box.
struct Aabb {
  /// Smallest corner.
  rw::math::Vector3D min{rw::math::Vector3D::Constant(std::numeric_limits<double>::infinity())};
  /// Largest corner.
  rw::math::Vector3D max{rw::math::Vector3D::Constant(-std::numeric_limits<double>::infinity())};
  /// True when no point was added.
  bool empty() const { return (min.array() > max.array()).any(); }
  /// Grows the box to contain p.
  void extend(const rw::math::Vector3D& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
};

/// The kinds of geometry a workcell can hold (RobWork's primitives plus meshes).
/// kFrustum is this project's extension, written as <Custom type="Frustum"> (RobWork's mechanism
/// for primitives it does not know).
enum class GeometryType { kBox, kSphere, kCylinder, kCone, kTube, kPlane, kFrustum, kMesh };

/// Name of a geometry type as written in workcell XML ("Box", ..., "Polytope").
const char* geometryTypeName(GeometryType type);

/// Immutable geometry centred at its own origin (RobWork's conventions, reference §1.3):
/// Box full edge lengths; Cylinder/Tube/Cone axis along z from -h/2 to +h/2 (cone apex at -h/2);
/// Tube inner radius `radius`, outer `radius + thickness`; Plane z = 0 with normal +z.
/// Shared between threads as `std::shared_ptr<const Geometry>`.
class Geometry {
 public:
  /// Box with full edge lengths x, y, z. @throws std::invalid_argument unless all > 0.
  static std::shared_ptr<const Geometry> box(double x, double y, double z);
  /// Sphere. @throws std::invalid_argument unless radius > 0.
  static std::shared_ptr<const Geometry> sphere(double radius);
  /// Cylinder along z. @throws std::invalid_argument unless radius, height > 0.
  static std::shared_ptr<const Geometry> cylinder(double radius, double height);
  /// Cone along z, base disk at +h/2, apex at -h/2. @throws std::invalid_argument unless > 0.
  static std::shared_ptr<const Geometry> cone(double radius, double height);
  /// Frustum along z: disk of `bottomRadius` at -h/2, of `topRadius` at +h/2 (a cone when one is
  /// 0). @throws std::invalid_argument unless the radii are >= 0, not both 0, and height > 0.
  static std::shared_ptr<const Geometry> frustum(double bottomRadius, double topRadius,
                                                 double height);
  /// Hollow cylinder. @throws std::invalid_argument unless radius >= 0, thickness, height > 0.
  static std::shared_ptr<const Geometry> tube(double radius, double thickness, double height);
  /// Infinite plane z = 0, normal +z.
  static std::shared_ptr<const Geometry> plane();
  /// A triangle mesh read from `sourceFile` (kept for the writer and for messages).
  /// @throws std::invalid_argument if the mesh has no triangles or an index is out of range.
  static std::shared_ptr<const Geometry> mesh(std::shared_ptr<const TriMesh> mesh,
                                              std::string sourceFile);

  /// The kind of geometry.
  GeometryType type() const { return type_; }
  /// Primitive parameters in XML attribute order (Box x y z; Sphere r; Cylinder r h; Cone r h;
  /// Tube r thickness h; Frustum bottom radius, top radius, h); empty for Plane and Mesh.
  const std::vector<double>& parameters() const { return parameters_; }
  /// File the mesh was read from; empty for primitives.
  const std::string& sourceFile() const { return sourceFile_; }
  /// Triangles: the mesh itself, or a tessellation of the primitive (a Plane gives a 10 m square).
  const TriMesh& triangles() const { return *mesh_; }
  /// Shared pointer to the triangles (never null).
  const std::shared_ptr<const TriMesh>& trianglesPtr() const { return mesh_; }
  /// True for Box, Sphere, Cylinder, Cone, Frustum and for meshes whose vertices all lie on or
  /// behind every face plane (within 1e-6 m).
  bool isConvex() const { return convex_; }
  /// Bounding box in the geometry's own frame (a Plane gives an infinite box in x and y).
  const Aabb& bounds() const { return bounds_; }

 private:
  Geometry(GeometryType type, std::vector<double> parameters, std::shared_ptr<const TriMesh> mesh,
           std::string sourceFile);

  GeometryType type_;
  std::vector<double> parameters_;
  std::shared_ptr<const TriMesh> mesh_;
  std::string sourceFile_;
  bool convex_ = false;
  Aabb bounds_;
};

}  // namespace rw::geometry
