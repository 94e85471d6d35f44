// The hot path allocates nothing once warmed up: collide() reuses its thread's buffers and
// ContactDetector::detect() the caller's output vectors. Counted by replacing operator new.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "contact_test_util.hpp"
#include "rw/kinematics/frame_tree.hpp"

namespace {

std::atomic<long> allocations{0};

}  // namespace

// AddressSanitizer owns operator new; under it the counting is off and the tests skip.
#if defined(__SANITIZE_ADDRESS__)
#define VISGRAB_COUNT_ALLOCATIONS 0
#else
#define VISGRAB_COUNT_ALLOCATIONS 1

// GCC cannot see that these replace the global pair and warns about malloc/free pairing.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop
#endif

namespace rwsim::contacts {
namespace {

using rw::math::Vector3D;
using test::Geometry;
using test::kPen;
using test::pose;

/// Allocations made by `run` on its third call (the first two warm the buffers up).
template <class F>
long allocationsOfThirdCall(F run) {
  if (!VISGRAB_COUNT_ALLOCATIONS) return 0;
  run();
  run();
  const long before = allocations.load();
  run();
  return allocations.load() - before;
}

TEST(Allocations, CollideAllocatesNothingOnceWarm) {
  if (!VISGRAB_COUNT_ALLOCATIONS) GTEST_SKIP() << "allocations are not counted under ASan";
  const std::vector<Eigen::Vector2d> l = {{0, 0},     {0.2, 0},   {0.2, 0.1},
                                          {0.1, 0.1}, {0.1, 0.2}, {0, 0.2}};
  const auto plane = ContactShape::build(*Geometry::plane());
  const auto box = ContactShape::build(*Geometry::box(0.1, 0.1, 0.1));
  const auto can = ContactShape::build(*Geometry::cylinder(0.03, 0.1));
  const auto ball = ContactShape::build(*Geometry::sphere(0.02));
  const auto tube = ContactShape::build(*Geometry::tube(0.03, 0.005, 0.1));
  const auto hull = ContactShape::build(*test::meshGeometry(test::uvSphere(0.05, 40, 26)));
  const auto lShape = ContactShape::build(*test::meshGeometry(test::prism(l, 0, 0.05)));
  struct Pair {
    const ContactShape* a;
    rw::math::Transform3D X_a;
    const ContactShape* b;
    rw::math::Transform3D X_b;
  };
  const std::vector<Pair> pairs = {
      {plane.get(), pose({0, 0, 0}), box.get(), pose({0, 0, 0.05 - kPen}, 0.3)},
      {box.get(), pose({0, 0, 0}), box.get(), pose({0.01, 0, 0.1 - kPen}, 0.5)},
      {box.get(), pose({0, 0, 0}), can.get(), pose({0, 0, 0.1 - kPen})},
      {plane.get(), pose({0, 0, 0}), tube.get(), pose({0, 0, 0.05 - kPen})},
      {box.get(), pose({0, 0, 0}), hull.get(), pose({0, 0, 0.1 - kPen})},
      {lShape.get(), pose({0, 0, 0}), box.get(), pose({0.05, 0.05, 0.1 - kPen}, 0.2)},
      {lShape.get(), pose({0, 0, 0}), ball.get(), pose({0.05, 0.05, 0.07 - kPen})},
      {lShape.get(), pose({0, 0, 0}), lShape.get(), pose({0.05, 0.05, 0.05 - kPen})},
  };
  std::vector<ContactPoint> out;
  out.reserve(64);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    const long count = allocationsOfThirdCall([&] {
      out.clear();
      collide(*p.a, p.X_a, *p.b, p.X_b, ContactOptions{}, out);
    });
    EXPECT_FALSE(out.empty()) << "pair " << i;
    EXPECT_EQ(count, 0) << "pair " << i;
  }
}

TEST(Allocations, DetectReusesTheOutputOnceWarm) {
  if (!VISGRAB_COUNT_ALLOCATIONS) GTEST_SKIP() << "allocations are not counted under ASan";
  auto wc = std::make_unique<rw::models::WorkCell>("alloc");
  rw::kinematics::FrameSpec spec;
  spec.name = "Box";
  spec.parent = rw::kinematics::FrameTree::kWorld;
  spec.type = rw::kinematics::FrameType::kMovable;
  spec.transform = pose({0, 0, 0.05 - kPen}, 0.3);
  const auto boxFrame = wc->frames().add(spec);
  rw::models::GeometryInstance g;
  g.geometry = Geometry::plane();
  wc->objectOf(rw::kinematics::FrameTree::kWorld).collision.push_back(g);
  g.geometry = Geometry::box(0.1, 0.1, 0.1);
  wc->objectOf(boxFrame).collision.push_back(g);
  dynamics::DynamicWorkCell dwc(std::move(wc));
  dwc.materials().addMaterial("Plastic");
  dynamics::Body floor;
  floor.name = "Floor";
  floor.frame = rw::kinematics::FrameTree::kWorld;
  floor.kind = dynamics::BodyKind::kFixed;
  floor.material = "Plastic";
  floor.geometryFrames = {floor.frame};
  dwc.addBody(floor);
  dynamics::Body box;
  box.name = "Box";
  box.frame = boxFrame;
  box.material = "Plastic";
  box.mass.mass = 1.0;
  box.mass.inertia = Eigen::Matrix3d::Identity() * 1e-3;
  dwc.addBody(box);
  const ContactDetector detector(dwc);
  const std::vector<rw::math::Transform3D> poses = {pose({0, 0, 0}), spec.transform};
  std::vector<BodyContact> out;
  const long count = allocationsOfThirdCall([&] { detector.detect(poses, out); });
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].points.size(), 4u);
  EXPECT_EQ(count, 0);
}

}  // namespace
}  // namespace rwsim::contacts
