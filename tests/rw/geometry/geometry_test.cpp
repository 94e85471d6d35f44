#include "rw/geometry/geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "mesh_checks.hpp"
#include "support/test_support.hpp"

namespace {

using rw::geometry::Geometry;
using rw::geometry::GeometryType;
using rw::geometry::TriMesh;
using rw::math::Vector3D;
using visgrab::test::isClosedAndConsistent;
using visgrab::test::signedVolume;

constexpr double kPi = std::numbers::pi;

/// Number of vertices on the circle of `radius` at height z (the segment count of a ring).
int ringVertexCount(const TriMesh& mesh, double radius, double z) {
  int count = 0;
  for (const Vector3D& v : mesh.vertices) {
    if (std::abs(v.z() - z) < 1e-12 && std::abs(v.head<2>().norm() - radius) < 1e-12) ++count;
  }
  return count;
}

/// Area of a regular n-gon inscribed in a circle of `radius`.
double inscribedPolygonArea(int n, double radius) {
  return 0.5 * n * radius * radius * std::sin(2.0 * kPi / n);
}

/// Expects the tessellation to be closed, outward wound and inside the exact bounds.
void expectClosedOutwardInside(const Geometry& g) {
  const TriMesh& mesh = g.triangles();
  EXPECT_TRUE(isClosedAndConsistent(mesh));
  EXPECT_GT(signedVolume(mesh), 0.0);
  for (const Vector3D& v : mesh.vertices) {
    EXPECT_TRUE((v.array() >= g.bounds().min.array() - 1e-12).all()) << v.transpose();
    EXPECT_TRUE((v.array() <= g.bounds().max.array() + 1e-12).all()) << v.transpose();
  }
}

void expectBounds(const Geometry& g, const Vector3D& halfExtent) {
  EXPECT_EQ(g.bounds().min, -halfExtent);
  EXPECT_EQ(g.bounds().max, halfExtent);
}

/// Expects `make` to throw std::invalid_argument whose message is exactly `message`.
void expectInvalid(const std::function<void()>& make, const std::string& message) {
  try {
    make();
    ADD_FAILURE() << "no exception, expected: " << message;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

/// Tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1) whose base z = 0 is a fan around vertex 4 at
/// (0.25, 0.25, baseZ): baseZ < 0 bulges out (still convex), baseZ > 0 dents in.
std::shared_ptr<TriMesh> tetrahedronWithApexOnBase(double baseZ) {
  auto mesh = std::make_shared<TriMesh>();
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25, 0.25, baseZ}};
  mesh->triangles = {{0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {4, 1, 0}, {4, 2, 1}, {4, 0, 2}};
  return mesh;
}

TEST(GeometryTest, BoxIsTwelveOutwardTrianglesWithExactVolume) {
  const auto box = Geometry::box(0.1, 0.2, 0.4);
  EXPECT_EQ(box->type(), GeometryType::kBox);
  EXPECT_EQ(box->parameters(), (std::vector<double>{0.1, 0.2, 0.4}));
  EXPECT_TRUE(box->sourceFile().empty());
  EXPECT_EQ(box->triangles().triangles.size(), 12U);
  EXPECT_EQ(box->triangles().vertices.size(), 8U);
  EXPECT_NEAR(signedVolume(box->triangles()), 0.1 * 0.2 * 0.4, 1e-15);
  expectClosedOutwardInside(*box);
  expectBounds(*box, Vector3D(0.05, 0.1, 0.2));
  EXPECT_TRUE(box->isConvex());
  EXPECT_EQ(box->trianglesPtr().get(), &box->triangles());
}

TEST(GeometryTest, SphereVolumeLiesBetweenInscribedBallAndSphere) {
  const double r = 0.3;
  const auto sphere = Geometry::sphere(r);
  const TriMesh& mesh = sphere->triangles();
  for (const Vector3D& v : mesh.vertices) EXPECT_NEAR(v.norm(), r, 1e-12);
  // The polyhedron is inscribed in the sphere and contains the ball whose radius is the smallest
  // distance from the centre to a face plane.
  double nearestFace = r;
  for (const auto& t : mesh.triangles) {
    const Vector3D& a = mesh.vertices[t[0]];
    const Vector3D n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
    nearestFace = std::min(nearestFace, n.dot(a));
  }
  const double volume = signedVolume(mesh);
  const double ballVolume = 4.0 / 3.0 * kPi;
  EXPECT_GT(volume, ballVolume * std::pow(nearestFace, 3));
  EXPECT_LT(volume, ballVolume * std::pow(r, 3));
  EXPECT_GT(nearestFace, 0.98 * r);  // fine enough for contact and drawing
  expectClosedOutwardInside(*sphere);
  expectBounds(*sphere, Vector3D::Constant(r));
  EXPECT_TRUE(sphere->isConvex());
  EXPECT_EQ(sphere->parameters(), std::vector<double>{r});
}

TEST(GeometryTest, CylinderVolumeIsInscribedPrism) {
  const double r = 0.05;
  const double h = 0.2;
  const auto cylinder = Geometry::cylinder(r, h);
  const TriMesh& mesh = cylinder->triangles();
  const int n = ringVertexCount(mesh, r, h / 2);
  EXPECT_GE(n, 16);
  EXPECT_EQ(ringVertexCount(mesh, r, -h / 2), n);
  EXPECT_NEAR(signedVolume(mesh), inscribedPolygonArea(n, r) * h, 1e-15);
  expectClosedOutwardInside(*cylinder);
  expectBounds(*cylinder, Vector3D(r, r, h / 2));
  EXPECT_TRUE(cylinder->isConvex());
  EXPECT_EQ(cylinder->parameters(), (std::vector<double>{r, h}));
}

TEST(GeometryTest, ConeHasApexAtMinusHalfHeightAndPyramidVolume) {
  const double r = 0.04;
  const double h = 0.1;
  const auto cone = Geometry::cone(r, h);
  const TriMesh& mesh = cone->triangles();
  const int n = ringVertexCount(mesh, r, h / 2);
  EXPECT_GE(n, 16);
  EXPECT_EQ(ringVertexCount(mesh, 0.0, -h / 2), 1);  // the apex
  EXPECT_NEAR(signedVolume(mesh), inscribedPolygonArea(n, r) * h / 3.0, 1e-15);
  expectClosedOutwardInside(*cone);
  expectBounds(*cone, Vector3D(r, r, h / 2));
  EXPECT_TRUE(cone->isConvex());
}

TEST(GeometryTest, FrustumIsAClosedConvexSolidBetweenTwoRings) {
  const double bottom = 0.04;
  const double top = 0.025;
  const double h = 0.1;
  const auto frustum = Geometry::frustum(bottom, top, h);
  const TriMesh& mesh = frustum->triangles();
  const int n = ringVertexCount(mesh, bottom, -h / 2);
  EXPECT_EQ(ringVertexCount(mesh, top, h / 2), n);
  // Similar polygons: V = h / 3 (A1 + A2 + sqrt(A1 A2)).
  const double a1 = inscribedPolygonArea(n, bottom);
  const double a2 = inscribedPolygonArea(n, top);
  EXPECT_NEAR(signedVolume(mesh), h / 3 * (a1 + a2 + std::sqrt(a1 * a2)), 1e-15);
  expectClosedOutwardInside(*frustum);
  expectBounds(*frustum, Vector3D(bottom, bottom, h / 2));
  EXPECT_TRUE(frustum->isConvex());
  EXPECT_EQ(frustum->parameters(), (std::vector<double>{bottom, top, h}));
  // A zero radius is an apex, as in a cone.
  const auto cone = Geometry::frustum(0.03, 0.0, h);
  EXPECT_EQ(ringVertexCount(cone->triangles(), 0.0, h / 2), 1);
  expectClosedOutwardInside(*cone);
  EXPECT_THROW(Geometry::frustum(0.0, 0.0, h), std::invalid_argument);
  EXPECT_THROW(Geometry::frustum(-0.01, 0.02, h), std::invalid_argument);
}

TEST(GeometryTest, TubeIsClosedAnnularSolid) {
  const double inner = 0.02;
  const double thickness = 0.01;
  const double h = 0.1;
  const auto tube = Geometry::tube(inner, thickness, h);
  const TriMesh& mesh = tube->triangles();
  const double outer = inner + thickness;
  const int n = ringVertexCount(mesh, outer, h / 2);
  EXPECT_GE(n, 16);
  EXPECT_EQ(ringVertexCount(mesh, inner, h / 2), n);
  const double expected = (inscribedPolygonArea(n, outer) - inscribedPolygonArea(n, inner)) * h;
  EXPECT_NEAR(signedVolume(mesh), expected, 1e-15);
  expectClosedOutwardInside(*tube);
  expectBounds(*tube, Vector3D(outer, outer, h / 2));
  EXPECT_FALSE(tube->isConvex());
  EXPECT_EQ(tube->parameters(), (std::vector<double>{inner, thickness, h}));
}

TEST(GeometryTest, TubeWithZeroInnerRadiusIsAllowed) {
  const auto tube = Geometry::tube(0.0, 0.05, 0.2);
  const int n = ringVertexCount(tube->triangles(), 0.05, 0.1);
  EXPECT_NEAR(signedVolume(tube->triangles()), inscribedPolygonArea(n, 0.05) * 0.2, 1e-15);
  EXPECT_TRUE(isClosedAndConsistent(tube->triangles()));
}

TEST(GeometryTest, PlaneIsTenMetreSquareFacingUpWithInfiniteBounds) {
  const auto plane = Geometry::plane();
  const TriMesh& mesh = plane->triangles();
  ASSERT_EQ(mesh.triangles.size(), 2U);
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vector3D& a = mesh.vertices[t[0]];
    const Vector3D normal = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    EXPECT_GT(normal.z(), 0.0);
    area += normal.norm() / 2.0;
  }
  EXPECT_NEAR(area, 100.0, 1e-12);
  for (const Vector3D& v : mesh.vertices) {
    EXPECT_EQ(v.z(), 0.0);
    EXPECT_EQ(std::abs(v.x()), 5.0);
    EXPECT_EQ(std::abs(v.y()), 5.0);
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(plane->bounds().min, Vector3D(-kInf, -kInf, 0.0));
  EXPECT_EQ(plane->bounds().max, Vector3D(kInf, kInf, 0.0));
  EXPECT_FALSE(plane->isConvex());
  EXPECT_TRUE(plane->parameters().empty());
}

TEST(GeometryTest, FactoriesRejectBadParameters) {
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  expectInvalid([] { Geometry::box(-1, 1, 1); }, "Box: x must be > 0, got -1");
  expectInvalid([] { Geometry::box(1, 0, 1); }, "Box: y must be > 0, got 0");
  expectInvalid([&] { Geometry::box(1, 1, kNan); }, "Box: z must be finite and > 0, got nan");
  expectInvalid([] { Geometry::sphere(0); }, "Sphere: radius must be > 0, got 0");
  expectInvalid([] { Geometry::cylinder(0.5, -2); }, "Cylinder: height must be > 0, got -2");
  expectInvalid([&] { Geometry::cone(kInf, 1); }, "Cone: radius must be finite and > 0, got inf");
  expectInvalid([] { Geometry::tube(-0.1, 0.1, 1); }, "Tube: radius must be >= 0, got -0.1");
  expectInvalid([] { Geometry::tube(0.1, 0, 1); }, "Tube: thickness must be > 0, got 0");
  expectInvalid([] { Geometry::tube(0.1, 0.1, 0); }, "Tube: height must be > 0, got 0");
}

TEST(GeometryTest, TypeNamesMatchWorkcellXml) {
  EXPECT_STREQ(geometryTypeName(GeometryType::kBox), "Box");
  EXPECT_STREQ(geometryTypeName(GeometryType::kSphere), "Sphere");
  EXPECT_STREQ(geometryTypeName(GeometryType::kCylinder), "Cylinder");
  EXPECT_STREQ(geometryTypeName(GeometryType::kCone), "Cone");
  EXPECT_STREQ(geometryTypeName(GeometryType::kTube), "Tube");
  EXPECT_STREQ(geometryTypeName(GeometryType::kPlane), "Plane");
  EXPECT_STREQ(geometryTypeName(GeometryType::kMesh), "Polytope");
}

TEST(GeometryTest, MeshKeepsSourceAndComputesBoundsAndConvexity) {
  const auto mesh = Geometry::mesh(tetrahedronWithApexOnBase(-0.5), "parts/tetra.stl");
  EXPECT_EQ(mesh->type(), GeometryType::kMesh);
  EXPECT_EQ(mesh->sourceFile(), "parts/tetra.stl");
  EXPECT_TRUE(mesh->parameters().empty());
  EXPECT_EQ(mesh->bounds().min, Vector3D(0, 0, -0.5));
  EXPECT_EQ(mesh->bounds().max, Vector3D(1, 1, 1));
  EXPECT_TRUE(isClosedAndConsistent(mesh->triangles()));
  EXPECT_TRUE(mesh->isConvex());
}

TEST(GeometryTest, MeshConvexityToleranceIsOneMicrometre) {
  // A dent of 1e-7 m puts vertex (0,1,0) 4e-7 m in front of the dented face: within tolerance.
  EXPECT_TRUE(Geometry::mesh(tetrahedronWithApexOnBase(1e-7), "tiny-dent")->isConvex());
  EXPECT_FALSE(Geometry::mesh(tetrahedronWithApexOnBase(1e-5), "dent")->isConvex());
  EXPECT_FALSE(Geometry::mesh(tetrahedronWithApexOnBase(0.2), "deep-dent")->isConvex());
}

TEST(GeometryTest, MeshConvexitySkipsDegenerateTriangles) {
  auto mesh = tetrahedronWithApexOnBase(-0.5);
  mesh->vertices.emplace_back(0.5, 0.0, 0.0);  // on edge 0-1
  mesh->triangles.push_back({0, 1, 5});        // collinear: no plane
  mesh->triangles.push_back({2, 2, 3});        // repeated vertex
  EXPECT_TRUE(Geometry::mesh(mesh, "degenerate")->isConvex());
}

TEST(GeometryTest, MeshOfTessellatedPrimitivesAgreesWithPrimitiveConvexity) {
  for (const auto& g : {Geometry::box(1, 2, 3), Geometry::sphere(0.5), Geometry::cylinder(1, 2),
                        Geometry::cone(1, 2)}) {
    EXPECT_TRUE(Geometry::mesh(g->trianglesPtr(), "tessellation")->isConvex())
        << geometryTypeName(g->type());
  }
  EXPECT_FALSE(Geometry::mesh(Geometry::tube(1, 0.5, 2)->trianglesPtr(), "tube")->isConvex());
}

TEST(GeometryTest, MeshRejectsMissingOrInvalidTriangles) {
  expectInvalid([] { Geometry::mesh(nullptr, "a.stl"); }, "Polytope 'a.stl': mesh is null");
  expectInvalid([] { Geometry::mesh(std::make_shared<TriMesh>(), "b.stl"); },
                "Polytope 'b.stl': mesh has no triangles");
  auto bad = std::make_shared<TriMesh>();
  bad->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  bad->triangles = {{0, 1, 2}, {0, 1, 3}};
  expectInvalid([&] { Geometry::mesh(bad, "c.stl"); },
                "Polytope 'c.stl': triangle 1 refers to vertex 3 but the mesh has 3 vertices");
  bad->triangles.pop_back();
  bad->vertices[1].x() = std::numeric_limits<double>::quiet_NaN();
  expectInvalid([&] { Geometry::mesh(bad, "d.stl"); }, "Polytope 'd.stl': vertex 1 is not finite");
}

}  // namespace
