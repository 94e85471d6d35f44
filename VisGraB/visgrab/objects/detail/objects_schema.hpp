#pragma once

#include <string_view>

namespace visgrab::objects::detail {

/// The text of xml/objects.xsd, embedded into the library at build time.
std::string_view objectsSchema();

}  // namespace visgrab::objects::detail
