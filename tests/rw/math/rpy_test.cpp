#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rw/math/rpy.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Rotation3D;
using rw::math::Vector3D;

// Elementary rotations written out independently of the library.
Rotation3D rotX(double a) {
  Rotation3D R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}
Rotation3D rotY(double a) {
  Rotation3D R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
Rotation3D rotZ(double a) {
  Rotation3D R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}

TEST(Rpy, FirstAngleTurnsAboutZSecondAboutYThirdAboutX) {
  // RobWork: RPY(a, b, c) = Rz(a) * Ry(b) * Rx(c).
  const double a = 0.3, b = -0.7, c = 1.1;
  const Rotation3D expected = rotZ(a) * rotY(b) * rotX(c);
  EXPECT_TRUE(rw::math::rpyToRotation(a, b, c).isApprox(expected, 1e-15));
}

TEST(Rpy, NinetyDegreesAboutZMapsXToY) {
  const Vector3D x = rw::math::rpyToRotation(90 * rw::math::kDeg2Rad, 0, 0) * Vector3D::UnitX();
  EXPECT_NEAR(x.x(), 0.0, 1e-15);
  EXPECT_NEAR(x.y(), 1.0, 1e-15);
  EXPECT_NEAR(x.z(), 0.0, 1e-15);
}

TEST(Rpy, RoundTripAwayFromSingularity) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> angle(-3.1, 3.1), pitch(-1.5, 1.5);
  for (int i = 0; i < 200; ++i) {
    const Vector3D rpy(angle(rng), pitch(rng), angle(rng));
    const Vector3D back = rw::math::rotationToRpy(rw::math::rpyToRotation(rpy));
    EXPECT_VECTOR_NEAR(back, rpy, 1e-9);
  }
}

TEST(Rpy, GimbalLockGivesTheSameRotation) {
  for (const double pitch : {M_PI / 2, -M_PI / 2}) {
    const Rotation3D R = rw::math::rpyToRotation(0.4, pitch, -0.9);
    const Vector3D rpy = rw::math::rotationToRpy(R);
    EXPECT_NEAR(rpy[2], 0.0, 1e-12);
    EXPECT_TRUE(rw::math::rpyToRotation(rpy).isApprox(R, 1e-12));
  }
}

}  // namespace
