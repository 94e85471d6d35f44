// ContactShape::build: which representation each geometry gets, and its precomputed structure.
#include <gtest/gtest.h>

#include <cmath>

#include "contact_test_util.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "rwsim/contacts/shapes.hpp"
#include "support/test_support.hpp"

namespace rwsim::contacts {
namespace {

using detail::MeshShape;
using detail::Polytope;
using detail::PolytopeShape;
using rw::math::Vector3D;
using test::Geometry;
using test::TriMesh;

const PolytopeShape& asPolytopes(const ContactShape& s) {
  EXPECT_EQ(s.kind(), ContactShape::Kind::kConvex);
  return static_cast<const PolytopeShape&>(s);
}

/// Checks the polytope's faces: unit normals, every vertex on or behind every face plane,
/// every face's loop on its plane, and Euler's formula V - E + F = 2 (solid polytopes).
void expectValidPolytope(const Polytope& p) {
  for (const auto& f : p.faces()) {
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
    for (const Vector3D& v : p.vertices()) EXPECT_LE(f.normal.dot(v) - f.offset, 1e-9);
  }
  if (!p.flat()) {
    EXPECT_EQ(p.vertices().size() + p.faces().size(), p.edges().size() + 2);
  }
}

TEST(ContactShape, BoxIsSixQuads) {
  const auto shape = ContactShape::build(*Geometry::box(1, 2, 3));
  const Polytope& p = asPolytopes(*shape).pieces().at(0);
  EXPECT_EQ(p.vertices().size(), 8u);
  EXPECT_EQ(p.faces().size(), 6u);
  EXPECT_EQ(p.edges().size(), 12u);
  for (const auto& f : p.faces()) EXPECT_EQ(f.count, 4);
  expectValidPolytope(p);
  EXPECT_VECTOR_NEAR(shape->localBounds().max, Vector3D(0.5, 1, 1.5), 1e-12);
}

const detail::RoundShape& asRound(const ContactShape& s) {
  EXPECT_EQ(s.kind(), ContactShape::Kind::kRound);
  return static_cast<const detail::RoundShape&>(s);
}

TEST(ContactShape, CylinderIsRoundWithATessellationWhoseCapIsOneFace) {
  const auto shape = ContactShape::build(*Geometry::cylinder(0.05, 0.2));
  ASSERT_EQ(shape->kind(), ContactShape::Kind::kRound);
  const detail::RoundShape& round = asRound(*shape);
  EXPECT_EQ(round.bottomRadius(), 0.05);
  EXPECT_EQ(round.topRadius(), 0.05);
  EXPECT_EQ(round.halfHeight(), 0.1);
  EXPECT_VECTOR_NEAR(shape->localBounds().max, Vector3D(0.05, 0.05, 0.1), 1e-15);
  const Polytope& p = round.polytope();
  EXPECT_EQ(p.faces().size(), 34u);     // 32 sides + 2 caps
  EXPECT_EQ(p.vertices().size(), 64u);  // the cap centres are gone
  int caps = 0;
  for (const auto& f : p.faces()) {
    if (std::abs(std::abs(f.normal.z()) - 1.0) < 1e-12) {
      ++caps;
      EXPECT_EQ(f.count, 32);
      EXPECT_NEAR(std::abs(f.offset), 0.1, 1e-12);
    }
  }
  EXPECT_EQ(caps, 2);
  expectValidPolytope(p);
}

TEST(ContactShape, ConeIsRoundWithATessellationWithApexAndBase) {
  const auto shape = ContactShape::build(*Geometry::cone(0.05, 0.1));
  ASSERT_EQ(shape->kind(), ContactShape::Kind::kRound);
  const detail::RoundShape& round = asRound(*shape);
  EXPECT_EQ(round.bottomRadius(), 0.0);  // apex at -h/2
  EXPECT_EQ(round.topRadius(), 0.05);
  const Polytope& p = round.polytope();
  EXPECT_EQ(p.faces().size(), 33u);
  EXPECT_EQ(p.vertices().size(), 33u);
  expectValidPolytope(p);
}

TEST(ContactShape, SphereAndPlaneAreAnalytic) {
  const auto sphere = ContactShape::build(*Geometry::sphere(0.1));
  EXPECT_EQ(sphere->kind(), ContactShape::Kind::kSphere);
  EXPECT_VECTOR_NEAR(sphere->localBounds().min, Vector3D::Constant(-0.1), 0.0);
  const auto plane = ContactShape::build(*Geometry::plane());
  EXPECT_EQ(plane->kind(), ContactShape::Kind::kHalfSpace);
  EXPECT_EQ(plane->localBounds().max.z(), 0.0);
  EXPECT_TRUE(std::isinf(plane->localBounds().min.z()));
}

TEST(ContactShape, TubeIsOneConvexPiecePerSegment) {
  const auto shape = ContactShape::build(*Geometry::tube(0.04, 0.01, 0.1));
  const auto& pieces = asPolytopes(*shape).pieces();
  ASSERT_EQ(pieces.size(), 32u);
  for (const Polytope& p : pieces) {
    EXPECT_EQ(p.vertices().size(), 8u);
    EXPECT_EQ(p.faces().size(), 6u);
    expectValidPolytope(p);
  }
  EXPECT_NEAR(shape->localBounds().max.x(), 0.05, 1e-12);
}

TEST(ContactShape, SolidTubeHasWedgePieces) {
  const auto shape = ContactShape::build(*Geometry::tube(0.0, 0.05, 0.1));
  const auto& pieces = asPolytopes(*shape).pieces();
  ASSERT_EQ(pieces.size(), 32u);
  EXPECT_EQ(pieces[0].vertices().size(), 6u);
  EXPECT_EQ(pieces[0].faces().size(), 5u);
  expectValidPolytope(pieces[0]);
}

TEST(ContactShape, ConvexMeshMergesCoplanarTriangles) {
  // 600 segments: 2400 triangles; each cap (600 triangles) becomes one face.
  const auto geometry = test::meshGeometry(test::fineCylinder(0.04, 0.1, 600));
  ASSERT_TRUE(geometry->isConvex());
  const auto shape = ContactShape::build(*geometry);
  const Polytope& p = asPolytopes(*shape).pieces().at(0);
  EXPECT_EQ(p.faces().size(), 602u);
  EXPECT_EQ(p.vertices().size(), 1200u);
  expectValidPolytope(p);
}

TEST(ContactShape, FlatMeshIsATwoSidedPatch) {
  const auto shape = ContactShape::build(*test::meshGeometry(test::floorPatch(2.5)));
  const Polytope& p = asPolytopes(*shape).pieces().at(0);
  EXPECT_TRUE(p.flat());
  EXPECT_EQ(p.vertices().size(), 4u);
  ASSERT_EQ(p.faces().size(), 6u);  // front, back and the four edges
  EXPECT_VECTOR_NEAR(p.faces()[0].normal, Vector3D::UnitZ(), 1e-12);
  EXPECT_VECTOR_NEAR(p.faces()[1].normal, -Vector3D::UnitZ(), 1e-12);
  EXPECT_EQ(p.edges().size(), 8u);  // two Gauss arcs per edge
}

TEST(ContactShape, NonConvexClosedMeshIsOneSidedTriangles) {
  const std::vector<Eigen::Vector2d> l = {{0, 0},     {0.2, 0},   {0.2, 0.1},
                                          {0.1, 0.1}, {0.1, 0.2}, {0, 0.2}};
  const auto geometry = test::meshGeometry(test::prism(l, 0, 0.05));
  ASSERT_FALSE(geometry->isConvex());
  const auto shape = ContactShape::build(*geometry);
  ASSERT_EQ(shape->kind(), ContactShape::Kind::kMesh);
  const auto& mesh = static_cast<const MeshShape&>(*shape);
  EXPECT_TRUE(mesh.oneSided());
  EXPECT_EQ(mesh.info().size(), 20u);
  // Exactly one reflex (concave) vertical edge: its two side triangles see no arc there; the
  // top and bottom caps' internal fan edges are flat, hence inactive too.
  int convexEdges = 0;
  for (const auto& t : mesh.info()) {
    for (const Vector3D& n : t.neighbour) convexEdges += n.squaredNorm() > 0.0 ? 1 : 0;
  }
  // 5 convex vertical edges (x2 sides), 6 top rim + 6 bottom rim edges (x2 sides).
  EXPECT_EQ(convexEdges, 2 * 5 + 2 * 12);
}

TEST(ContactShape, OpenNonFlatMeshIsTwoSided) {
  TriMesh m;
  m.vertices = {Vector3D(0, 0, 0), Vector3D(1, 0, 0), Vector3D(0, 1, 0), Vector3D(0, 0, 1)};
  m.triangles = {{0, 1, 2}, {0, 3, 1}};
  const auto shape = ContactShape::build(*test::meshGeometry(m));
  ASSERT_EQ(shape->kind(), ContactShape::Kind::kMesh);
  EXPECT_FALSE(static_cast<const MeshShape&>(*shape).oneSided());
}

TEST(ContactShape, RobWorkFingerTipHull) {
  REQUIRE_COMPAT_DATA(data);
  const auto mesh = rw::geometry::loadMesh(data / "devices/SDH2/geometry/FingerTip_hull.stl");
  const auto geometry = Geometry::mesh(mesh, "FingerTip_hull.stl");
  ASSERT_TRUE(geometry->isConvex());
  const auto shape = ContactShape::build(*geometry);
  const Polytope& p = asPolytopes(*shape).pieces().at(0);
  EXPECT_LT(p.faces().size(), mesh->triangles.size());
  EXPECT_GT(p.faces().size(), 100u);
  expectValidPolytope(p);
}

}  // namespace
}  // namespace rwsim::contacts
