#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

namespace visgrab::analysis::detail {

/// `value` with `digits` decimals (locale-independent); `undefined` for NaN.
inline std::string fixed(double value, int digits, std::string_view undefined = "–") {
  if (std::isnan(value)) return std::string(undefined);
  char buffer[64];
  const auto r =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, digits);
  return std::string(buffer, r.ptr);
}

/// A percentage rounded to an integer with " %" (paper Tables 3-4); `undefined` for NaN.
inline std::string percent(double value, std::string_view undefined = "–") {
  if (std::isnan(value)) return std::string(undefined);
  return fixed(value, 0) + " %";
}

}  // namespace visgrab::analysis::detail
