#pragma once

#include <string_view>

namespace visgrab::generator::detail {

/// The text of xml/camera-profile.xsd, embedded into the library at build time.
std::string_view cameraProfileSchema();

}  // namespace visgrab::generator::detail
