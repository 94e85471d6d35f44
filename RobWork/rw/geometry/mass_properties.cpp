#include "rw/geometry/mass_properties.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rw::geometry {

namespace {

using rw::math::Vector3D;

/// A mesh whose |volume| is below this fraction of its bounding-box diagonal cubed is flat.
constexpr double kFlatVolumeRatio = 1e-9;

/// Inertia tensor about the origin of a body with second moments C = integral of r r^T dV.
Eigen::Matrix3d inertiaFromSecondMoments(const Eigen::Matrix3d& C) {
  return C.trace() * Eigen::Matrix3d::Identity() - C;
}

/// A solid with the given volume, centroid and principal moments (per unit density).
SolidProperties makeSolid(double volume, const Vector3D& centroid, double ixx, double iyy,
                          double izz) {
  SolidProperties s;
  s.volume = volume;
  s.centroid = centroid;
  s.inertia = Vector3D(ixx, iyy, izz).asDiagonal();
  return s;
}

Eigen::Matrix3d symmetrised(const Eigen::Matrix3d& m) { return 0.5 * (m + m.transpose()); }

}  // namespace

Eigen::Matrix3d parallelAxisTerm(double mass, const Vector3D& d) {
  return mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

SolidProperties meshSolidProperties(const TriMesh& mesh) {
  if (mesh.vertices.empty() || mesh.triangles.empty()) return {};
  Aabb box;
  for (const Vector3D& v : mesh.vertices) box.extend(v);
  // Tetrahedra are spanned from the box centre rather than the origin, which keeps the sums
  // well conditioned for meshes far from their frame's origin.
  const Vector3D ref = 0.5 * (box.min + box.max);
  double volume = 0.0;
  Vector3D firstMoment = Vector3D::Zero();
  Eigen::Matrix3d secondMoment = Eigen::Matrix3d::Zero();
  for (const auto& t : mesh.triangles) {
    const Vector3D a = mesh.vertices[t[0]] - ref;
    const Vector3D b = mesh.vertices[t[1]] - ref;
    const Vector3D c = mesh.vertices[t[2]] - ref;
    // Tetrahedron (ref, a, b, c): signed volume v = a.(b x c) / 6, centroid (a + b + c) / 4,
    // integral of r r^T = v / 20 * (a a^T + b b^T + c c^T + s s^T) with s = a + b + c.
    const double v = a.dot(b.cross(c)) / 6.0;
    const Vector3D s = a + b + c;
    volume += v;
    firstMoment += v * s / 4.0;
    secondMoment +=
        v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  if (volume < 0.0) {  // wound clockwise: every term has the opposite sign
    volume = -volume;
    firstMoment = -firstMoment;
    secondMoment = -secondMoment;
  }
  const double size = (box.max - box.min).norm();
  if (!(volume > kFlatVolumeRatio * size * size * size)) return {};
  const Vector3D g = firstMoment / volume;
  const Eigen::Matrix3d aboutCentroid = secondMoment - volume * g * g.transpose();
  SolidProperties result;
  result.volume = volume;
  result.centroid = ref + g;
  result.inertia = symmetrised(inertiaFromSecondMoments(aboutCentroid));
  return result;
}

SolidProperties boxSolidProperties(double x, double y, double z) {
  const double v = x * y * z;
  return makeSolid(v, Vector3D::Zero(), v * (y * y + z * z) / 12.0, v * (x * x + z * z) / 12.0,
                   v * (x * x + y * y) / 12.0);
}

SolidProperties sphereSolidProperties(double radius) {
  const double v = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  const double i = 0.4 * v * radius * radius;
  return makeSolid(v, Vector3D::Zero(), i, i, i);
}

SolidProperties cylinderSolidProperties(double radius, double height) {
  const double r2 = radius * radius;
  const double v = std::numbers::pi * r2 * height;
  const double ixx = v * (3.0 * r2 + height * height) / 12.0;
  return makeSolid(v, Vector3D::Zero(), ixx, ixx, 0.5 * v * r2);
}

SolidProperties coneSolidProperties(double radius, double height) {
  const double r2 = radius * radius;
  const double v = std::numbers::pi * r2 * height / 3.0;
  // The centroid lies a quarter of the height from the base (at +h/2) towards the apex.
  const double ixx = v * (3.0 * r2 / 20.0 + 3.0 * height * height / 80.0);
  return makeSolid(v, Vector3D(0.0, 0.0, height / 4.0), ixx, ixx, 0.3 * v * r2);
}

SolidProperties frustumSolidProperties(double bottomRadius, double topRadius, double height) {
  // Stacked disks of radius rho(z), linear in z: the volume, first and second moments are
  // integrals of polynomials of degree <= 4 in z, which 3-point Gauss-Legendre integrates exactly.
  constexpr std::array<double, 3> kNodes = {-0.77459666924148338, 0.0, 0.77459666924148338};
  constexpr std::array<double, 3> kWeights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double v = 0.0;
  double zMoment = 0.0;
  double z2Moment = 0.0;
  double r4 = 0.0;
  for (std::size_t k = 0; k < kNodes.size(); ++k) {
    const double z = 0.5 * height * kNodes[k];
    const double rho = bottomRadius + (topRadius - bottomRadius) * (z / height + 0.5);
    const double area = std::numbers::pi * rho * rho;
    const double w = 0.5 * height * kWeights[k];
    v += w * area;
    zMoment += w * area * z;
    z2Moment += w * area * z * z;
    r4 += w * area * rho * rho;
  }
  const double cz = zMoment / v;
  // A disk of radius rho has 1/4 m rho^2 about a diameter and 1/2 m rho^2 about its axis.
  const double ixx = 0.25 * r4 + z2Moment - v * cz * cz;
  return makeSolid(v, Vector3D(0.0, 0.0, cz), ixx, ixx, 0.5 * r4);
}

SolidProperties tubeSolidProperties(double radius, double thickness, double height) {
  const double inner2 = radius * radius;
  const double outer = radius + thickness;
  const double outer2 = outer * outer;
  const double v = std::numbers::pi * (outer2 - inner2) * height;
  const double ixx = v * (3.0 * (outer2 + inner2) + height * height) / 12.0;
  return makeSolid(v, Vector3D::Zero(), ixx, ixx, 0.5 * v * (outer2 + inner2));
}

SolidProperties solidProperties(const Geometry& geometry) {
  const std::vector<double>& p = geometry.parameters();
  switch (geometry.type()) {
    case GeometryType::kBox:
      return boxSolidProperties(p[0], p[1], p[2]);
    case GeometryType::kSphere:
      return sphereSolidProperties(p[0]);
    case GeometryType::kCylinder:
      return cylinderSolidProperties(p[0], p[1]);
    case GeometryType::kCone:
      return coneSolidProperties(p[0], p[1]);
    case GeometryType::kTube:
      return tubeSolidProperties(p[0], p[1], p[2]);
    case GeometryType::kFrustum:
      return frustumSolidProperties(p[0], p[1], p[2]);
    case GeometryType::kPlane:
      return {};
    case GeometryType::kMesh:
      return meshSolidProperties(geometry.triangles());
  }
  return {};
}

SolidProperties transformSolid(const SolidProperties& solid, const rw::math::Transform3D& X_AB) {
  SolidProperties out;
  out.volume = solid.volume;
  out.centroid = X_AB * solid.centroid;
  const Eigen::Matrix3d R = X_AB.linear();
  out.inertia = symmetrised(R * solid.inertia * R.transpose());
  return out;
}

BodyMassProperties estimateMassProperties(double mass, const std::vector<PlacedGeometry>& geometry,
                                          const std::optional<Vector3D>& cog) {
  if (!std::isfinite(mass) || !(mass > 0.0)) {
    throw std::invalid_argument("estimateMassProperties: mass must be finite and > 0, got " +
                                std::to_string(mass));
  }
  std::vector<SolidProperties> solids;
  double volume = 0.0;
  Vector3D weighted = Vector3D::Zero();
  for (const PlacedGeometry& placed : geometry) {
    if (!placed.geometry) throw std::invalid_argument("estimateMassProperties: null geometry");
    const SolidProperties s = solidProperties(*placed.geometry);
    if (!(s.volume > 0.0)) continue;
    solids.push_back(transformSolid(s, placed.X_body_geometry));
    volume += s.volume;
    weighted += s.volume * solids.back().centroid;
  }
  BodyMassProperties result;
  result.mass = mass;
  if (solids.empty()) {
    result.cog = cog.value_or(Vector3D::Zero());
    const double r = kNoVolumeSphereRadius;
    result.inertia = 0.4 * mass * r * r * Eigen::Matrix3d::Identity();
    return result;
  }
  const double density = mass / volume;
  const Vector3D centroid = weighted / volume;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (const SolidProperties& s : solids) {
    inertia += density * s.inertia + parallelAxisTerm(density * s.volume, s.centroid - centroid);
  }
  result.fromGeometry = true;
  result.cog = cog.value_or(centroid);
  // About a given COG away from the centroid: I_cog = I_centroid + m (|d|^2 E - d d^T).
  result.inertia = symmetrised(inertia + parallelAxisTerm(mass, result.cog - centroid));
  return result;
}

}  // namespace rw::geometry
