#pragma once

#include <Eigen/Geometry>
#include <numbers>

/// Math types of the workcell layer: Eigen directly, with RobWork's names.
namespace rw::math {

/// A point or direction in 3-D, metres.
using Vector3D = Eigen::Vector3d;
/// A 3x3 rotation matrix.
using Rotation3D = Eigen::Matrix3d;
/// A rigid transform; `X_AB` maps coordinates in frame B to frame A.
using Transform3D = Eigen::Isometry3d;
/// A joint configuration (radians for revolute joints, metres for prismatic ones).
using Q = Eigen::VectorXd;

/// Degrees to radians.
inline constexpr double kDeg2Rad = std::numbers::pi / 180.0;
/// Radians to degrees.
inline constexpr double kRad2Deg = 180.0 / std::numbers::pi;

/// Builds a transform from a rotation and a translation.
inline Transform3D makeTransform(const Rotation3D& R, const Vector3D& p) {
  Transform3D X = Transform3D::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

/// A pure translation.
inline Transform3D makeTranslation(const Vector3D& p) {
  return makeTransform(Rotation3D::Identity(), p);
}

}  // namespace rw::math
