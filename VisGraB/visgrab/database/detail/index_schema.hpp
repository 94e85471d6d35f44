#pragma once

#include <string_view>

namespace visgrab::database::detail {

/// The text of xml/database-index.xsd, compiled in.
std::string_view indexSchema();

}  // namespace visgrab::database::detail
