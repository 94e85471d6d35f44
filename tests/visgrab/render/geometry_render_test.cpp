#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "render_test_util.hpp"
#include "rw/math/rpy.hpp"
#include "visgrab/render/offscreen_renderer.hpp"

namespace visgrab::render {
namespace {

using rw::math::Transform3D;
using test::makeBox;

Transform3D pose(double roll, double pitch, double yaw, const Eigen::Vector3d& p) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  return rw::math::makeTransform(R, p);
}

Scene sceneWith(std::initializer_list<SceneItem> items) {
  Scene scene;
  scene.items = items;
  return scene;
}

TEST(GeometryRenderTest, CubeSilhouetteMatchesProjectedCorners) {
  OffscreenRenderer renderer;
  const MeshHandle cube = renderer.add(makeBox(Eigen::Vector3f::Constant(0.5f)));
  const PinholeCamera camera = test::testCamera();
  const Transform3D X_WM = pose(0.3, -0.2, 0.7, {0.05, 0.1, 0.02});
  const RenderResult result = renderer.render(sceneWith({{cube, X_WM, 7}}), camera);

  std::vector<Eigen::Vector2d> projected;
  for (const auto& corner : test::boxCorners(X_WM, Eigen::Vector3d::Constant(0.5))) {
    projected.push_back(test::projectOpenCv(camera, corner));
  }
  const auto hull = test::convexHull(projected);
  int both = 0;
  int either = 0;
  int rendered = 0;
  for (int row = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col) {
      const bool inside = test::insideConvex(hull, Eigen::Vector2d(col, row));
      const bool drawn = result.instanceIds.at(row, col) == 7;
      both += inside && drawn ? 1 : 0;
      either += inside || drawn ? 1 : 0;
      rendered += drawn ? 1 : 0;
    }
  }
  ASSERT_GT(rendered, 10000);  // a sizeable silhouette, so the IoU means something
  const double iou = static_cast<double>(both) / either;
  EXPECT_GE(iou, 0.98) << "both " << both << ", either " << either;
}

TEST(GeometryRenderTest, CubeDepthEqualsRayIntersection) {
  OffscreenRenderer renderer;
  const MeshHandle cube = renderer.add(makeBox(Eigen::Vector3f::Constant(0.5f)));
  const PinholeCamera camera = test::testCamera();
  const Transform3D X_WM = pose(0.3, -0.2, 0.7, {0.05, 0.1, 0.02});
  const RenderResult result = renderer.render(sceneWith({{cube, X_WM, 3}}), camera);
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5);

  // Image centre.
  const int centreRow = camera.height / 2;
  const int centreCol = camera.width / 2;
  const double centreDepth = test::rayBoxDepth(camera, centreRow, centreCol, X_WM, half);
  ASSERT_TRUE(std::isfinite(centreDepth));
  EXPECT_EQ(result.instanceIds.at(centreRow, centreCol), 3);
  EXPECT_NEAR(result.depth.at(centreRow, centreCol), centreDepth, 1e-3);

  // Near the corner closest to the camera: 4 px from its projection toward the silhouette's
  // centre, where the ray may hit any of the three faces meeting there.
  const auto corners = test::boxCorners(X_WM, half);
  const Eigen::Isometry3d X_CW = camera.X_WC.inverse();
  const Eigen::Vector3d nearest = *std::min_element(
      corners.begin(), corners.end(),
      [&](const auto& a, const auto& b) { return (X_CW * a).z() < (X_CW * b).z(); });
  const Eigen::Vector2d corner = test::projectOpenCv(camera, nearest);
  const Eigen::Vector2d centre = test::projectOpenCv(camera, X_WM.translation());
  const Eigen::Vector2d probe = corner + 4.0 * (centre - corner).normalized();
  const int row = static_cast<int>(std::lround(probe.y()));
  const int col = static_cast<int>(std::lround(probe.x()));
  const double cornerDepth = test::rayBoxDepth(camera, row, col, X_WM, half);
  ASSERT_TRUE(std::isfinite(cornerDepth));
  EXPECT_EQ(result.instanceIds.at(row, col), 3);
  EXPECT_NEAR(result.depth.at(row, col), cornerDepth, 1e-3);

  // Every pixel whose ray hits the box well inside: depth within 1 mm.
  int checked = 0;
  for (int r = 0; r < camera.height; r += 7) {
    for (int c = 0; c < camera.width; c += 7) {
      const double expected = test::rayBoxDepth(camera, r, c, X_WM, half);
      if (!std::isfinite(expected) || result.instanceIds.at(r, c) != 3) continue;
      ++checked;
      ASSERT_NEAR(result.depth.at(r, c), expected, 1e-3) << "row " << r << " col " << c;
    }
  }
  EXPECT_GT(checked, 200);
}

