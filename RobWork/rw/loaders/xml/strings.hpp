#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rw::loaders::xml {

/// `text` with &, <, > and " escaped for XML element text and attribute values.
std::string escapeXml(std::string_view text);

/// Levenshtein distance between two strings (for "did you mean" suggestions in messages).
std::size_t editDistance(std::string_view a, std::string_view b);

}  // namespace rw::loaders::xml
