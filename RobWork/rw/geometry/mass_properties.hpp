#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/math/types.hpp"

namespace rw::geometry {

/// Volume integrals of a uniform solid of density 1 (so mass = volume).
struct SolidProperties {
  /// Volume in m^3 (0 for shapes without volume: planes, flat or empty meshes).
  double volume = 0.0;
  /// Centroid in the shape's frame.
  rw::math::Vector3D centroid = rw::math::Vector3D::Zero();
  /// Inertia tensor about the centroid, shape-frame axes, per unit density (m^5).
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// Exact volume, centroid and inertia of the solid bounded by a closed, consistently wound
/// triangle mesh (sum of signed tetrahedra spanned from a reference point by each triangle).
/// A mesh wound clockwise gives the same result as wound counter-clockwise. An open mesh gives
/// a value that depends on the reference point; a flat or empty mesh gives volume 0.
SolidProperties meshSolidProperties(const TriMesh& mesh);

/// Box with full edge lengths x, y, z centred at the origin.
SolidProperties boxSolidProperties(double x, double y, double z);
/// Solid sphere centred at the origin.
SolidProperties sphereSolidProperties(double radius);
/// Solid cylinder along z from -h/2 to +h/2.
SolidProperties cylinderSolidProperties(double radius, double height);
/// Solid cone along z, base disk at +h/2, apex at -h/2 (Geometry::cone's convention).
SolidProperties coneSolidProperties(double radius, double height);
/// Solid frustum along z: disk of `bottomRadius` at -h/2, of `topRadius` at +h/2.
SolidProperties frustumSolidProperties(double bottomRadius, double topRadius, double height);
/// Hollow cylinder along z: inner radius `radius`, outer `radius + thickness`, from -h/2 to h/2.
SolidProperties tubeSolidProperties(double radius, double thickness, double height);

/// Properties of a geometry: the analytic values for Box, Sphere, Cylinder, Cone and Tube (not
/// their tessellation), the exact mesh integrals for meshes, volume 0 for a Plane.
SolidProperties solidProperties(const Geometry& geometry);

/// The same solid seen from another frame: `X_AB` maps the solid's frame B into frame A.
SolidProperties transformSolid(const SolidProperties& solid, const rw::math::Transform3D& X_AB);

/// Inertia tensor of a point mass `mass` at offset `d` from the reference point:
/// mass * (|d|^2 E - d d^T) (the parallel-axis term).
Eigen::Matrix3d parallelAxisTerm(double mass, const rw::math::Vector3D& d);

/// One geometry placed in a body frame.
struct PlacedGeometry {
  /// The shape (not null).
  std::shared_ptr<const Geometry> geometry;
  /// Pose of the geometry in the body frame.
  rw::math::Transform3D X_body_geometry = rw::math::Transform3D::Identity();
};

/// Radius of the solid sphere whose inertia stands in for a body without volume (RobWork's
/// choice, reference §2.4).
inline constexpr double kNoVolumeSphereRadius = 1e-4;

/// Mass properties of a body in its body frame.
struct BodyMassProperties {
  /// Mass in kg.
  double mass = 0.0;
  /// Centre of mass in the body frame.
  rw::math::Vector3D cog = rw::math::Vector3D::Zero();
  /// Inertia tensor about `cog` (not about the body origin), body-frame axes, kg m^2.
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  /// False when the geometry had no volume and the small-sphere fallback was used.
  bool fromGeometry = false;
};

/// Estimates the mass properties of a body of total mass `mass` spread uniformly over the
/// volume of its geometries (RobWork's EstimateInertia): each geometry gets mass in proportion
/// to its volume, the COG is the volume-weighted centroid and the inertia is combined with the
/// parallel-axis theorem. Geometries without volume (planes, flat meshes) are ignored.
/// If `cog` is given it replaces the centroid and the inertia is taken about it.
/// Unlike RobWork (which returns the tensor about the body origin and uses it as if about the
/// COG, reference §2.4 and Appendix A.10), the tensor is about the COG.
/// When no geometry has volume, `fromGeometry` is false, the COG is `cog` or the origin and the
/// inertia that of a solid sphere of radius kNoVolumeSphereRadius (the caller warns).
/// Overlapping geometries are counted twice.
/// @throws std::invalid_argument unless mass is finite and > 0, or if a geometry is null.
BodyMassProperties estimateMassProperties(double mass, const std::vector<PlacedGeometry>& geometry,
                                          const std::optional<rw::math::Vector3D>& cog = {});

}  // namespace rw::geometry
