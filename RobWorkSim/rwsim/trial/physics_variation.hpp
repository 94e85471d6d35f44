#pragma once

#include "rwsim/dynamics/dynamic_workcell.hpp"

namespace rwsim::trial {

/// Scale factors one trial applies to the dwc's physical values (the identity changes nothing):
/// the perturbations of a robust verdict, where each grasp runs several times under seeded
/// variations (the caller samples the numbers; the engines honour them).
struct PhysicsVariation {
  /// Every friction coefficient of the material table times this (> 0).
  double frictionScale = 1.0;
  /// The mass and inertia tensor of every object (isVariedObject()) times this (> 0); the
  /// centre of mass stays where it is.
  double objectMassScale = 1.0;
  /// False: the world has no gravity (a trial protocol's choice, e.g. ACRONYM's shake; the dwc's
  /// gravity is not edited, each engine zeroes its own copy).
  bool gravity = true;

  /// True when both scales are exactly 1 and gravity is on: the engine then runs on the dwc's
  /// own values, with bitwise the results of an engine made without a variation.
  bool isIdentity() const { return frictionScale == 1.0 && objectMassScale == 1.0 && gravity; }
  /// @throws std::invalid_argument naming the scale and its value unless both scales are
  /// finite and > 0.
  void check() const;
};

/// Whether PhysicsVariation::objectMassScale applies to `body`: a dynamic (rigid) body that is
/// no part of a device (not a hand link or base; fixed and kinematic bodies have no mass to vary).
bool isVariedObject(const dynamics::Body& body);

}  // namespace rwsim::trial
