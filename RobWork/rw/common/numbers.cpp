#include "rw/common/numbers.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include "rw/common/xml_tree.hpp"

namespace rw::common {

namespace {

bool isXmlSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

std::string quoted(std::string_view token) {
  if (token.size() > 40) return "\"" + std::string(token.substr(0, 37)) + "...\"";
  return "\"" + std::string(token) + "\"";
}

}  // namespace

ParsedNumber parseFiniteNumber(std::string_view text) {
  const std::string_view token = trimXmlSpace(text);
  ParsedNumber result;
  if (token.empty()) {
    result.error = "a number is missing";
    return result;
  }
  std::string_view digits = token;
  if (digits.front() == '+') digits.remove_prefix(1);
  // from_chars also takes "inf" and "nan" spellings; they are rejected below as not finite.
  const auto [end, ec] =
      std::from_chars(digits.data(), digits.data() + digits.size(), result.value);
  if (ec == std::errc::result_out_of_range) {
    result.error = quoted(token) + " is out of range";
  } else if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty() ||
             (digits.front() == '+' || digits.front() == '-') != (token.front() == '-')) {
    result.error = quoted(token) + " is not a number";
  } else if (!std::isfinite(result.value)) {
    result.error = quoted(token) + " is not a finite number";
  }
  return result;
}

std::string parseNumberList(std::string_view text, std::vector<double>& values) {
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isXmlSpace(text[i])) ++i;
    if (i == text.size()) break;
    std::size_t j = i;
    while (j < text.size() && !isXmlSpace(text[j])) ++j;
    const ParsedNumber n = parseFiniteNumber(text.substr(i, j - i));
    if (!n.error.empty()) return n.error;
    values.push_back(n.value);
    i = j;
  }
  return {};
}

}  // namespace rw::common
