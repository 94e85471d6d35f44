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
  /// Measured normal force, newtons; used only with GwsForce::kMeasuredNormalForce.
  double normalForce = 1.0;
  /// Measured contact force on the object (normal and friction), newtons; used only with
  /// GwsForce::kMeasuredForce, which centres the cone on it.
  rw::math::Vector3D force = rw::math::Vector3D::Zero();
  /// Contacts with the same cluster id >= 0 (e.g. the finger link that made them) may be merged
  /// by GwsOptions::mergeClusters; -1: never merged.
  int cluster = -1;
};

}  // namespace rw::graspplanning
