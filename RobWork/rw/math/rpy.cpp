#include "rw/math/rpy.hpp"

#include <cmath>

namespace rw::math {

Rotation3D rpyToRotation(double roll, double pitch, double yaw) {
  const double ca = std::cos(roll), sa = std::sin(roll);
  const double cb = std::cos(pitch), sb = std::sin(pitch);
  const double cc = std::cos(yaw), sc = std::sin(yaw);
  Rotation3D R;
  R << ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc,  //
      sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc,   //
      -sb, cb * sc, cb * cc;
  return R;
}

Rotation3D rpyToRotation(const Vector3D& rpy) { return rpyToRotation(rpy[0], rpy[1], rpy[2]); }

Vector3D rotationToRpy(const Rotation3D& R) {
  const double cb = std::hypot(R(0, 0), R(1, 0));
  const double pitch = std::atan2(-R(2, 0), cb);
  if (cb < 1e-12) {
    // Gimbal lock: only roll - yaw (or roll + yaw) is defined; put it all into roll.
    const double roll = pitch > 0 ? std::atan2(R(1, 2), R(0, 2)) : std::atan2(-R(1, 2), -R(0, 2));
    return {roll, pitch, 0.0};
  }
  return {std::atan2(R(1, 0), R(0, 0)), pitch, std::atan2(R(2, 1), R(2, 2))};
}

Transform3D rpyTransform(const Vector3D& rpy, const Vector3D& position) {
  return makeTransform(rpyToRotation(rpy), position);
}

}  // namespace rw::math
