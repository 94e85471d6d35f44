#pragma once

#include <string_view>

namespace visgrab::grasp::detail {

/// The text of xml/grasp-description.xsd, embedded into the library at build time.
std::string_view graspDescriptionSchema();

}  // namespace visgrab::grasp::detail
