#include "rwsim/trial/physics_variation.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rwsim::trial {

namespace {

void checkScale(const char* name, double scale) {
  if (std::isfinite(scale) && scale > 0.0) return;
  char text[160];
  std::snprintf(text, sizeof(text), "physics variation: %s must be a finite number > 0, not %g",
                name, scale);
  throw std::invalid_argument(text);
}

}  // namespace

void PhysicsVariation::check() const {
  checkScale("frictionScale", frictionScale);
  checkScale("objectMassScale", objectMassScale);
}

bool isVariedObject(const dynamics::Body& body) {
  return body.kind == dynamics::BodyKind::kRigid && !body.device.valid();
}

}  // namespace rwsim::trial