/// A flat disc of about 12 px radius parallel to the image plane, centred on `p_C` (camera
/// frame): its projection is an ellipse (affine in x, y at fixed z), so the centroid of its
/// pixels is the projection of its centre, up to the sampling of pixel centres (measured below
/// 0.07 px). The tolerance is 0.2 px, well under the 0.5 px that a half-pixel convention error
/// would shift it by.
void expectCentroidAt(OffscreenRenderer& renderer, const PinholeCamera& camera,
                      const Eigen::Vector3d& p_C) {
  const float radius = static_cast<float>(12.0 * p_C.z() / camera.fx);
  const MeshHandle disc = renderer.add(test::makeDisc(radius, 48));
  // Disc frame: normal -z_C (towards the camera).
  const Eigen::Matrix3d R_CM = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  const Transform3D X_WM = camera.X_WC * rw::math::makeTransform(R_CM, p_C);
  const RenderResult result = renderer.render(sceneWith({{disc, X_WM, 1}}), camera);
  double sumU = 0;
  double sumV = 0;
  int count = 0;
  for (int row = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col) {
      if (result.instanceIds.at(row, col) != 1) continue;
      sumU += col;
      sumV += row;
      ++count;
    }
  }
  ASSERT_GT(count, 300);
  const Eigen::Vector2d expected = test::projectOpenCv(camera, camera.X_WC * p_C);
  EXPECT_NEAR(sumU / count, expected.x(), 0.2) << "point " << p_C.transpose();
  EXPECT_NEAR(sumV / count, expected.y(), 0.2) << "point " << p_C.transpose();
}

TEST(GeometryRenderTest, PointProjectsWhereOpenCvPutsIt) {
  OffscreenRenderer renderer;
  PinholeCamera camera = test::testCamera();
  expectCentroidAt(renderer, camera, {0.0, 0.0, 1.0});
  expectCentroidAt(renderer, camera, {0.213, -0.097, 1.31});
  expectCentroidAt(renderer, camera, {-0.55, 0.38, 1.07});  // near the bottom-left corner
  expectCentroidAt(renderer, camera, {0.61, -0.45, 1.12});  // near the top-right corner
}

TEST(GeometryRenderTest, PointProjectsWithSkewAndOddSize) {
  OffscreenRenderer renderer;
  PinholeCamera camera = test::testCamera();
  camera.width = 333;
  camera.height = 211;
  camera.cx = 170.2;
  camera.cy = 101.6;
  camera.fx = 310.0;
  camera.fy = 305.0;
  camera.skew = 4.5;
  expectCentroidAt(renderer, camera, {0.11, -0.07, 0.9});
  expectCentroidAt(renderer, camera, {-0.35, 0.21, 1.2});
}

TEST(GeometryRenderTest, BackgroundHasBackgroundColourIdZeroAndInfiniteDepth) {
  OffscreenRenderer renderer;
  const MeshHandle cube = renderer.add(makeBox(Eigen::Vector3f::Constant(0.2f)));
  Scene scene = sceneWith({{cube, Transform3D::Identity(), 5}});
  scene.background = {0.2f, 0.4f, 0.6f};
  const PinholeCamera camera = test::testCamera();
  const RenderResult result = renderer.render(scene, camera);
  ASSERT_EQ(result.colour.width, camera.width);
  ASSERT_EQ(result.colour.height, camera.height);
  const Eigen::Vector3i expected(test::linearToSrgb(0.2), test::linearToSrgb(0.4),
                                 test::linearToSrgb(0.6));
  for (const auto& [row, col] : {std::pair{0, 0}, {0, 799}, {599, 0}, {599, 799}, {10, 400}}) {
    EXPECT_LE((test::pixel(result.colour, row, col) - expected).cwiseAbs().maxCoeff(), 1)
        << test::pixel(result.colour, row, col).transpose();
    EXPECT_EQ(result.instanceIds.at(row, col), 0);
    EXPECT_EQ(result.depth.at(row, col), std::numeric_limits<float>::infinity());
  }
  // The cube is at the world origin, which the camera looks at.
  const Eigen::Vector2d centre = test::projectOpenCv(camera, Eigen::Vector3d::Zero());
  const int row = static_cast<int>(std::lround(centre.y()));
  const int col = static_cast<int>(std::lround(centre.x()));
  EXPECT_EQ(result.instanceIds.at(row, col), 5);
  EXPECT_TRUE(std::isfinite(result.depth.at(row, col)));
}

