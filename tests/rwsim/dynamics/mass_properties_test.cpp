// Mass properties of meshes and primitives (rw/geometry/mass_properties.hpp) against analytic
// values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "rw/geometry/mass_properties.hpp"
#include "support/test_support.hpp"

namespace {

using rw::geometry::Geometry;
using rw::geometry::PlacedGeometry;
using rw::geometry::SolidProperties;
using rw::geometry::TriMesh;
using rw::math::Transform3D;
using rw::math::Vector3D;

constexpr double kPi = std::numbers::pi;

/// Diagonal of a matrix as a vector, for EXPECT_VECTOR_NEAR.
Eigen::VectorXd diag(const Eigen::Matrix3d& m) { return m.diagonal(); }

/// The nine entries of a matrix, row-major.
Eigen::VectorXd entries(const Eigen::Matrix3d& m) {
  return Eigen::Map<const Eigen::Matrix<double, 9, 1>>(Eigen::Matrix3d(m.transpose()).data());
}

/// Point-mass shift written out: m (|d|^2 E - d d^T).
Eigen::Matrix3d shiftByHand(double m, const Vector3D& d) {
  Eigen::Matrix3d out;
  out << d.y() * d.y() + d.z() * d.z(), -d.x() * d.y(), -d.x() * d.z(),  //
      -d.x() * d.y(), d.x() * d.x() + d.z() * d.z(), -d.y() * d.z(),     //
      -d.x() * d.z(), -d.y() * d.z(), d.x() * d.x() + d.y() * d.y();
  return m * out;
}

/// Axis-aligned box [lo, hi] as a closed mesh wound counter-clockwise seen from outside.
TriMesh boxMesh(const Vector3D& lo, const Vector3D& hi) {
  TriMesh m;
  for (int k = 0; k < 8; ++k) {
    m.vertices.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                            (k & 4) ? hi.z() : lo.z());
  }
  const auto quad = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    m.triangles.push_back({a, b, c});
    m.triangles.push_back({a, c, d});
  };
  quad(0, 4, 6, 2);
  quad(1, 3, 7, 5);
  quad(0, 1, 5, 4);
  quad(2, 6, 7, 3);
  quad(0, 2, 3, 1);
  quad(4, 5, 7, 6);
  return m;
}

TriMesh reversed(TriMesh m) {
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

/// The L-shaped prism [0,2]x[0,1]x[0,1] united with [0,1]x[1,2]x[0,1], as one closed mesh:
/// the L polygon (0,0) (2,0) (2,1) (1,1) (1,2) (0,2) extruded from z = 0 to z = 1.
TriMesh lShapeMesh() {
  const std::vector<std::pair<double, double>> outline = {{0, 0}, {2, 0}, {2, 1},
                                                          {1, 1}, {1, 2}, {0, 2}};
  TriMesh m;
  for (const double z : {0.0, 1.0}) {
    for (const auto& [x, y] : outline) m.vertices.emplace_back(x, y, z);
  }
  const std::uint32_t n = 6;
  // The L is star-shaped from (0,0): a fan from vertex 0 triangulates it.
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    m.triangles.push_back({0, i + 1, i});          // bottom, normal -z
    m.triangles.push_back({n, n + i, n + i + 1});  // top, normal +z
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
  }
  return m;
}

TEST(MassProperties, UnitCubeMeshHasVolumeOneAndInertiaOneSixth) {
  const SolidProperties s = rw::geometry::meshSolidProperties(boxMesh({2, 3, 4}, {3, 4, 5}));
  EXPECT_NEAR(s.volume, 1.0, 1e-12);
  EXPECT_VECTOR_NEAR(s.centroid, Vector3D(2.5, 3.5, 4.5), 1e-12);
  // m = 1: m/12 (1 + 1) = 1/6 on the diagonal, no products of inertia.
  EXPECT_VECTOR_NEAR(entries(s.inertia), entries(Eigen::Matrix3d::Identity() / 6.0), 1e-12);
}

TEST(MassProperties, WindingDirectionDoesNotMatter) {
  const TriMesh cube = boxMesh({-1, 0, 0}, {1, 1, 3});
  const SolidProperties a = rw::geometry::meshSolidProperties(cube);
  const SolidProperties b = rw::geometry::meshSolidProperties(reversed(cube));
  EXPECT_NEAR(a.volume, 6.0, 1e-12);
  EXPECT_NEAR(b.volume, a.volume, 1e-12);
  EXPECT_VECTOR_NEAR(b.centroid, a.centroid, 1e-12);
  EXPECT_VECTOR_NEAR(entries(b.inertia), entries(a.inertia), 1e-12);
}

