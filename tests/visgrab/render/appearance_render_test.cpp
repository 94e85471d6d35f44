#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "render_test_util.hpp"
#include "visgrab/render/offscreen_renderer.hpp"

namespace visgrab::render {
namespace {

using rw::math::Transform3D;

/// Linear value of a pixel's channels, averaged.
double linearGrey(const visual::RgbImage& image, const Eigen::Vector2d& uv) {
  const Eigen::Vector3i p = test::pixel(image, static_cast<int>(std::lround(uv.y())),
                                        static_cast<int>(std::lround(uv.x())));
  return (test::srgbToLinear(static_cast<std::uint8_t>(p.x())) +
          test::srgbToLinear(static_cast<std::uint8_t>(p.y())) +
          test::srgbToLinear(static_cast<std::uint8_t>(p.z()))) /
         3.0;
}

Lighting onlyAmbient(float ambient) {
  Lighting lighting;
  lighting.ambient = Eigen::Vector3f::Constant(ambient);
  lighting.lights.clear();
  return lighting;
}

TEST(AppearanceRenderTest, TextureQuadrantsAppearWhereTheImageHasThem) {
  OffscreenRenderer renderer;
  PinholeCamera camera = test::testCamera();
  // A quad facing the camera, built in camera coordinates (x right, y down): its top-left
  // corner as seen in the image has uv (0, 0), the texture's top-left pixel.
  auto texture = std::make_shared<visual::RgbImage>();
  texture->width = 2;
  texture->height = 2;
  texture->pixels = {255, 0, 0,   0,   255, 0,     // top row: red, green
                     0,   0, 255, 255, 255, 255};  // bottom row: blue, white
  auto quad = std::make_shared<visual::VisualMesh>();
  const float s = 0.3f;
  const float z = 1.5f;
  quad->positions = {{-s, -s, z}, {s, -s, z}, {-s, s, z}, {s, s, z}};  // TL, TR, BL, BR
  quad->uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}};
  quad->normals.assign(4, -Eigen::Vector3f::UnitZ());
  quad->triangles = {{0, 2, 3}, {0, 3, 1}};  // counter-clockwise as seen from the camera
  quad->colour = Eigen::Vector3f::Ones();
  quad->specular = 0.0f;
  quad->texture = texture;
  const MeshHandle handle = renderer.add(quad);
  Scene scene;
  scene.items = {{handle, camera.X_WC, 1}};
  scene.lighting = onlyAmbient(1.0f);
  const RenderResult result = renderer.render(scene, camera);

  struct Expected {
    double x, y;
    Eigen::Vector3i rgb;
  };
  const Expected quadrants[] = {{-s / 2, -s / 2, {255, 0, 0}},
                                {s / 2, -s / 2, {0, 255, 0}},
                                {-s / 2, s / 2, {0, 0, 255}},
                                {s / 2, s / 2, {255, 255, 255}}};
  for (const auto& q : quadrants) {
    const Eigen::Vector2d uv =
        test::projectOpenCv(camera, camera.X_WC * Eigen::Vector3d(q.x, q.y, z));
    const Eigen::Vector3i got = test::pixel(result.colour, static_cast<int>(std::lround(uv.y())),
                                            static_cast<int>(std::lround(uv.x())));
    // Bilinear filtering in linear light blends ~0.4% of the neighbouring texel at a pixel
    // centre half a pixel from the texel centre; sRGB encoding magnifies that near 0 to ~12.
    EXPECT_LE((got - q.rgb).cwiseAbs().maxCoeff(), 16)
        << "at (" << q.x << ", " << q.y << "): got " << got.transpose() << ", expected "
        << q.rgb.transpose();
  }
}