TEST(GeometryRenderTest, NearerObjectWinsWhereTheyOverlap) {
  OffscreenRenderer renderer;
  const Eigen::Vector3d half(0.15, 0.15, 0.15);
  const MeshHandle cube = renderer.add(makeBox(half.cast<float>()));
  const PinholeCamera camera = test::testCamera();
  // Along the line of sight: the second cube is 0.5 m nearer the camera, shifted sideways.
  const Eigen::Vector3d towardsCamera = (camera.X_WC.translation()).normalized();
  const Transform3D X_WFar = pose(0.1, 0.2, 0.3, {0.0, 0.0, 0.0});
  const Transform3D X_WNear =
      pose(-0.2, 0.1, 0.5, 0.5 * towardsCamera + Eigen::Vector3d(0.08, 0.0, 0.03));
  // Listed far-last and near-first, so the order of drawing cannot decide the result.
  const RenderResult result =
      renderer.render(sceneWith({{cube, X_WNear, 2}, {cube, X_WFar, 1}}), camera);

  auto hullOf = [&](const Transform3D& X_WM) {
    std::vector<Eigen::Vector2d> projected;
    for (const auto& corner : test::boxCorners(X_WM, half)) {
      projected.push_back(test::projectOpenCv(camera, corner));
    }
    return test::convexHull(projected);
  };
  const auto farHull = hullOf(X_WFar);
  const auto nearHull = hullOf(X_WNear);
  int overlap = 0;
  int farOnly = 0;
  for (int row = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col) {
      const Eigen::Vector2d p(col, row);
      const double nearDepth = test::rayBoxDepth(camera, row, col, X_WNear, half);
      const double farDepth = test::rayBoxDepth(camera, row, col, X_WFar, half);
      if (!std::isfinite(nearDepth) || !std::isfinite(farDepth)) {
        // Count clear far-only pixels (not on the near cube's outline).
        if (std::isfinite(farDepth) && !test::insideConvex(nearHull, p) &&
            test::insideConvex(farHull, p) && result.instanceIds.at(row, col) == 1) {
          ++farOnly;
        }
        continue;
      }
      ++overlap;
      ASSERT_EQ(result.instanceIds.at(row, col), 2) << "row " << row << " col " << col;
      ASSERT_NEAR(result.depth.at(row, col), nearDepth, 1e-3);
    }
  }
  EXPECT_GT(overlap, 1000);
  EXPECT_GT(farOnly, 1000);
}

TEST(GeometryRenderTest, ColourOnlyRenderGivesTheSameColourAndNoDepthOrIds) {
  OffscreenRenderer renderer;
  const MeshHandle cube = renderer.add(makeBox(Eigen::Vector3f(0.15f, 0.1f, 0.2f)));
  const PinholeCamera camera = test::testCamera();
  Scene scene = sceneWith({{cube, pose(0.1, 0.2, 0.3, {0.0, 0.0, 0.0}), 1},
                           {cube, pose(-0.2, 0.1, 0.5, {0.2, 0.1, 0.05}), 2}});
  Light key;
  key.direction_W = rw::math::Vector3D(0.35, 0.45, -1.0);
  key.castsShadows = true;
  scene.lighting.lights = {key};
  const RenderResult full = renderer.render(scene, camera);
  RenderOptions colourOnly;
  colourOnly.depthAndIds = false;
  const RenderResult colour = renderer.render(scene, camera, colourOnly);
  EXPECT_TRUE(colour.depth.values.empty());
  EXPECT_TRUE(colour.instanceIds.values.empty());
  ASSERT_EQ(colour.colour.width, camera.width);
  ASSERT_EQ(colour.colour.height, camera.height);
  // Not a blank image: the cubes cover part of it, in other colours than the background.
  std::size_t covered = 0;
  for (const std::uint16_t id : full.instanceIds.values) covered += id != 0 ? 1 : 0;
  EXPECT_GT(covered, full.instanceIds.values.size() / 20);
  const auto& px = full.colour.pixels;
  std::size_t shaded = 0;
  for (std::size_t i = 0; i + 2 < px.size(); i += 3) {
    shaded += px[i] != px[0] || px[i + 1] != px[1] || px[i + 2] != px[2] ? 1 : 0;
  }
  EXPECT_GT(shaded, px.size() / 3 / 20);
  EXPECT_EQ(colour.colour.pixels, full.colour.pixels);
  // And a full render after it is whole again.
  const RenderResult again = renderer.render(scene, camera);
  EXPECT_EQ(again.instanceIds.values, full.instanceIds.values);
  EXPECT_EQ(again.colour.pixels, full.colour.pixels);
}

