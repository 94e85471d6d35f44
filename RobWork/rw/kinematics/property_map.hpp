#pragma once

#include <map>
#include <string>
#include <variant>

#include "rw/math/types.hpp"

namespace rw::kinematics {

/// A property value: RobWork's workcell XML knows string, double and Q.
using PropertyValue = std::variant<std::string, double, rw::math::Q>;

/// One named property with its optional description.
struct Property {
  /// The value.
  PropertyValue value;
  /// Free text from the `desc` attribute.
  std::string description;
};

/// Properties by name, sorted (so writers are deterministic).
using PropertyMap = std::map<std::string, Property>;

}  // namespace rw::kinematics
