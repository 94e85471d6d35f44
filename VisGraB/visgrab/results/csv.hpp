#pragma once

#include <string>
#include <string_view>
#include <vector>

/// CSV text as the result files use it: RFC 4180 quoting, one record per line.
namespace visgrab::results {

/// `text` as one CSV field. Quoted when it contains a comma, quote, backslash, line break or
/// leading/trailing space, or when `alwaysQuote`; inside quotes `"` becomes `""`, and `\`, line
/// feed and carriage return become `\\`, `\n`, `\r`, so that a record never spans lines.
std::string csvField(std::string_view text, bool alwaysQuote = false);

/// Splits one CSV line (without its line break) into fields, undoing csvField.
/// @throws std::invalid_argument saying what is wrong (unterminated quote, text after a closing
/// quote, unknown escape) and at which 1-based column.
std::vector<std::string> splitCsvLine(std::string_view line);

/// Shortest text that reads back as exactly `value` ("nan", "inf", "-inf" for non-finite).
std::string formatDouble(double value);

/// Reads a number written by formatDouble (or any decimal). @throws std::invalid_argument.
double parseDouble(std::string_view text);

/// Reads a decimal integer. @throws std::invalid_argument.
int parseInt(std::string_view text);

}  // namespace visgrab::results
