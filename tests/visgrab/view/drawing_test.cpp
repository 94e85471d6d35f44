// A workcell with a box and a one-joint "hand" drawn from a camera straight above: the hand's
// pixels and instance ids are where forward kinematics worked by hand puts its link, background
// where nothing is; the outcome colour, arrows, bounds, crease normals and camera framing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rw/loaders/workcell_loader.hpp"
#include "support/test_support.hpp"
#include "visgrab/render/offscreen_renderer.hpp"
#include "visgrab/view/cameras.hpp"
#include "visgrab/view/drawable_mesh.hpp"
#include "visgrab/view/grasp_pictures.hpp"
#include "visgrab/view/workcell_drawing.hpp"

namespace {

using visgrab::render::PinholeCamera;
using visgrab::view::DrawStyle;
using visgrab::view::WorkcellDrawing;

// A device "Arm" (the first frame, so its base hangs on WORLD: RobWork attaches a device to the
// last workcell-level frame before it): base at the origin, a revolute joint about z 0.2 m up, a
// grey 20 x 4 x 4 cm link from 5 to 25 cm along the joint's x axis; then a blue block (10 cm
// cube, centre 0.3 0 0.05).
constexpr const char* kWorkcell = R"(<WorkCell name="Test">
  <SerialDevice name="Arm">
    <Frame name="Base"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Frame>
    <Joint name="J1" type="Revolute"><RPY>0 0 0</RPY><Pos>0 0 0.2</Pos>
      <Drawable name="Link"><RGB>0.7 0.7 0.7</RGB><RPY>0 0 0</RPY><Pos>0.15 0 0</Pos>
        <Box x="0.2" y="0.04" z="0.04"/></Drawable>
    </Joint>
    <Q name="Home">0</Q>
  </SerialDevice>
  <Frame name="Block" refframe="WORLD">
    <RPY>0 0 0</RPY><Pos>0.3 0 0.05</Pos>
    <Drawable name="BlockBox"><RGB>0.1 0.2 0.9</RGB><RPY>0 0 0</RPY><Pos>0 0 0</Pos>
      <Box x="0.1" y="0.1" z="0.1"/></Drawable>
  </Frame>
</WorkCell>)";

std::unique_ptr<rw::models::WorkCell> workcell() {
  visgrab::test::TempDir dir;
  visgrab::test::writeFile(dir.path() / "test.wc.xml", kWorkcell);
  return rw::loaders::loadWorkCell(dir.path() / "test.wc.xml");
}

// 640 x 480, f = 500 px, 1.5 m above the origin looking straight down: camera x = world x,
// camera y = world -y. A world point (x, y, z) is at u = 319.5 + 500 x / (1.5 - z),
// v = 239.5 - 500 y / (1.5 - z).
PinholeCamera topCamera() {
  PinholeCamera c;
  c.X_WC = rw::math::Transform3D::Identity();
  c.X_WC.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  c.X_WC.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
  return c;
}

struct Pixel {
  int row, col;
};

Pixel pixelOf(double x, double y, double z) {
  return {static_cast<int>(std::lround(239.5 - 500.0 * y / (1.5 - z))),
          static_cast<int>(std::lround(319.5 + 500.0 * x / (1.5 - z)))};
}

std::array<int, 3> colourAt(const visgrab::visual::RgbImage& image, Pixel p) {
  const std::size_t i = 3 * (static_cast<std::size_t>(p.row) * image.width + p.col);
  return {image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]};
}

class Drawing : public ::testing::Test {
 protected:
  void SetUp() override {
    wc_ = workcell();
    drawing_ = std::make_unique<WorkcellDrawing>(*wc_, offscreen_.renderer(), "Arm");
    arm_ = wc_->findDevice("Arm");
    ASSERT_NE(arm_, nullptr);
  }
  void TearDown() override { drawing_.reset(); }

  visgrab::render::RenderResult draw(double q, const DrawStyle& style = {}, bool arrow = false) {
    rw::kinematics::State state = wc_->defaultState();
    arm_->setQ(rw::math::Q::Constant(1, q), state);
    visgrab::render::Scene scene;
    scene.background = visgrab::view::studioBackground();
    scene.lighting = visgrab::view::studioLighting();
    drawing_->addItems(state, scene, style);
    if (arrow) {
      drawing_->addArrow({-0.2, -0.1, 0.1}, {-0.2, 0.1, 0.1}, 0.01, {1.0f, 0.0f, 0.0f}, scene);
    }
    return offscreen_.render(scene, topCamera());
  }