TEST(AppearanceRenderTest, FaceAtSixtyDegreesToTheLightGetsCosineOfTheLight) {
  OffscreenRenderer renderer;
  auto square = test::makeSquare(0.4f);
  square->colour = Eigen::Vector3f::Ones();
  square->specular = 0.0f;
  const MeshHandle handle = renderer.add(square);
  PinholeCamera camera = test::testCamera();
  camera.X_WC = test::lookAt({0.0, -2.0, 1.5}, {0.0, 0.0, 0.2});
  // A faces straight up into the light; B is tilted 60 degrees towards the camera.
  const Transform3D X_WA = rw::math::makeTranslation({-0.3, 0.0, 0.0});
  const Transform3D X_WB = rw::math::makeTransform(
      Eigen::AngleAxisd(std::numbers::pi / 3.0, Eigen::Vector3d::UnitX()).toRotationMatrix(),
      {0.3, 0.0, 0.2});
  Scene scene;
  scene.items = {{handle, X_WA, 1}, {handle, X_WB, 2}};
  const float ambient = 0.2f;
  const float light = 0.6f;
  scene.lighting = onlyAmbient(ambient);
  Light sun;
  sun.direction_W = {0.0, 0.0, -1.0};
  sun.colour = Eigen::Vector3f::Constant(light);
  scene.lighting.lights = {sun};
  const RenderResult result = renderer.render(scene, camera);

  const double a = linearGrey(result.colour, test::projectOpenCv(camera, X_WA.translation()));
  const double b = linearGrey(result.colour, test::projectOpenCv(camera, X_WB.translation()));
  EXPECT_NEAR(a, ambient + light, 0.01);
  EXPECT_NEAR(b, ambient + light * 0.5, 0.01);
  EXPECT_GT(a, b);
  EXPECT_NEAR((b - ambient) / (a - ambient), std::cos(std::numbers::pi / 3.0), 0.03);
}

TEST(AppearanceRenderTest, SpecularHighlightWhereLightReflectsIntoTheCamera) {
  OffscreenRenderer renderer;
  auto square = test::makeSquare(0.4f);
  square->colour = Eigen::Vector3f::Ones();
  square->specular = 0.5f;
  const MeshHandle handle = renderer.add(square);
  PinholeCamera camera = test::testCamera();
  camera.cx = 399.5;
  camera.cy = 299.5;
  camera.X_WC = test::lookAt({0.0, -1.0, 1.0}, {0.0, 0.0, 0.0});
  // The square faces the camera; the light travels along the optical axis, so at the image
  // centre the half vector equals the normal.
  const Eigen::Matrix3d R_CM = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  const Transform3D X_WM = camera.X_WC * rw::math::makeTransform(R_CM, {0.0, 0.0, 1.2});
  Scene scene;
  scene.items = {{handle, X_WM, 1}};
  scene.lighting = onlyAmbient(0.1f);
  Light light;
  light.direction_W = camera.X_WC.linear().col(2);
  light.colour = Eigen::Vector3f::Constant(0.4f);
  scene.lighting.lights = {light};
  const RenderResult result = renderer.render(scene, camera);
  // 0.1 ambient + 0.4 diffuse + 0.5 * 0.4 specular.
  EXPECT_NEAR(linearGrey(result.colour, {399.5, 299.5}), 0.7, 0.01);
}

TEST(AppearanceRenderTest, PointLightShinesFromItsPosition) {
  OffscreenRenderer renderer;
  auto square = test::makeSquare(2.0f);
  square->colour = Eigen::Vector3f::Ones();
  square->specular = 0.0f;
  const MeshHandle handle = renderer.add(square);
  PinholeCamera camera = test::testCamera();
  Scene scene;
  scene.items = {{handle, Transform3D::Identity(), 1}};
  scene.lighting = onlyAmbient(0.1f);
  Light lamp;
  lamp.type = Light::Type::kPoint;
  lamp.position_W = {0.0, 0.0, 0.5};
  lamp.colour = Eigen::Vector3f::Constant(0.5f);
  scene.lighting.lights = {lamp};
  const RenderResult result = renderer.render(scene, camera);
  // Right under the lamp n . l = 1; at (0.5, 0, 0) it is cos 45 degrees.
  EXPECT_NEAR(linearGrey(result.colour, test::projectOpenCv(camera, {0.0, 0.0, 0.0})), 0.6, 0.01);
  EXPECT_NEAR(linearGrey(result.colour, test::projectOpenCv(camera, {0.5, 0.0, 0.0})),
              0.1 + 0.5 * std::sqrt(0.5), 0.01);
}