TEST(MassProperties, TessellatedCylinderMatchesThePrismExactlyAndTheCylinderApproximately) {
  const double r = 0.05;
  const double h = 0.2;
  const auto cylinder = Geometry::cylinder(r, h);
  const SolidProperties mesh = rw::geometry::meshSolidProperties(cylinder->triangles());
  // The tessellation is a prism over a regular n-gon inscribed in the circle.
  const double n = 32;
  const double theta = 2 * kPi / n;
  const double area = n / 2 * r * r * std::sin(theta);
  // Polar moment of the n-gon: n triangles (0, a, b) with |a| = |b| = r, angle theta between
  // them: each A/6 (a.a + b.b + a.b) = r^4 sin(theta) (2 + cos(theta)) / 12.
  const double polar = n * std::pow(r, 4) * std::sin(theta) * (2 + std::cos(theta)) / 12;
  EXPECT_NEAR(mesh.volume, area * h, 1e-14);
  EXPECT_VECTOR_NEAR(mesh.centroid, Vector3D::Zero(), 1e-14);
  const Eigen::Vector3d prism(polar / 2 * h + area * h * h * h / 12,
                              polar / 2 * h + area * h * h * h / 12, polar * h);
  EXPECT_VECTOR_NEAR(diag(mesh.inertia), prism, 1e-14);
  // Against the true cylinder: the n-gon misses a fraction 1 - n sin(theta) / (2 pi) of the
  // area (0.64 % for n = 32); the moments miss a little more, below twice that.
  const SolidProperties exact = rw::geometry::solidProperties(*cylinder);
  const double missing = 1 - n * std::sin(theta) / (2 * kPi);
  EXPECT_NEAR(exact.volume, kPi * r * r * h, 1e-14);
  EXPECT_NEAR(mesh.volume / exact.volume, 1.0, missing * 1.0001);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(mesh.inertia(i, i) / exact.inertia(i, i), 1.0, 2 * missing) << "axis " << i;
    EXPECT_LT(mesh.inertia(i, i), exact.inertia(i, i));
  }
}

TEST(MassProperties, PrimitivesAgreeWithTheirTessellations) {
  // Round shapes are tessellated with 32 segments (and 16 stacks for the sphere): a few percent.
  const std::vector<std::shared_ptr<const Geometry>> shapes = {
      Geometry::box(0.1, 0.2, 0.3), Geometry::sphere(0.04), Geometry::cone(0.03, 0.12),
      Geometry::frustum(0.03, 0.02, 0.1), Geometry::tube(0.02, 0.01, 0.05)};
  for (const auto& shape : shapes) {
    SCOPED_TRACE(rw::geometry::geometryTypeName(shape->type()));
    const SolidProperties exact = rw::geometry::solidProperties(*shape);
    const SolidProperties mesh = rw::geometry::meshSolidProperties(shape->triangles());
    EXPECT_NEAR(mesh.volume / exact.volume, 1.0, 0.03);
    EXPECT_VECTOR_NEAR(mesh.centroid, exact.centroid, 1e-3);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(mesh.inertia(i, i) / exact.inertia(i, i), 1.0, 0.05);
  }
}

TEST(MassProperties, ConeCentroidIsAQuarterOfTheHeightFromTheBase) {
  // Apex at -h/2, base at +h/2: the centroid is h/4 below the base, at z = +h/4.
  const SolidProperties cone = rw::geometry::coneSolidProperties(0.1, 0.4);
  EXPECT_VECTOR_NEAR(cone.centroid, Vector3D(0, 0, 0.1), 1e-14);
  EXPECT_NEAR(cone.volume, kPi * 0.01 * 0.4 / 3, 1e-14);
  EXPECT_NEAR(cone.inertia(2, 2), 0.3 * cone.volume * 0.01, 1e-14);
  EXPECT_NEAR(cone.inertia(0, 0), cone.volume * (3.0 / 20 * 0.01 + 3.0 / 80 * 0.16), 1e-14);
}