  visgrab::render::OffscreenRenderer offscreen_;
  std::unique_ptr<rw::models::WorkCell> wc_;
  std::unique_ptr<WorkcellDrawing> drawing_;
  const rw::models::Device* arm_ = nullptr;
};

TEST_F(Drawing, TheHandIsWhereForwardKinematicsPutsIt) {
  // q = 0: link centre (0.15, 0, 0.2); q = 90 deg: (0, 0.15, 0.2).
  const Pixel along_x = pixelOf(0.15, 0.0, 0.22);
  const Pixel along_y = pixelOf(0.0, 0.15, 0.22);
  EXPECT_EQ(along_x.row, 240);
  EXPECT_EQ(along_x.col, 378);
  EXPECT_EQ(along_y.row, 181);
  EXPECT_EQ(along_y.col, 320);
  const auto q0 = draw(0.0);
  const auto q90 = draw(std::numbers::pi / 2);
  EXPECT_TRUE(drawing_->isHandInstance(q0.instanceIds.at(along_x.row, along_x.col)));
  EXPECT_EQ(q0.instanceIds.at(along_y.row, along_y.col), 0);
  EXPECT_TRUE(drawing_->isHandInstance(q90.instanceIds.at(along_y.row, along_y.col)));
  EXPECT_EQ(q90.instanceIds.at(along_x.row, along_x.col), 0);
  // The link's top face is 1.5 - 0.22 = 1.28 m from the camera.
  EXPECT_NEAR(q0.depth.at(along_x.row, along_x.col), 1.28, 1e-4);

  // The link's ends, 5 and 25 cm from the joint: its pixels stop there (1 px tolerance).
  int first = -1, last = -1;
  for (int col = 0; col < 640; ++col) {
    if (drawing_->isHandInstance(q0.instanceIds.at(240, col))) {
      if (first < 0) first = col;
      last = col;
    }
  }
  EXPECT_NEAR(first, 319.5 + 500.0 * 0.05 / 1.28, 1.0);
  EXPECT_NEAR(last, 319.5 + 500.0 * 0.25 / 1.28, 1.0);

  // Hand pixels are the link's grey (no outcome colour): r = g = b.
  const auto grey = colourAt(q0.colour, along_x);
  EXPECT_NEAR(grey[0], grey[1], 10);
  EXPECT_NEAR(grey[1], grey[2], 15);
}

TEST_F(Drawing, BackgroundWhereNothingIsAndTheBlockWhereItStands) {
  const auto r = draw(0.0);
  const Eigen::Vector3f bg = visgrab::view::studioBackground();
  auto srgb = [](float c) {
    const double s = c <= 0.0031308f ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return static_cast<int>(std::lround(255.0 * s));
  };
  for (const Pixel p : {Pixel{5, 5}, Pixel{470, 630}, pixelOf(0.0, -0.2, 0.0)}) {
    EXPECT_EQ(r.instanceIds.at(p.row, p.col), 0);
    EXPECT_TRUE(std::isinf(r.depth.at(p.row, p.col)));
    const auto c = colourAt(r.colour, p);
    EXPECT_NEAR(c[0], srgb(bg.x()), 1);
    EXPECT_NEAR(c[1], srgb(bg.y()), 1);
    EXPECT_NEAR(c[2], srgb(bg.z()), 1);
  }
  const Pixel block = pixelOf(0.3, 0.0, 0.1);
  const auto blockId = drawing_->instanceId(wc_->findFrame("Block"));
  ASSERT_NE(blockId, 0);
  EXPECT_FALSE(drawing_->isHandInstance(blockId));
  EXPECT_EQ(r.instanceIds.at(block.row, block.col), blockId);
  EXPECT_NEAR(r.depth.at(block.row, block.col), 1.4, 1e-4);
  const auto blue = colourAt(r.colour, block);
  EXPECT_GT(blue[2], blue[0] + 60);

  // Without the hand, its pixels are background.
  const auto noHand = draw(0.0, DrawStyle{false, true, std::nullopt});
  const Pixel link = pixelOf(0.15, 0.0, 0.22);
  EXPECT_EQ(noHand.instanceIds.at(link.row, link.col), 0);
  EXPECT_EQ(noHand.instanceIds.at(block.row, block.col), blockId);
}

