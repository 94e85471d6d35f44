#pragma once

#include <charconv>
#include <string>

namespace rw::common {

/// The shortest decimal text that reads back as the same double (std::to_chars; locale
/// independent). Callers decide how they write zeros' signs and non-finite values.
inline std::string shortestText(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace rw::common