TEST(AppearanceRenderTest, KeyLightCastsAShadowOnTheTable) {
  OffscreenRenderer renderer;
  auto table = test::makeSquare(2.0f);
  table->colour = Eigen::Vector3f::Ones();
  table->specular = 0.0f;
  const MeshHandle tableHandle = renderer.add(table);
  const MeshHandle boxHandle = renderer.add(test::makeBox(Eigen::Vector3f::Constant(0.1f)));
  PinholeCamera camera = test::testCamera();
  camera.X_WC = test::lookAt({0.0, -2.0, 1.5}, {0.0, 0.0, 0.0});
  Scene scene;
  scene.items = {{tableHandle, Transform3D::Identity(), 1},
                 {boxHandle, rw::math::makeTranslation({0.0, 0.0, 0.5}), 2}};
  scene.lighting = onlyAmbient(0.2f);
  Light sun;
  sun.direction_W = {0.6, 0.0, -1.0};
  sun.colour = Eigen::Vector3f::Constant(0.6f);
  sun.castsShadows = true;
  scene.lighting.lights = {sun};
  const RenderResult result = renderer.render(scene, camera);
  // The box's centre casts its shadow at (0.3, 0, 0); (-0.4, 0.3, 0) is in full light.
  const Eigen::Vector2d shadow = test::projectOpenCv(camera, {0.3, 0.0, 0.0});
  const Eigen::Vector2d lit = test::projectOpenCv(camera, {-0.4, 0.3, 0.0});
  EXPECT_EQ(result.instanceIds.at(static_cast<int>(std::lround(shadow.y())),
                                  static_cast<int>(std::lround(shadow.x()))),
            1);
  EXPECT_NEAR(linearGrey(result.colour, shadow), 0.2, 0.01);
  EXPECT_NEAR(linearGrey(result.colour, lit), 0.2 + 0.6 / std::sqrt(1.36), 0.01);
}

RenderResult renderBusyScene(OffscreenRenderer& renderer) {
  auto texture = std::make_shared<visual::RgbImage>();
  texture->width = 16;
  texture->height = 16;
  for (int i = 0; i < 16 * 16; ++i) {
    texture->pixels.push_back(static_cast<std::uint8_t>(i * 7));
    texture->pixels.push_back(static_cast<std::uint8_t>(i * 13));
    texture->pixels.push_back(static_cast<std::uint8_t>(255 - i));
  }
  auto box = test::makeBox({0.1f, 0.15f, 0.2f});
  box->texture = texture;
  box->specular = 0.5f;
  const MeshHandle boxHandle = renderer.add(box);
  const MeshHandle tableHandle = renderer.add(test::makeSquare(2.0f));
  Scene scene;
  scene.items.push_back({tableHandle, Transform3D::Identity(), 1});
  for (int i = 0; i < 5; ++i) {
    scene.items.push_back(
        {boxHandle,
         rw::math::makeTransform(
             Eigen::AngleAxisd(0.4 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
             {-0.5 + 0.25 * i, 0.1 * (i % 2), 0.2}),
         static_cast<std::uint16_t>(10 + i)});
  }
  scene.lighting.lights[0].castsShadows = true;
  Light fill;
  fill.type = Light::Type::kPoint;
  fill.position_W = {1.0, -1.0, 1.0};
  fill.colour = {0.2f, 0.2f, 0.3f};
  scene.lighting.lights.push_back(fill);
  return renderer.render(scene, test::testCamera());
}

TEST(AppearanceRenderTest, RenderingIsDeterministic) {
  OffscreenRenderer first;
  const RenderResult a = renderBusyScene(first);
  const RenderResult b = renderBusyScene(first);
  OffscreenRenderer second;
  const RenderResult c = renderBusyScene(second);
  for (const RenderResult* other : {&b, &c}) {
    EXPECT_TRUE(a.colour.pixels == other->colour.pixels);
    EXPECT_TRUE(a.depth.values == other->depth.values);
    EXPECT_TRUE(a.instanceIds.values == other->instanceIds.values);
  }
  // The scene is not trivially empty.
  int objects = 0;
  for (std::uint16_t id : a.instanceIds.values) objects += id >= 10 ? 1 : 0;
  EXPECT_GT(objects, 5000);
}

}  // namespace
}  // namespace visgrab::render
