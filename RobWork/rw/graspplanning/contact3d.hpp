#pragma once

#include "rw/math/types.hpp"

namespace rw::graspplanning {

/// A point contact between a finger and the grasped object, in the object's frame.
struct Contact3D {
  /// Contact point, metres.
  rw::math::Vector3D position = rw::math::Vector3D::Zero();
  /// Unit contact normal pointing INTO the object: the direction of the force the finger applies.
  rw::math::Vector3D normal = rw::math::Vector3D::UnitZ();
  /// Coulomb friction coefficient (>= 0).
  double mu = 0.6;
  /// Measured normal force, newtons; used only when GwsOptions::useMeasuredNormalForce is set.
  double normalForce = 1.0;
};

}  // namespace rw::graspplanning