TEST(MassProperties, FrustumMatchesCylinderConeAndTheFrustumVolume) {
  // Equal radii: the cylinder; a zero bottom radius: the cone (apex at -h/2).
  const SolidProperties cylinder = rw::geometry::cylinderSolidProperties(0.05, 0.2);
  const SolidProperties asCylinder = rw::geometry::frustumSolidProperties(0.05, 0.05, 0.2);
  EXPECT_NEAR(asCylinder.volume, cylinder.volume, 1e-15);
  EXPECT_VECTOR_NEAR(asCylinder.centroid, cylinder.centroid, 1e-15);
  EXPECT_TRUE(asCylinder.inertia.isApprox(cylinder.inertia, 1e-12));
  const SolidProperties cone = rw::geometry::coneSolidProperties(0.1, 0.4);
  const SolidProperties asCone = rw::geometry::frustumSolidProperties(0.0, 0.1, 0.4);
  EXPECT_NEAR(asCone.volume, cone.volume, 1e-15);
  EXPECT_VECTOR_NEAR(asCone.centroid, cone.centroid, 1e-15);
  EXPECT_TRUE(asCone.inertia.isApprox(cone.inertia, 1e-12));
  // V = pi h / 3 (a^2 + a b + b^2); centroid h (a^2 + 2ab + 3b^2) / (4 (a^2 + ab + b^2)) above
  // the bottom.
  const double a = 0.04;
  const double b = 0.02;
  const double h = 0.1;
  const SolidProperties f = rw::geometry::frustumSolidProperties(a, b, h);
  EXPECT_NEAR(f.volume, kPi * h / 3 * (a * a + a * b + b * b), 1e-15);
  EXPECT_NEAR(f.centroid.z() + h / 2,
              h * (a * a + 2 * a * b + 3 * b * b) / (4 * (a * a + a * b + b * b)), 1e-15);
}

TEST(MassProperties, OffsetAndRotatedBoxByTheParallelAxisTheorem) {
  // Box a x b x c = 0.1 x 0.2 x 0.3, mass 2, turned 90 deg about z and placed at (0.1, 0, 0.05).
  const double m = 2.0;
  Transform3D X = rw::math::makeTransform(
      Eigen::AngleAxisd(kPi / 2, Vector3D::UnitZ()).toRotationMatrix(), Vector3D(0.1, 0, 0.05));
  const std::vector<PlacedGeometry> placed = {{Geometry::box(0.1, 0.2, 0.3), X}};

  // About its own centre (m/12 = 1/6): Ixx = (b^2 + c^2)/6 = 0.13/6, Iyy = (a^2 + c^2)/6 =
  // 0.10/6, Izz = (a^2 + b^2)/6 = 0.05/6. Turning about z swaps the x and y moments.
  const auto atCentroid = rw::geometry::estimateMassProperties(m, placed);
  EXPECT_TRUE(atCentroid.fromGeometry);
  EXPECT_VECTOR_NEAR(atCentroid.cog, Vector3D(0.1, 0, 0.05), 1e-14);
  Eigen::Matrix3d expected = Eigen::Vector3d(0.10 / 6, 0.13 / 6, 0.05 / 6).asDiagonal();
  EXPECT_VECTOR_NEAR(entries(atCentroid.inertia), entries(expected), 1e-14);

  // About a given COG at the body origin: d = (-0.1, 0, -0.05), |d|^2 = 0.0125:
  // Ixx += 2 (0.0125 - 0.01) = 0.005, Iyy += 2 * 0.0125 = 0.025, Izz += 2 (0.0125 - 0.0025) =
  // 0.02, Ixz = Izx = -2 * (-0.1)(-0.05) = -0.01.
  const auto atOrigin = rw::geometry::estimateMassProperties(m, placed, Vector3D::Zero());
  EXPECT_VECTOR_NEAR(atOrigin.cog, Vector3D::Zero(), 0.0);
  expected << 0.10 / 6 + 0.005, 0, -0.01,  //
      0, 0.13 / 6 + 0.025, 0,              //
      -0.01, 0, 0.05 / 6 + 0.02;
  EXPECT_VECTOR_NEAR(entries(atOrigin.inertia), entries(expected), 1e-14);
}

