#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rw::common {

/// A number read from XML text, or why it could not be read.
struct ParsedNumber {
  /// The value (valid when `error` is empty).
  double value = 0.0;
  /// Empty on success, else a message such as `"abc" is not a number`.
  std::string error;
};

/// Reads one finite number (decimal or exponent form, optional sign, surrounding whitespace
/// allowed). NaN, infinities and values out of double range are errors.
ParsedNumber parseFiniteNumber(std::string_view text);

/// Reads whitespace-separated finite numbers into `values`; on failure returns the message for
/// the first bad token and leaves `values` partly filled.
std::string parseNumberList(std::string_view text, std::vector<double>& values);

}  // namespace rw::common
