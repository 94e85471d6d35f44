#include <gtest/gtest.h>

#include <cmath>

#include "rw/math/dh.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

Transform3D rx(double a) { return Transform3D(Eigen::AngleAxisd(a, Vector3D::UnitX())); }
Transform3D ry(double a) { return Transform3D(Eigen::AngleAxisd(a, Vector3D::UnitY())); }
Transform3D rz(double a) { return Transform3D(Eigen::AngleAxisd(a, Vector3D::UnitZ())); }
Transform3D tx(double d) { return Transform3D(Eigen::Translation3d(d, 0, 0)); }
Transform3D ty(double d) { return Transform3D(Eigen::Translation3d(0, d, 0)); }
Transform3D tz(double d) { return Transform3D(Eigen::Translation3d(0, 0, d)); }

constexpr double kAlpha = 0.4, kA = 0.25, kD = -0.13, kTheta = 1.2;

TEST(DenavitHartenberg, CraigIsRxTxRzTz) {
  EXPECT_TRANSFORM_NEAR(rw::math::craigDH(kAlpha, kA, kD, kTheta),
                        rx(kAlpha) * tx(kA) * rz(kTheta) * tz(kD), 1e-15);
}

TEST(DenavitHartenberg, SchillingIsRzTzTxRx) {
  EXPECT_TRANSFORM_NEAR(rw::math::schillingDH(kAlpha, kA, kD, kTheta),
                        rz(kTheta) * tz(kD) * tx(kA) * rx(kAlpha), 1e-15);
}

TEST(DenavitHartenberg, HgpIsTyRyTxRx) {
  const double beta = -0.6, b = 0.07;
  EXPECT_TRANSFORM_NEAR(rw::math::hgpDH(kAlpha, kA, beta, b),
                        ty(b) * ry(beta) * tx(kA) * rx(kAlpha), 1e-15);
}

TEST(DenavitHartenberg, CraigAtZeroAnglesIsATranslation) {
  // alpha = theta = 0: the link is a along x and d along z.
  const Transform3D X = rw::math::craigDH(0, 0.5, 0.2, 0);
  EXPECT_TRUE(X.linear().isIdentity(1e-15));
  EXPECT_NEAR((X.translation() - Vector3D(0.5, 0, 0.2)).norm(), 0.0, 1e-15);
}

}  // namespace
