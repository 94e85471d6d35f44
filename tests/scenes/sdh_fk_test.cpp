// Forward kinematics of RobWork's own SDH2 model (RW_COMPAT_DATA/devices/SDH2/SchunkHand.wc.xml)
// against transforms composed by hand from the numbers in that file.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "scene_test_helpers.hpp"

namespace {

using Eigen::Matrix4d;
using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::test::scenes::deviceOf;
using visgrab::test::scenes::load;
using visgrab::test::scenes::worldPose;

using HandQ = std::array<double, 7>;

double deg(double degrees) { return degrees * std::numbers::pi / 180.0; }

// Homogeneous matrices, written out entry by entry.
Matrix4d translation(double x, double y, double z) {
  Matrix4d m = Matrix4d::Identity();
  m(0, 3) = x;
  m(1, 3) = y;
  m(2, 3) = z;
  return m;
}

// [c -s 0; s c 0; 0 0 1]
Matrix4d rotZ(double a) {
  Matrix4d m = Matrix4d::Identity();
  m(0, 0) = std::cos(a);
  m(0, 1) = -std::sin(a);
  m(1, 0) = std::sin(a);
  m(1, 1) = std::cos(a);
  return m;
}

// [c 0 s; 0 1 0; -s 0 c]
Matrix4d rotY(double a) {
  Matrix4d m = Matrix4d::Identity();
  m(0, 0) = std::cos(a);
  m(0, 2) = std::sin(a);
  m(2, 0) = -std::sin(a);
  m(2, 2) = std::cos(a);
  return m;
}

// [1 0 0; 0 c -s; 0 s c]
Matrix4d rotX(double a) {
  Matrix4d m = Matrix4d::Identity();
  m(1, 1) = std::cos(a);
  m(1, 2) = -std::sin(a);
  m(2, 1) = std::sin(a);
  m(2, 2) = std::cos(a);
  return m;
}

Vector3D position(const Matrix4d& m) { return Vector3D(m(0, 3), m(1, 3), m(2, 3)); }

Transform3D toTransform(const Matrix4d& m) {
  Transform3D X = Transform3D::Identity();
  X.matrix() = m;
  return X;
}

// One finger from the frame its Joint2 hangs on to its fingertip frame (the file's
// <Define id="finger">). RobWork's <RPY>a b c</RPY><Pos>x y z</Pos> is T(x,y,z) Rz(a) Ry(b) Rx(c)
// in degrees, and a revolute joint adds Rz(q) after its placement:
//   Joint2: <RPY>0 0 90</RPY><Pos>0 0 0.0175</Pos>     -> T(0, 0, 0.0175) Rx(90 deg) Rz(q_joint2)
//   Joint3: <RPY>0 0 0</RPY><Pos>0 0.086501 0</Pos>    -> T(0, 0.086501, 0) Rz(q_joint3)
//   TCP:    <RPY>0 -90 -10</RPY><Pos>-0.01 0.05 0</Pos> -> T(-0.01, 0.05, 0) Ry(-90 deg) Rx(-10
//   deg)
Matrix4d finger(double qJoint2, double qJoint3) {
  const Matrix4d joint2 = translation(0, 0, 0.0175) * rotX(deg(90)) * rotZ(qJoint2);
  const Matrix4d joint3 = translation(0, 0.086501, 0) * rotZ(qJoint3);
  const Matrix4d tcp = translation(-0.01, 0.05, 0) * rotY(deg(-90)) * rotX(deg(-10));
  return joint2 * joint3 * tcp;
}

// X_W_fN.TCP for N = 1, 2, 3, with q = [f1.J2, f1.J3, spread, f2.J2, f2.J3, f3.J2, f3.J3].
std::array<Matrix4d, 3> fingertipsByHand(const HandQ& q) {
  // Base: Movable, initial value <RPY>0 0 0</RPY><Pos>0 0 0.056</Pos>. The file's root is the
  // device itself, so Base hangs on WORLD.
  const Matrix4d X_WB = translation(0, 0, 0.056);
  // Finger 1: f1 (on Base, no transform) -> F1Base <Pos>0.038105 0 0.025</Pos> -> finger.
  const Matrix4d X_B_F1Base = translation(0.038105, 0, 0.025);
  // Finger 2: f2 <RPY>120 0 0</RPY> -> F2Base <RPY>60 0 0</RPY><Pos>0.038105 0 0.025</Pos>
  // -> F2Joint1 <RPY>0 0 180</RPY>, revolute, q = spread -> F2Joint1Rev <RPY>0 0 -180</RPY>
  // -> finger.
  const Matrix4d X_B_F2Rev = rotZ(deg(120)) * translation(0.038105, 0, 0.025) * rotZ(deg(60)) *
                             rotX(deg(180)) * rotZ(q[2]) * rotX(deg(-180));
  // Finger 3: f3 <RPY>-120 0 0</RPY> -> F3Base <RPY>-60 0 0</RPY><Pos>0.038105 0 0.025</Pos>
  // -> F3Joint1 <RPY>0 0 180</RPY>, <Depend on="F2Joint1" gain="-1" offset="0"/>: q = -spread
  // -> F3Joint1Rev <RPY>0 0 -180</RPY> -> finger.
  const Matrix4d X_B_F3Rev = rotZ(deg(-120)) * translation(0.038105, 0, 0.025) * rotZ(deg(-60)) *
                             rotX(deg(180)) * rotZ(-q[2]) * rotX(deg(-180));
  return {X_WB * X_B_F1Base * finger(q[0], q[1]), X_WB * X_B_F2Rev * finger(q[3], q[4]),
          X_WB * X_B_F3Rev * finger(q[5], q[6])};
}

rw::math::Q toQ(const HandQ& q) { return Eigen::Map<const Eigen::VectorXd>(q.data(), 7); }

// Close configurations of VisGraB's pre-shapes (reference §7.1).
constexpr HandQ kZero{0, 0, 0, 0, 0, 0, 0};
constexpr HandQ kCylinderClose{0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349};
constexpr HandQ kBallClose{0.0, 0.349, 1.047, 0.0, 0.349, 0.0, 0.349};
constexpr HandQ kParallelClose{-1.571, -1.571, 1.571, 0.0, 0.419, 0.0, 0.419};

class RobWorkSdhFk : public ::testing::Test {
 protected:
  // X_W_fN.TCP of the loaded model at q.
  std::array<Transform3D, 3> fingertips(const rw::models::WorkCell& wc, const HandQ& q) const {
    rw::kinematics::State state = wc.defaultState();
    deviceOf(wc, "SchunkHand").setQ(toQ(q), state);
    return {worldPose(wc, state, "SchunkHand.f1.TCP"), worldPose(wc, state, "SchunkHand.f2.TCP"),
            worldPose(wc, state, "SchunkHand.f3.TCP")};
  }
};

TEST_F(RobWorkSdhFk, FingertipsEqualTheTransformsComposedByHand) {
  REQUIRE_COMPAT_DATA(data);
  const auto wc = load(data / "devices" / "SDH2" / "SchunkHand.wc.xml");
  for (const HandQ& q : {kZero, kCylinderClose, kBallClose, kParallelClose}) {
    const auto loaded = fingertips(*wc, q);
    const auto expected = fingertipsByHand(q);
    for (std::size_t i = 0; i < 3; ++i) {
      SCOPED_TRACE("f" + std::to_string(i + 1) + ".TCP at q = " + std::to_string(q[0]) + " " +
                   std::to_string(q[1]) + " " + std::to_string(q[2]) + " ...");
      EXPECT_VECTOR_NEAR(loaded[i].translation(), position(expected[i]), 1e-9);
      EXPECT_TRANSFORM_NEAR(loaded[i], toTransform(expected[i]), 1e-9);
    }
  }
}

// The values derived in reference §6.1 (rounded there to 0.1 mm).
TEST_F(RobWorkSdhFk, MatchesTheDerivedValuesOfTheReference) {
  REQUIRE_COMPAT_DATA(data);
  const auto wc = load(data / "devices" / "SDH2" / "SchunkHand.wc.xml");
  const auto zero = fingertips(*wc, kZero);
  EXPECT_VECTOR_NEAR(zero[0].translation(), Vector3D(0.0281, 0, 0.2350), 1e-4);
  EXPECT_VECTOR_NEAR(zero[1].translation(), Vector3D(-0.0091, 0.0330, 0.2350), 1e-4);
  EXPECT_VECTOR_NEAR(zero[2].translation(), Vector3D(-0.0091, -0.0330, 0.2350), 1e-4);

  rw::kinematics::State state = wc->defaultState();
  EXPECT_VECTOR_NEAR(worldPose(*wc, state, "SchunkHand.f1.Joint2").translation(),
                     Vector3D(0.0381, 0, 0.0985), 1e-4);
  EXPECT_VECTOR_NEAR(worldPose(*wc, state, "SchunkHand.f2.Joint2").translation(),
                     Vector3D(-0.0191, 0.0330, 0.0985), 1e-4);
  EXPECT_VECTOR_NEAR(worldPose(*wc, state, "SchunkHand.f3.Joint2").translation(),
                     Vector3D(-0.0191, -0.0330, 0.0985), 1e-4);
  EXPECT_NEAR(worldPose(*wc, state, "SchunkHand.f1.Joint3").translation().z(), 0.1850, 1e-4);

  const auto ball = fingertips(*wc, kBallClose);
  EXPECT_VECTOR_NEAR(ball[0].translation(), Vector3D(0.0116, 0, 0.2286), 1e-4);
  EXPECT_VECTOR_NEAR(ball[1].translation(), Vector3D(-0.0058, 0.0101, 0.2286), 1e-4);
  EXPECT_VECTOR_NEAR(ball[2].translation(), Vector3D(-0.0058, -0.0101, 0.2286), 1e-4);

  const auto parallel = fingertips(*wc, kParallelClose);
  EXPECT_VECTOR_NEAR(parallel[0].translation(), Vector3D(0.1346, 0, 0.0485), 1e-4);
  EXPECT_VECTOR_NEAR(parallel[1].translation(), Vector3D(-0.0191, 0.0035, 0.2266), 1e-4);
  EXPECT_VECTOR_NEAR(parallel[2].translation(), Vector3D(-0.0191, -0.0035, 0.2266), 1e-4);
}

// The hand composition itself, checked against the reference's numbers without any loader.
TEST(SdhFkByHand, ReproducesTheReferenceAtZero) {
  const auto tips = fingertipsByHand(kZero);
  EXPECT_VECTOR_NEAR(position(tips[0]), Vector3D(0.028105, 0, 0.235001), 1e-12);
  EXPECT_VECTOR_NEAR(position(tips[1]),
                     Vector3D(-0.0190525 + 0.01, 0.038105 * std::sqrt(3.0) / 2, 0.235001), 1e-12);
}

}  // namespace