// A box over a ground plate, lit from above at an angle: the box casts a shadow on the plate.
Scene shadowScene(MeshHandle plate, MeshHandle box, const Eigen::Vector3d& boxAt,
                  const Eigen::Vector3d& lightDirection) {
  Scene scene = sceneWith(
      {{plate, pose(0.0, 0.0, 0.0, {0.0, 0.0, -0.01}), 1}, {box, pose(0.0, 0.0, 0.4, boxAt), 2}});
  Light key;
  key.direction_W = lightDirection;
  key.castsShadows = true;
  scene.lighting.lights = {key};
  return scene;
}

TEST(GeometryRenderTest, ShadowMapIsReusedOnlyForTheSameSceneAndLight) {
  OffscreenRenderer renderer;
  const MeshHandle plate = renderer.add(makeBox(Eigen::Vector3f(0.6f, 0.6f, 0.01f)));
  const MeshHandle box = renderer.add(makeBox(Eigen::Vector3f(0.08f, 0.08f, 0.15f)));
  const PinholeCamera camera = test::testCamera();
  PinholeCamera other = camera;
  other.X_WC = test::lookAt({0.5, -1.6, 1.3}, {0.0, 0.0, 0.0});
  const Eigen::Vector3d light(0.4, 0.3, -1.0);
  const Scene first = shadowScene(plate, box, {0.0, 0.0, 0.15}, light);
  const Scene moved = shadowScene(plate, box, {0.12, -0.05, 0.15}, light);
  const Scene relit = shadowScene(plate, box, {0.0, 0.0, 0.15}, {-0.5, 0.2, -1.0});
  RenderOptions colourOnly;
  colourOnly.depthAndIds = false;
  // One renderer draws the scene from two cameras (the second reuses the shadow map), then
  // the box moved, then the light turned; each must match a renderer that draws it first.
  const auto a = renderer.render(first, camera, colourOnly).colour.pixels;
  const auto b = renderer.render(first, other, colourOnly).colour.pixels;
  const auto c = renderer.render(moved, other, colourOnly).colour.pixels;
  const auto d = renderer.render(relit, other, colourOnly).colour.pixels;
  const auto fresh = [&](const Scene& scene, const PinholeCamera& cam) {
    OffscreenRenderer own;
    own.add(makeBox(Eigen::Vector3f(0.6f, 0.6f, 0.01f)));
    own.add(makeBox(Eigen::Vector3f(0.08f, 0.08f, 0.15f)));
    return own.render(scene, cam, colourOnly).colour.pixels;
  };
  EXPECT_EQ(a, fresh(first, camera));
  EXPECT_EQ(b, fresh(first, other));
  EXPECT_EQ(c, fresh(moved, other));
  EXPECT_EQ(d, fresh(relit, other));
  // The three scenes look different from the second camera (the shadow moved with the box and
  // with the light), so a stale shadow map could not match.
  EXPECT_NE(b, c);
  EXPECT_NE(b, d);
}

TEST(GeometryRenderTest, RejectsBadInput) {
  OffscreenRenderer renderer;
  PinholeCamera camera = test::testCamera();
  Scene scene = sceneWith({{MeshHandle{3}, Transform3D::Identity(), 1}});
  EXPECT_THROW(renderer.render(scene, camera), std::invalid_argument);
  scene.items.clear();
  camera.near = 0.0;
  EXPECT_THROW(renderer.render(scene, camera), std::invalid_argument);
  auto bad = makeBox(Eigen::Vector3f::Ones());
  bad->triangles.push_back({0, 1, 99});
  try {
    renderer.add(bad);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace visgrab::render
