#include <gtest/gtest.h>

#include <cstdio>

#include "mesh_test_support.hpp"
#include "objects_test_support.hpp"
#include "visgrab/objects/convex_decomposition.hpp"
#include "visgrab/objects/convex_hull.hpp"
#include "visgrab/objects/mesh_object.hpp"

namespace {

using visgrab::objects::checkClosure;
using visgrab::objects::decomposeConvex;
using visgrab::objects::meshVolume;
using visgrab::test::objects::convexityViolation;

// Every piece closed, convex and of positive volume.
void expectConvexPieces(const visgrab::objects::ConvexDecomposition& d, const std::string& what) {
  for (std::size_t i = 0; i < d.pieces.size(); ++i) {
    EXPECT_TRUE(checkClosure(d.pieces[i]).closed()) << what << " piece " << i;
    EXPECT_LT(convexityViolation(d.pieces[i]), 1e-8) << what << " piece " << i;
    EXPECT_GT(meshVolume(d.pieces[i]), 0.0) << what << " piece " << i;
  }
}

TEST(ConvexHull, OfACubesCornersAndCentreIsTheCube) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  points.emplace_back(0.5, 0.5, 0.5);
  const auto hull = visgrab::objects::convexHull(points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  EXPECT_EQ(hull.triangles.size(), 12u);
  EXPECT_NEAR(meshVolume(hull), 1.0, 1e-12);
  EXPECT_TRUE(checkClosure(hull).closed());
  EXPECT_THROW(visgrab::objects::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}),
               std::invalid_argument);
}

TEST(ConvexDecomposition, ConvexMeshStaysOnePiece) {
  const auto box = visgrab::test::objects::boxMesh({0, 0, 0}, {0.1, 0.2, 0.3});
  const auto d = decomposeConvex(box);
  ASSERT_EQ(d.pieces.size(), 1u);
  EXPECT_NEAR(d.piecesVolume, 0.006, 1e-12);
}

TEST(ConvexDecomposition, LShapeSplitsIntoConvexPiecesOfItsVolume) {
  // L = a 2 x 2 square without its 1 x 1 upper right quarter, 0.5 high: volume 1.5.
  const auto l =
      visgrab::test::objects::prismMesh({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 0.5);
  ASSERT_TRUE(checkClosure(l).closed());
  const auto d = decomposeConvex(l);
  EXPECT_GE(d.pieces.size(), 2u);
  EXPECT_NEAR(d.meshVolume, 1.5, 1e-12);
  expectConvexPieces(d, "L");
  EXPECT_NEAR(d.piecesVolume, 1.5, 0.1 * 1.5);
  // Its hull would be 1.75: the pieces must do better than the hull.
  EXPECT_LT(d.piecesVolume, 1.5 * 1.03 + 1e-12);
}

TEST(ConvexDecomposition, CutsAreExactInVolume) {
  // A staircase of three steps (a 3 x 1, a 2 x 1 and a 1 x 1 block, 1 high; star-shaped about
  // its first vertex, so the prism's fan caps are valid) needs two cuts; the pieces' volumes add
  // up to the mesh's (the cuts sit 1e-7 of the extent off the vertices: slivers of that size).
  const auto stairs = visgrab::test::objects::prismMesh(
      {{0, 0}, {3, 0}, {3, 1}, {2, 1}, {2, 2}, {1, 2}, {1, 3}, {0, 3}}, 1.0);
  const auto d = decomposeConvex(stairs);
  expectConvexPieces(d, "stairs");
  EXPECT_EQ(d.pieces.size(), 3u);
  EXPECT_NEAR(d.meshVolume, 6.0, 1e-12);
  EXPECT_NEAR(d.piecesVolume, 6.0, 1e-5);
}

// The 18 objects: the welded visual body of each (its parts joined by position; closed) is
// decomposed; the pieces' summed volume is within 10 % of the body's volume.
TEST(ConvexDecomposition, ProjectObjectsVisualBodiesWithinTenPercent) {
  const auto& models = visgrab::test::objects::projectModels();
  ASSERT_EQ(models.size(), 18u);
  for (const auto& model : models) {
    const auto body = visgrab::test::objects::weldedVisual(model);
    const auto closure = checkClosure(body);
    EXPECT_TRUE(closure.closed()) << model.name << ": " << closure.openEdges << " open, "
                                  << closure.crowdedEdges << " crowded, " << closure.flippedEdges
                                  << " flipped";
    const auto d = decomposeConvex(body);
    expectConvexPieces(d, model.name);
    const double error = d.piecesVolume / d.meshVolume - 1.0;
    std::printf("%-15s %5zu triangles  volume %.6g m^3  %2zu pieces  error %+.2f %%\n",
                model.name.c_str(), body.triangles.size(), d.meshVolume, d.pieces.size(),
                100.0 * error);
    EXPECT_LT(std::abs(error), 0.10) << model.name;
  }
}

}  // namespace