TEST(MassProperties, LShapedMeshEqualsItsTwoBoxesShiftedToTheCombinedCog) {
  const TriMesh l = lShapeMesh();
  EXPECT_FALSE(Geometry::mesh(std::make_shared<const TriMesh>(l), "L")->isConvex());
  const SolidProperties s = rw::geometry::meshSolidProperties(l);
  // Box A: 2 x 1 x 1 centred at (1, 0.5, 0.5), volume 2; box B: 1 x 1 x 1 at (0.5, 1.5, 0.5).
  const Vector3D cA(1, 0.5, 0.5);
  const Vector3D cB(0.5, 1.5, 0.5);
  const Vector3D c = (2 * cA + cB) / 3;  // (5/6, 5/6, 1/2)
  EXPECT_NEAR(s.volume, 3.0, 1e-12);
  EXPECT_VECTOR_NEAR(s.centroid, Vector3D(5.0 / 6, 5.0 / 6, 0.5), 1e-12);
  // Unit density: box A (1 + 1)/12 * 2, (4 + 1)/12 * 2, (4 + 1)/12 * 2; box B 1/6 each.
  const Eigen::Matrix3d IA = Eigen::Vector3d(2.0 / 6, 10.0 / 12, 10.0 / 12).asDiagonal();
  const Eigen::Matrix3d IB = Eigen::Matrix3d::Identity() / 6;
  const Eigen::Matrix3d expected = IA + shiftByHand(2, cA - c) + IB + shiftByHand(1, cB - c);
  EXPECT_VECTOR_NEAR(entries(s.inertia), entries(expected), 1e-12);

  // The same body as two placed boxes, with a total mass of 6 (density 2).
  const std::vector<PlacedGeometry> boxes = {
      {Geometry::box(2, 1, 1), rw::math::makeTranslation(cA)},
      {Geometry::box(1, 1, 1), rw::math::makeTranslation(cB)}};
  const auto body = rw::geometry::estimateMassProperties(6.0, boxes);
  EXPECT_VECTOR_NEAR(body.cog, c, 1e-12);
  EXPECT_VECTOR_NEAR(entries(body.inertia), entries(2 * expected), 1e-12);
}

TEST(MassProperties, MassIsSplitByVolume) {
  // A 1 m^3 cube and a 7 m^3 box along x: mass 8 gives density 1; the COG is volume-weighted.
  const std::vector<PlacedGeometry> parts = {
      {Geometry::box(1, 1, 1), rw::math::makeTranslation(Vector3D(-4, 0, 0))},
      {Geometry::box(7, 1, 1), rw::math::makeTranslation(Vector3D(0, 0, 0))}};
  const auto body = rw::geometry::estimateMassProperties(8.0, parts);
  EXPECT_VECTOR_NEAR(body.cog, Vector3D(-0.5, 0, 0), 1e-12);
  // Iyy: cube 1/6 + 1 * 3.5^2, box 7 (49 + 1)/12 + 7 * 0.5^2.
  EXPECT_NEAR(body.inertia(1, 1), 1.0 / 6 + 12.25 + 7 * 50.0 / 12 + 1.75, 1e-12);
}

TEST(MassProperties, PlanesAndFlatMeshesHaveNoVolume) {
  EXPECT_EQ(rw::geometry::solidProperties(*Geometry::plane()).volume, 0.0);
  TriMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  flat.triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(rw::geometry::meshSolidProperties(flat).volume, 0.0);
  EXPECT_EQ(rw::geometry::meshSolidProperties(TriMesh{}).volume, 0.0);

  // A plane next to a box: only the box counts.
  const std::vector<PlacedGeometry> parts = {
      {Geometry::plane(), Transform3D::Identity()},
      {Geometry::box(1, 1, 1), rw::math::makeTranslation(Vector3D(0, 0, 1))}};
  const auto body = rw::geometry::estimateMassProperties(1.0, parts);
  EXPECT_VECTOR_NEAR(body.cog, Vector3D(0, 0, 1), 1e-14);
  EXPECT_VECTOR_NEAR(diag(body.inertia), Eigen::Vector3d::Constant(1.0 / 6), 1e-14);
}

TEST(MassProperties, WithoutVolumeASmallSolidSphereStandsIn) {
  const auto body = rw::geometry::estimateMassProperties(
      0.5, {{Geometry::plane(), Transform3D::Identity()}}, Vector3D(0, 0, 0.1));
  EXPECT_FALSE(body.fromGeometry);
  EXPECT_VECTOR_NEAR(body.cog, Vector3D(0, 0, 0.1), 0.0);
  const double i = 0.4 * 0.5 * 1e-4 * 1e-4;
  EXPECT_VECTOR_NEAR(entries(body.inertia), entries(i * Eigen::Matrix3d::Identity()), 1e-24);
  EXPECT_FALSE(rw::geometry::estimateMassProperties(1.0, {}).fromGeometry);
}

TEST(MassProperties, RejectsANonPositiveMass) {
  EXPECT_THROW(rw::geometry::estimateMassProperties(0.0, {}), std::invalid_argument);
  EXPECT_THROW(rw::geometry::estimateMassProperties(-1.0, {}), std::invalid_argument);
  EXPECT_THROW(rw::geometry::estimateMassProperties(std::nan(""), {}), std::invalid_argument);
}

}  // namespace
