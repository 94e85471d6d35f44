// Placements, the random stream and the stereo rig, against geometry worked in the test.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rw/proximity/convex_shape.hpp"
#include "rw/proximity/gjk.hpp"
#include "support/test_support.hpp"
#include "visgrab/generator/placement.hpp"
#include "visgrab/generator/stereo_rig.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::database::SceneConditions;
using visgrab::database::Texture;
namespace gen = visgrab::generator;
namespace objects = visgrab::objects;

const objects::ObjectModel& model(int id) {
  static const auto spec =
      objects::loadObjectSpecs(visgrab::test::sourceDir() / "scenes/objects/objects.xml");
  static std::map<int, objects::ObjectModel> cache;
  auto it = cache.find(id);
  if (it == cache.end())
    it = cache.emplace(id, objects::generateObject(*spec.findObject(id))).first;
  return it->second;
}

TEST(Random, SameSeedSameStreamAndPlausibleMoments) {
  gen::Random a(7, "scene"), b(7, "scene"), c(7, "other");
  double sum = 0.0, sum2 = 0.0, n1 = 0.0, n2 = 0.0;
  bool differs = false;
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    const double u = a.uniform(0.0, 1.0);
    EXPECT_EQ(u, b.uniform(0.0, 1.0));
    differs = differs || u != c.uniform(0.0, 1.0);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
    const double z = a.normal();
    b.normal();
    n1 += z;
    n2 += z * z;
  }
  EXPECT_TRUE(differs);
  EXPECT_NEAR(sum / kN, 0.5, 0.01);
  EXPECT_NEAR(sum2 / kN - 0.25, 1.0 / 12.0, 0.005);
  EXPECT_NEAR(n1 / kN, 0.0, 0.03);
  EXPECT_NEAR(n2 / kN, 1.0, 0.04);
}

TEST(Placement, SingleObjectsRestOnTheTableNearItsCentre) {
  for (const int id : {5, 13, 18}) {
    for (int pose = 1; pose <= 8; ++pose) {
      const SceneConditions scene = SceneConditions::single(Texture::kPlain, id, pose);
      const auto placement = gen::placeObjects(scene, {&model(id)}, 1);
      ASSERT_EQ(placement.X_TO.size(), 1u);
      const Transform3D& X = placement.X_TO[0];
      // Lowest collision vertex on z = 0, found here by brute force over the vertices.
      double lowest = 1e9, xlo = 1e9, xhi = -1e9;
      for (const auto& piece : model(id).collision) {
        for (const Vector3D& v : piece.triangles->vertices) {
          const Vector3D p = X * v;
          lowest = std::min(lowest, p.z());
          xlo = std::min(xlo, p.x());
          xhi = std::max(xhi, p.x());
        }
      }
      EXPECT_NEAR(lowest, 0.0, 1e-12) << id << "/" << pose;
      EXPECT_LE(std::abs(0.5 * (xlo + xhi)), 0.05 + 1e-12);
      // Standing: the object's z axis up; lying: horizontal.
      const double upZ = (X.linear() * Vector3D::UnitZ()).z();
      if (pose <= 4) {
        EXPECT_NEAR(upZ, 1.0, 1e-12);
      } else {
        EXPECT_NEAR(upZ, 0.0, 1e-12);
      }
    }
  }
}

// Gap between two placed objects along the line through their footprint centres, from the
// vertices (brute force).
double gapAlong(const objects::ObjectModel& a, const Transform3D& Xa, const objects::ObjectModel& b,
                const Transform3D& Xb, const Vector3D& d) {
  double aHigh = -1e9, bLow = 1e9;
  for (const auto& piece : a.collision) {
    for (const Vector3D& v : piece.triangles->vertices) aHigh = std::max(aHigh, (Xa * v).dot(d));
  }
  for (const auto& piece : b.collision) {
    for (const Vector3D& v : piece.triangles->vertices) bLow = std::min(bLow, (Xb * v).dot(d));
  }
  return bLow - aHigh;
}