TEST_F(Drawing, OutcomeColourTintsTheHandOnly) {
  DrawStyle style;
  style.handColour = Eigen::Vector3f(0.9f, 0.05f, 0.05f);
  const auto r = draw(0.0, style);
  const auto link = colourAt(r.colour, pixelOf(0.15, 0.0, 0.22));
  EXPECT_GT(link[0], link[1] + 80);
  EXPECT_GT(link[0], link[2] + 80);
  const auto block = colourAt(r.colour, pixelOf(0.3, 0.0, 0.1));
  EXPECT_GT(block[2], block[0] + 60);  // still blue
}

TEST_F(Drawing, ArrowsSpanTailToTip) {
  const auto r = draw(0.0, {}, true);
  using visgrab::view::WorkcellDrawing;
  // Along x = -0.2 at height 0.1 from y = -0.1 to 0.1.
  const Pixel mid = pixelOf(-0.2, 0.0, 0.1);
  EXPECT_EQ(r.instanceIds.at(mid.row, mid.col), WorkcellDrawing::kArrowInstance);
  const Pixel inTail = pixelOf(-0.2, -0.095, 0.1);
  const Pixel beforeTail = pixelOf(-0.2, -0.105, 0.1);
  const Pixel nearTip = pixelOf(-0.2, 0.095, 0.1);
  const Pixel pastTip = pixelOf(-0.2, 0.105, 0.1);
  EXPECT_EQ(r.instanceIds.at(inTail.row, inTail.col), WorkcellDrawing::kArrowInstance);
  EXPECT_EQ(r.instanceIds.at(beforeTail.row, beforeTail.col), 0);
  EXPECT_EQ(r.instanceIds.at(nearTip.row, nearTip.col), WorkcellDrawing::kArrowInstance);
  EXPECT_EQ(r.instanceIds.at(pastTip.row, pastTip.col), 0);
  // Shaft radius 1 cm: 2 cm wide (500 * 0.02 / 1.4 = 7.1 px) at the middle of the shaft.
  const Pixel shaft = pixelOf(-0.2, -0.03, 0.1);
  int width = 0;
  for (int col = shaft.col - 20; col <= shaft.col + 20; ++col) {
    width += r.instanceIds.at(shaft.row, col) == WorkcellDrawing::kArrowInstance ? 1 : 0;
  }
  EXPECT_NEAR(width, 500.0 * 0.02 / 1.4, 1.5);
  const auto red = colourAt(r.colour, mid);
  EXPECT_GT(red[0], red[1] + 80);
}

TEST_F(Drawing, BoundsFollowTheState) {
  rw::kinematics::State state = wc_->defaultState();
  const auto link = drawing_->handFrames();
  ASSERT_EQ(link.size(), 1u);
  EXPECT_EQ(wc_->frames().frame(link[0]).name(), "Arm.J1");
  auto box = drawing_->bounds(state, link);
  // Mesh vertices are single precision.
  EXPECT_LT((box.min() - Eigen::Vector3d(0.05, -0.02, 0.18)).norm(), 1e-6);
  EXPECT_LT((box.max() - Eigen::Vector3d(0.25, 0.02, 0.22)).norm(), 1e-6);
  arm_->setQ(rw::math::Q::Constant(1, std::numbers::pi / 2), state);
  box = drawing_->bounds(state, link);
  EXPECT_NEAR(box.min().x(), -0.02, 1e-6);
  EXPECT_NEAR(box.max().y(), 0.25, 1e-6);
  EXPECT_TRUE(drawing_->bounds(state, {}).isEmpty());
}

