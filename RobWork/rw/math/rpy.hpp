#pragma once

#include "rw/math/types.hpp"

namespace rw::math {

/// RobWork's RPY convention: R = Rz(roll) * Ry(pitch) * Rx(yaw), angles in radians.
/// The first angle turns about z, the second about y, the third about x.
Rotation3D rpyToRotation(double roll, double pitch, double yaw);

/// Same as rpyToRotation(rpy[0], rpy[1], rpy[2]).
Rotation3D rpyToRotation(const Vector3D& rpy);

/// Inverse of rpyToRotation: (roll, pitch, yaw) with pitch in [-pi/2, pi/2]. At the gimbal-lock
/// singularity (|pitch| = pi/2) yaw is set to 0.
Vector3D rotationToRpy(const Rotation3D& R);

/// Transform from RPY angles (radians) and a position.
Transform3D rpyTransform(const Vector3D& rpy, const Vector3D& position);

}  // namespace rw::math
