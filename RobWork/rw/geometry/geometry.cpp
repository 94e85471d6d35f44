#include "rw/geometry/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace rw::geometry {
namespace {

using rw::math::Vector3D;
using Index = std::uint32_t;

/// Segments around the z axis of round primitives (cylinder, cone, tube, sphere longitudes).
constexpr Index kRoundSegments = 32;
/// Latitude bands of the UV sphere, pole to pole.
constexpr Index kSphereStacks = 16;
/// Half the edge of the square drawn for a Plane (10 m x 10 m).
constexpr double kPlaneHalfSize = 5.0;
/// A mesh vertex may lie this far (metres) in front of a face plane and the mesh still be convex.
constexpr double kConvexTolerance = 1e-6;
/// Triangles with |cross product| below this fraction of their longest squared edge are skipped.
constexpr double kDegenerateRatio = 1e-12;

constexpr std::array<const char*, 8> kTypeNames = {"Box",  "Sphere", "Cylinder", "Cone",
                                                   "Tube", "Plane",  "Frustum",  "Polytope"};
static_assert(kTypeNames.size() == static_cast<std::size_t>(GeometryType::kMesh) + 1,
              "kTypeNames must name every GeometryType");

std::string formatNumber(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

void requirePositive(const char* shape, const char* name, double value) {
  if (std::isfinite(value) && value > 0.0) return;
  throw std::invalid_argument(std::string(shape) + ": " + name + " must be " +
                              (std::isfinite(value) ? "> 0" : "finite and > 0") + ", got " +
                              formatNumber(value));
}

void requireNonNegative(const char* shape, const char* name, double value) {
  if (std::isfinite(value) && value >= 0.0) return;
  throw std::invalid_argument(std::string(shape) + ": " + name + " must be " +
                              (std::isfinite(value) ? ">= 0" : "finite and >= 0") + ", got " +
                              formatNumber(value));
}

/// Collects vertices and counter-clockwise (seen from outside) triangles of a tessellation.
class MeshBuilder {
 public:
  Index vertex(double x, double y, double z) {
    mesh_.vertices.emplace_back(x, y, z);
    return static_cast<Index>(mesh_.vertices.size() - 1);
  }
  /// Adds `kRoundSegments` vertices on the circle of `radius` at height z; returns the first.
  Index ring(double radius, double z) {
    const Index first = static_cast<Index>(mesh_.vertices.size());
    for (Index i = 0; i < kRoundSegments; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / kRoundSegments;
      vertex(radius * std::cos(angle), radius * std::sin(angle), z);
    }
    return first;
  }
  void triangle(Index a, Index b, Index c) { mesh_.triangles.push_back({a, b, c}); }
  /// A planar quad a-b-c-d, counter-clockwise seen from outside.
  void quad(Index a, Index b, Index c, Index d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  std::shared_ptr<const TriMesh> finish() {
    return std::make_shared<const TriMesh>(std::move(mesh_));
  }

 private:
  TriMesh mesh_;
};

/// Index of vertex i (taken modulo the segment count) of the ring starting at `first`.
Index around(Index first, Index i) { return first + i % kRoundSegments; }

std::shared_ptr<const TriMesh> tessellateBox(double x, double y, double z) {
  MeshBuilder b;
  // Corner k has bit 0 set for +x, bit 1 for +y, bit 2 for +z.
  for (Index k = 0; k < 8; ++k) {
    b.vertex((k & 1U) != 0 ? x / 2 : -x / 2, (k & 2U) != 0 ? y / 2 : -y / 2,
             (k & 4U) != 0 ? z / 2 : -z / 2);
  }
  b.quad(0, 4, 6, 2);  // -x
  b.quad(1, 3, 7, 5);  // +x
  b.quad(0, 1, 5, 4);  // -y
  b.quad(2, 6, 7, 3);  // +y
  b.quad(0, 2, 3, 1);  // -z
  b.quad(4, 5, 7, 6);  // +z
  return b.finish();
}

std::shared_ptr<const TriMesh> tessellateSphere(double r) {
  MeshBuilder b;
  const Index north = b.vertex(0, 0, r);
  std::vector<Index> rings;
  for (Index k = 1; k < kSphereStacks; ++k) {
    const double polar = std::numbers::pi * k / kSphereStacks;
    rings.push_back(b.ring(r * std::sin(polar), r * std::cos(polar)));
  }
  const Index south = b.vertex(0, 0, -r);
  for (Index i = 0; i < kRoundSegments; ++i) {
    b.triangle(north, around(rings.front(), i), around(rings.front(), i + 1));
    for (std::size_t k = 0; k + 1 < rings.size(); ++k) {
      const Index upper = rings[k];
      const Index lower = rings[k + 1];
      b.quad(around(lower, i), around(lower, i + 1), around(upper, i + 1), around(upper, i));
    }
    b.triangle(south, around(rings.back(), i + 1), around(rings.back(), i));
  }
  return b.finish();
}

std::shared_ptr<const TriMesh> tessellateFrustum(double bottom, double top, double h) {
  MeshBuilder b;
  // A zero radius is a single apex vertex; its ring indices all map to it.
  const Index bottomRing = bottom > 0.0 ? b.ring(bottom, -h / 2) : b.vertex(0, 0, -h / 2);
  const Index topRing = top > 0.0 ? b.ring(top, h / 2) : b.vertex(0, 0, h / 2);
  const auto at = [](Index first, double radius, Index i) {
    return radius > 0.0 ? around(first, i) : first;
  };
  const Index bottomCentre = bottom > 0.0 ? b.vertex(0, 0, -h / 2) : bottomRing;
  const Index topCentre = top > 0.0 ? b.vertex(0, 0, h / 2) : topRing;
  for (Index i = 0; i < kRoundSegments; ++i) {
    const Index b0 = at(bottomRing, bottom, i);
    const Index b1 = at(bottomRing, bottom, i + 1);
    const Index t0 = at(topRing, top, i);
    const Index t1 = at(topRing, top, i + 1);
    if (b0 != b1) b.triangle(b0, b1, t1);
    if (t0 != t1) b.triangle(b0, t1, t0);
    if (top > 0.0) b.triangle(topCentre, t0, t1);
    if (bottom > 0.0) b.triangle(bottomCentre, b1, b0);
  }
  return b.finish();
}

std::shared_ptr<const TriMesh> tessellateTube(double inner, double outer, double h) {
  MeshBuilder b;
  const Index outerBottom = b.ring(outer, -h / 2);
  const Index outerTop = b.ring(outer, h / 2);
  const Index innerBottom = b.ring(inner, -h / 2);
  const Index innerTop = b.ring(inner, h / 2);
  for (Index i = 0; i < kRoundSegments; ++i) {
    const Index j = i + 1;
    b.quad(around(outerBottom, i), around(outerBottom, j), around(outerTop, j),
           around(outerTop, i));
    b.quad(around(innerBottom, i), around(innerTop, i), around(innerTop, j),
           around(innerBottom, j));
    b.quad(around(innerTop, i), around(outerTop, i), around(outerTop, j), around(innerTop, j));
    b.quad(around(innerBottom, i), around(innerBottom, j), around(outerBottom, j),
           around(outerBottom, i));
  }
  return b.finish();
}

std::shared_ptr<const TriMesh> tessellatePlane() {
  MeshBuilder b;
  const double s = kPlaneHalfSize;
  b.quad(b.vertex(-s, -s, 0), b.vertex(s, -s, 0), b.vertex(s, s, 0), b.vertex(-s, s, 0));
  return b.finish();
}

Aabb symmetricBox(double hx, double hy, double hz) {
  Aabb box;
  box.max = Vector3D(hx, hy, hz);
  box.min = -box.max;
  return box;
}

/// Exact bounds of a primitive from its parameters (not from its tessellation).
Aabb primitiveBounds(GeometryType type, const std::vector<double>& p) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  switch (type) {
    case GeometryType::kBox:
      return symmetricBox(p[0] / 2, p[1] / 2, p[2] / 2);
    case GeometryType::kSphere:
      return symmetricBox(p[0], p[0], p[0]);
    case GeometryType::kCylinder:
    case GeometryType::kCone:
      return symmetricBox(p[0], p[0], p[1] / 2);
    case GeometryType::kTube:
      return symmetricBox(p[0] + p[1], p[0] + p[1], p[2] / 2);
    case GeometryType::kFrustum:
      return symmetricBox(std::max(p[0], p[1]), std::max(p[0], p[1]), p[2] / 2);
    case GeometryType::kPlane: {
      Aabb box;
      box.min = Vector3D(-kInf, -kInf, 0.0);
      box.max = Vector3D(kInf, kInf, 0.0);
      return box;
    }
    case GeometryType::kMesh:
      break;
  }
  return Aabb{};
}

Aabb meshBounds(const TriMesh& mesh) {
  Aabb box;
  for (const Vector3D& v : mesh.vertices) box.extend(v);
  return box;
}

/// True when every vertex lies on or behind every non-degenerate face plane (within
/// kConvexTolerance); assumes consistent outward winding. O(V * F), stopping at the first
/// vertex in front of a face: fine for RobWork's convex hulls (about 2000 triangles).
bool meshIsConvex(const TriMesh& mesh) {
  for (const auto& t : mesh.triangles) {
    const Vector3D& a = mesh.vertices[t[0]];
    const Vector3D& b = mesh.vertices[t[1]];
    const Vector3D& c = mesh.vertices[t[2]];
    const Vector3D normal = (b - a).cross(c - a);
    const double longestSquared =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double length = normal.norm();
    if (!(length > kDegenerateRatio * longestSquared)) continue;  // degenerate (or NaN)
    const Vector3D unitNormal = normal / length;
    for (const Vector3D& v : mesh.vertices) {
      if (unitNormal.dot(v - a) > kConvexTolerance) return false;
    }
  }
  return true;
}

bool primitiveIsConvex(GeometryType type) {
  return type == GeometryType::kBox || type == GeometryType::kSphere ||
         type == GeometryType::kCylinder || type == GeometryType::kCone ||
         type == GeometryType::kFrustum;
}

void validateMesh(const TriMesh* mesh, const std::string& sourceFile) {
  const std::string what = "Polytope '" + sourceFile + "': ";
  if (mesh == nullptr) throw std::invalid_argument(what + "mesh is null");
  if (mesh->triangles.empty()) throw std::invalid_argument(what + "mesh has no triangles");
  const std::size_t n = mesh->vertices.size();
  for (std::size_t i = 0; i < mesh->triangles.size(); ++i) {
    for (const Index index : mesh->triangles[i]) {
      if (index >= n) {
        throw std::invalid_argument(what + "triangle " + std::to_string(i) + " refers to vertex " +
                                    std::to_string(index) + " but the mesh has " +
                                    std::to_string(n) + " vertices");
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!mesh->vertices[i].allFinite()) {
      throw std::invalid_argument(what + "vertex " + std::to_string(i) + " is not finite");
    }
  }
}

}  // namespace

const char* geometryTypeName(GeometryType type) {
  const auto index = static_cast<std::size_t>(type);
  return index < kTypeNames.size() ? kTypeNames[index] : "Unknown";
}

Geometry::Geometry(GeometryType type, std::vector<double> parameters,
                   std::shared_ptr<const TriMesh> mesh, std::string sourceFile)
    : type_(type),
      parameters_(std::move(parameters)),
      mesh_(std::move(mesh)),
      sourceFile_(std::move(sourceFile)) {
  if (type_ == GeometryType::kMesh) {
    bounds_ = meshBounds(*mesh_);
    convex_ = meshIsConvex(*mesh_);
  } else {
    bounds_ = primitiveBounds(type_, parameters_);
    convex_ = primitiveIsConvex(type_);
  }
}

std::shared_ptr<const Geometry> Geometry::box(double x, double y, double z) {
  requirePositive("Box", "x", x);
  requirePositive("Box", "y", y);
  requirePositive("Box", "z", z);
  return std::shared_ptr<const Geometry>(
      new Geometry(GeometryType::kBox, {x, y, z}, tessellateBox(x, y, z), {}));
}

std::shared_ptr<const Geometry> Geometry::sphere(double radius) {
  requirePositive("Sphere", "radius", radius);
  return std::shared_ptr<const Geometry>(
      new Geometry(GeometryType::kSphere, {radius}, tessellateSphere(radius), {}));
}

std::shared_ptr<const Geometry> Geometry::cylinder(double radius, double height) {
  requirePositive("Cylinder", "radius", radius);
  requirePositive("Cylinder", "height", height);
  return std::shared_ptr<const Geometry>(new Geometry(
      GeometryType::kCylinder, {radius, height}, tessellateFrustum(radius, radius, height), {}));
}

std::shared_ptr<const Geometry> Geometry::cone(double radius, double height) {
  requirePositive("Cone", "radius", radius);
  requirePositive("Cone", "height", height);
  return std::shared_ptr<const Geometry>(new Geometry(GeometryType::kCone, {radius, height},
                                                      tessellateFrustum(0.0, radius, height), {}));
}

std::shared_ptr<const Geometry> Geometry::frustum(double bottomRadius, double topRadius,
                                                  double height) {
  requireNonNegative("Frustum", "bottom radius", bottomRadius);
  requireNonNegative("Frustum", "top radius", topRadius);
  requirePositive("Frustum", "the larger radius", std::max(bottomRadius, topRadius));
  requirePositive("Frustum", "height", height);
  return std::shared_ptr<const Geometry>(
      new Geometry(GeometryType::kFrustum, {bottomRadius, topRadius, height},
                   tessellateFrustum(bottomRadius, topRadius, height), {}));
}

std::shared_ptr<const Geometry> Geometry::tube(double radius, double thickness, double height) {
  requireNonNegative("Tube", "radius", radius);
  requirePositive("Tube", "thickness", thickness);
  requirePositive("Tube", "height", height);
  return std::shared_ptr<const Geometry>(
      new Geometry(GeometryType::kTube, {radius, thickness, height},
                   tessellateTube(radius, radius + thickness, height), {}));
}

std::shared_ptr<const Geometry> Geometry::plane() {
  return std::shared_ptr<const Geometry>(
      new Geometry(GeometryType::kPlane, {}, tessellatePlane(), {}));
}

std::shared_ptr<const Geometry> Geometry::mesh(std::shared_ptr<const TriMesh> mesh,
                                               std::string sourceFile) {
  validateMesh(mesh.get(), sourceFile);
  return std::shared_ptr<const Geometry>(
      new Geometry(GeometryType::kMesh, {}, std::move(mesh), std::move(sourceFile)));
}

}  // namespace rw::geometry