TEST(DrawableMesh, CreasesStaySharpAndRoundSidesSmooth) {
  const auto box =
      visgrab::view::shadedMesh(rw::geometry::Geometry::box(1, 2, 3)->triangles(), {1, 1, 1});
  ASSERT_EQ(box.triangles.size(), 12u);
  for (std::size_t t = 0; t < box.triangles.size(); ++t) {
    const auto& tri = box.triangles[t];
    const Eigen::Vector3f face = (box.positions[tri[1]] - box.positions[tri[0]])
                                     .cross(box.positions[tri[2]] - box.positions[tri[0]])
                                     .normalized();
    for (const auto v : tri) EXPECT_GT(box.normals[v].dot(face), 0.9999f);
  }
  // A cylinder's side: normals horizontal and radial.
  const auto cylinder =
      visgrab::view::shadedMesh(rw::geometry::Geometry::cylinder(0.5, 2.0)->triangles(), {1, 1, 1});
  int side = 0;
  for (std::size_t v = 0; v < cylinder.positions.size(); ++v) {
    const Eigen::Vector3f& p = cylinder.positions[v];
    const Eigen::Vector3f& n = cylinder.normals[v];
    if (std::abs(n.z()) < 1e-6f) {
      ++side;
      EXPECT_NEAR(n.head<2>().dot(p.head<2>().normalized()), 1.0f, 1e-3f);
    } else {
      EXPECT_NEAR(std::abs(n.z()), 1.0f, 1e-6f);  // caps
    }
  }
  EXPECT_GT(side, 0);
}

TEST(Cameras, OrbitLooksAtItsTargetWithZUp) {
  visgrab::view::Orbit orbit;
  orbit.target = Eigen::Vector3d(0.1, 0.2, 0.05);
  orbit.azimuthDeg = 30;
  orbit.elevationDeg = 40;
  orbit.distance = 0.8;
  const auto camera = visgrab::view::orbitCamera(orbit, 800, 600);
  const Eigen::Vector2d centre = camera.project(orbit.target);
  EXPECT_NEAR(centre.x(), 399.5, 1e-9);
  EXPECT_NEAR(centre.y(), 299.5, 1e-9);
  // Higher in the world is higher in the image.
  EXPECT_LT(camera.project(orbit.target + Eigen::Vector3d(0, 0, 0.05)).y(), 299.5 - 10);
  // The eye: 0.8 m away, 40 degrees up, on the 30 degree azimuth.
  const Eigen::Vector3d eye = camera.X_WC.translation() - orbit.target;
  EXPECT_NEAR(eye.norm(), 0.8, 1e-12);
  EXPECT_NEAR(std::asin(eye.z() / 0.8) * 180 / std::numbers::pi, 40.0, 1e-9);
  EXPECT_NEAR(std::atan2(eye.y(), eye.x()) * 180 / std::numbers::pi, 30.0, 1e-9);
  // Framing keeps every corner of the box inside the image.
  Eigen::AlignedBox3d box(Eigen::Vector3d(-0.1, -0.3, 0.0), Eigen::Vector3d(0.4, 0.1, 0.25));
  for (const auto preset : {visgrab::view::ViewPreset::kOblique, visgrab::view::ViewPreset::kTop,
                            visgrab::view::ViewPreset::kSide}) {
    const auto c = visgrab::view::orbitCamera(
        visgrab::view::framed(visgrab::view::presetOrbit(preset), box, 640, 480), 640, 480);
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector2d p =
          c.project(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)));
      EXPECT_GT(p.x(), 0.0);
      EXPECT_LT(p.x(), 640.0);
      EXPECT_GT(p.y(), 0.0);
      EXPECT_LT(p.y(), 480.0);
    }
  }
  EXPECT_THROW(visgrab::view::orbitCamera(orbit, 0, 10), std::invalid_argument);
  orbit.distance = -1;
  EXPECT_THROW(visgrab::view::orbitCamera(orbit, 10, 10), std::invalid_argument);
}

TEST(Cameras, PresetNamesRoundTrip) {
  for (const auto p : {visgrab::view::ViewPreset::kOblique, visgrab::view::ViewPreset::kFront,
                       visgrab::view::ViewPreset::kSide, visgrab::view::ViewPreset::kTop}) {
    EXPECT_EQ(visgrab::view::viewPresetFromName(visgrab::view::viewPresetName(p)), p);
  }
  EXPECT_FALSE(visgrab::view::viewPresetFromName("isometric").has_value());
}

}  // namespace