TEST(Placement, PairsStandApartOrAlmostTouching) {
  for (int pose = 1; pose <= 8; ++pose) {
    const SceneConditions scene = SceneConditions::pairScene(Texture::kTextured, 'c', pose);
    const auto& a = model(scene.objects[0]);
    const auto& b = model(scene.objects[1]);
    const auto p = gen::placeObjects(scene, {&a, &b}, 3);
    ASSERT_EQ(p.X_TO.size(), 2u);
    Vector3D d = p.X_TO[1].translation() - p.X_TO[0].translation();
    d.z() = 0.0;
    // The direction the generator used is not exposed; the largest gap over directions near
    // the centre line is the separating gap along it, and it must lie in the promised range.
    double best = -1e9;
    for (int k = -40; k <= 40; ++k) {
      const double angle = std::atan2(d.y(), d.x()) + k * 0.5 * std::numbers::pi / 180.0;
      best = std::max(best, gapAlong(a, p.X_TO[0], b, p.X_TO[1],
                                     Vector3D(std::cos(angle), std::sin(angle), 0.0)));
    }
    if (pose <= 4) {
      EXPECT_GE(best, 0.04 - 1e-9) << pose;
      EXPECT_LT(best, 0.09 + 1e-3) << pose;
    } else {
      // Not overlapping, and as close as the generator promises: the distance by GJK (which
      // the proximity tests check against worked distances) is the gap.
      double distance = 1e9;
      for (const auto& pa : a.collision) {
        for (const auto& pb : b.collision) {
          const Transform3D X_ab = pa.X_OG.inverse() * p.X_TO[0].inverse() * p.X_TO[1] * pb.X_OG;
          distance = std::min(distance, rw::proximity::gjkDistance(gen::convexShapeOf(pa),
                                                                   gen::convexShapeOf(pb), X_ab)
                                            .distance);
        }
      }
      EXPECT_NEAR(distance, 0.001, 2e-5) << pose;
    }
  }
}

TEST(Placement, DeterministicPerSeedAndAttempt) {
  const SceneConditions scene = SceneConditions::single(Texture::kPlain, 5, 2);
  const auto a = gen::placeObjects(scene, {&model(5)}, 11);
  const auto b = gen::placeObjects(scene, {&model(5)}, 11);
  const auto c = gen::placeObjects(scene, {&model(5)}, 11, 1);
  EXPECT_TRUE(a.X_TO[0].isApprox(b.X_TO[0], 0.0));
  EXPECT_FALSE(a.X_TO[0].isApprox(c.X_TO[0], 1e-9));
  EXPECT_THROW(gen::placeObjects(scene, {}, 11), std::invalid_argument);
}

TEST(StereoRig, LookAtAimsTheOpticalAxisWithAHorizontalImageRow) {
  const Vector3D eye(0.1, -0.5, 0.5), target(0.0, 0.0, 0.05);
  const Transform3D X = gen::lookAt(eye, target);
  EXPECT_VECTOR_NEAR(Vector3D(X.translation()), eye, 1e-15);
  EXPECT_VECTOR_NEAR(Vector3D(X.linear().col(2)), (target - eye).normalized(), 1e-12);
  EXPECT_NEAR(X.linear().col(0).z(), 0.0, 1e-12);  // image rows horizontal
  EXPECT_LT(X.linear().col(1).z(), 0.0);           // image y points down in the world
  EXPECT_NEAR(X.linear().determinant(), 1.0, 1e-12);
  EXPECT_THROW(gen::lookAt(eye, eye), std::invalid_argument);
  EXPECT_THROW(gen::lookAt(eye, eye - Vector3D::UnitZ()), std::invalid_argument);
}

TEST(StereoRig, CamerasProjectAsTheCalibrationsP1AndP2) {
  const gen::StereoRigSpec spec;
  const auto calibration = gen::rigCalibration(spec);
  EXPECT_EQ(calibration.check(), "");
  EXPECT_NEAR(calibration.baseline(), spec.baseline, 1e-12);
  const auto [left, right] = gen::rigCameras(calibration);
  const Transform3D X_LW = calibration.X_TL.inverse();
  // The rig centre is at the spec's eye.
  EXPECT_VECTOR_NEAR(Vector3D(calibration.X_TL * Vector3D(0.5 * spec.baseline, 0, 0)), spec.eye,
                     1e-12);
  for (const Vector3D& p : {Vector3D(0, 0, 0), Vector3D(0.1, 0.05, 0.1), Vector3D(-0.2, 0.3, 0)}) {
    const Eigen::Vector4d pL = (X_LW * p).homogeneous();
    const Eigen::Vector3d u1 = calibration.P1 * pL;
    const Eigen::Vector3d u2 = calibration.P2 * pL;
    EXPECT_LT((left.project(p) - u1.hnormalized()).norm(), 1e-9);
    EXPECT_LT((right.project(p) - u2.hnormalized()).norm(), 1e-9);
    // Disparity f b / z.
    EXPECT_NEAR(u1.hnormalized().x() - u2.hnormalized().x(), spec.focal * spec.baseline / pL.z(),
                1e-9);
  }
}

}  // namespace
