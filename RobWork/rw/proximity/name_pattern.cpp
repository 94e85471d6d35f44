#include "rw/proximity/name_pattern.hpp"

#include <regex>
#include <stdexcept>
#include <string_view>

namespace rw::proximity {

namespace {

constexpr std::string_view kRegexPrefix = "REGEX";

// The ECMAScript regex of a wildcard pattern: * and ? become .* and ., the rest is literal.
std::string wildcardToRegex(const std::string& pattern) {
  static const std::string kSpecial = R"(\^$.|+()[]{})";
  std::string regex;
  regex.reserve(2 * pattern.size());
  for (const char c : pattern) {
    if (c == '*') {
      regex += ".*";
    } else if (c == '?') {
      regex += '.';
    } else {
      if (kSpecial.find(c) != std::string::npos) regex += '\\';
      regex += c;
    }
  }
  return regex;
}

}  // namespace

struct NamePattern::Compiled {
  std::regex regex;
};

NamePattern::NamePattern(const std::string& pattern) : text_(pattern) {
  const bool raw = pattern.starts_with(kRegexPrefix);
  const std::string regex = raw ? pattern.substr(kRegexPrefix.size()) : wildcardToRegex(pattern);
  try {
    compiled_ =
        std::make_shared<const Compiled>(Compiled{std::regex(regex, std::regex::ECMAScript)});
  } catch (const std::regex_error& e) {
    throw std::invalid_argument("proximity rule pattern \"" + pattern +
                                "\" is not a valid regular expression: " + e.what());
  }
}

bool NamePattern::matches(const std::string& name) const {
  return std::regex_match(name, compiled_->regex);
}

}  // namespace rw::proximity
