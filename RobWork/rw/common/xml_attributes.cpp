#include "rw/common/xml_attributes.hpp"

#include <charconv>
#include <system_error>
#include <utility>

#include "rw/common/numbers.hpp"

namespace rw::common {

namespace {

// A value as messages quote it (long values cut, so that one bad attribute cannot flood a log).
std::string quotedValue(std::string_view value) {
  constexpr std::size_t kLongest = 40;
  if (value.size() > kLongest) return "\"" + std::string(value.substr(0, kLongest - 3)) + "...\"";
  return "\"" + std::string(value) + "\"";
}

std::string integerKind(long long min, long long max) {
  constexpr long long kLowest = std::numeric_limits<long long>::min();
  constexpr long long kHighest = std::numeric_limits<long long>::max();
  if (max == kHighest && min == 1) return "a positive integer";
  if (max == kHighest && min == 0) return "a non-negative integer";
  if (max == kHighest && min == kLowest) return "an integer";
  if (max == kHighest) return "an integer >= " + std::to_string(min);
  if (min == kLowest) return "an integer <= " + std::to_string(max);
  return "an integer from " + std::to_string(min) + " to " + std::to_string(max);
}

std::string attributeProblem(std::string_view name, std::string_view problem) {
  return "attribute " + std::string(name) + ": " + std::string(problem);
}

}  // namespace

ParsedInteger parseInteger(std::string_view text, long long min, long long max) {
  const std::string_view token = trimXmlSpace(text);
  ParsedInteger result;
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  // "+-5" and "++5": one sign at most.
  const bool signOk = digits.size() == token.size() ||
                      (!digits.empty() && digits.front() != '-' && digits.front() != '+');
  const auto [end, ec] =
      std::from_chars(digits.data(), digits.data() + digits.size(), result.value);
  const bool whole = ec == std::errc() && end == digits.data() + digits.size() && signOk;
  if (!whole || result.value < min || result.value > max) {
    result.error = "expected " + integerKind(min, max) + ", got " + quotedValue(token);
  }
  return result;
}

std::string parseNumbers(std::string_view text, std::size_t count, std::string_view meaning,
                         std::vector<double>& values) {
  values.clear();
  std::string problem = parseNumberList(text, values);
  if (!problem.empty()) return problem;
  if (count > 0 && values.size() != count) {
    problem = "expected " + std::to_string(count) + " numbers";
    if (!meaning.empty()) problem += " (" + std::string(meaning) + ")";
    problem += ", got " + std::to_string(values.size());
  }
  return problem;
}

std::optional<bool> parseBoolean(std::string_view text) {
  const std::string_view token = trimXmlSpace(text);
  if (token == "true" || token == "1") return true;
  if (token == "false" || token == "0") return false;
  return std::nullopt;
}

std::optional<std::size_t> findChoice(std::string_view text,
                                      std::span<const std::string_view> names) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == text) return i;
  }
  return std::nullopt;
}

std::string listChoices(std::span<const std::string_view> names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += "\"" + std::string(names[i]) + "\"";
  }
  return out;
}

std::string checkAttributeValue(const AttributeRule& rule, std::string_view value) {
  switch (rule.kind) {
    case ValueKind::kNumber:
      return parseFiniteNumber(value).error;
    case ValueKind::kNumbers: {
      std::vector<double> values;
      return parseNumbers(value, rule.count, rule.meaning, values);
    }
    case ValueKind::kInteger:
      return parseInteger(value, rule.min, rule.max).error;
    case ValueKind::kBoolean:
      if (parseBoolean(value)) return {};
      return "expected true or false, got " + quotedValue(value);
    case ValueKind::kChoice:
      if (findChoice(value, rule.choices)) return {};
      return "expected " + listChoices(rule.choices) + ", got " + quotedValue(value);
  }
  return {};
}

std::string explainAttributeValues(const XmlElement& element,
                                   std::span<const AttributeRule> rules) {
  for (const XmlAttribute& a : element.attributes) {
    for (const AttributeRule& rule : rules) {
      if (rule.name != a.name) continue;
      const std::string problem = checkAttributeValue(rule, a.value);
      if (!problem.empty()) return attributeProblem(a.name, problem);
    }
  }
  return {};
}

XmlValueReader::XmlValueReader(DiagnosticSink& sink, Describe describe)
    : sink_(sink), describe_(std::move(describe)) {}

std::string XmlValueReader::describe(const XmlElement& element) const {
  return describe_ ? describe_(element) : element.describe();
}

void XmlValueReader::error(const XmlElement& element, std::string_view message) const {
  sink_.error(element.location, describe(element) + ": " + std::string(message));
}

void XmlValueReader::warning(const XmlElement& element, std::string_view message) const {
  sink_.warning(element.location, describe(element) + ": " + std::string(message));
}

const std::string* XmlValueReader::required(const XmlElement& element,
                                            std::string_view name) const {
  const std::string* value = element.attribute(name);
  if (value == nullptr) error(element, "missing required attribute \"" + std::string(name) + "\"");
  return value;
}

std::optional<double> XmlValueReader::number(const XmlElement& element,
                                             std::string_view name) const {
  if (element.attribute(name) == nullptr) {
    (void)required(element, name);
    return std::nullopt;
  }
  return optionalNumber(element, name);
}

std::optional<double> XmlValueReader::optionalNumber(const XmlElement& element,
                                                     std::string_view name) const {
  const std::string* value = element.attribute(name);
  if (value == nullptr) return std::nullopt;
  const ParsedNumber n = parseFiniteNumber(*value);
  if (!n.error.empty()) {
    error(element, attributeProblem(name, n.error));
    return std::nullopt;
  }
  return n.value;
}

std::optional<std::vector<double>> XmlValueReader::numbers(
    const XmlElement& element, std::initializer_list<std::string_view> names) const {
  std::vector<double> values;
  bool ok = true;
  for (std::string_view name : names) {
    const auto v = number(element, name);
    ok = ok && v.has_value();
    values.push_back(v.value_or(0.0));
  }
  if (!ok) return std::nullopt;
  return values;
}

std::optional<std::vector<double>> XmlValueReader::numberList(const XmlElement& element,
                                                              std::string_view name,
                                                              std::size_t count,
                                                              std::string_view meaning) const {
  if (required(element, name) == nullptr) return std::nullopt;
  return optionalNumberList(element, name, count, meaning);
}

std::optional<std::vector<double>> XmlValueReader::optionalNumberList(
    const XmlElement& element, std::string_view name, std::size_t count,
    std::string_view meaning) const {
  const std::string* value = element.attribute(name);
  if (value == nullptr) return std::nullopt;
  std::vector<double> values;
  const std::string problem = parseNumbers(*value, count, meaning, values);
  if (!problem.empty()) {
    error(element, attributeProblem(name, problem));
    return std::nullopt;
  }
  return values;
}

std::optional<std::array<double, 3>> XmlValueReader::vector3(const XmlElement& element,
                                                             std::string_view name,
                                                             std::string_view meaning) const {
  const auto values = numberList(element, name, 3, meaning);
  if (!values) return std::nullopt;
  return std::array<double, 3>{(*values)[0], (*values)[1], (*values)[2]};
}

std::optional<long long> XmlValueReader::integer(const XmlElement& element, std::string_view name,
                                                 long long min, long long max) const {
  const std::string* value = required(element, name);
  if (value == nullptr) return std::nullopt;
  const ParsedInteger n = parseInteger(*value, min, max);
  if (!n.error.empty()) {
    error(element, attributeProblem(name, n.error));
    return std::nullopt;
  }
  return n.value;
}

std::optional<bool> XmlValueReader::optionalBoolean(const XmlElement& element,
                                                    std::string_view name) const {
  const std::string* value = element.attribute(name);
  if (value == nullptr) return std::nullopt;
  const auto b = parseBoolean(*value);
  if (!b)
    error(element, attributeProblem(name, "expected true or false, got " + quotedValue(*value)));
  return b;
}

std::optional<std::size_t> XmlValueReader::choice(const XmlElement& element, std::string_view name,
                                                  std::span<const std::string_view> names,
                                                  std::string_view what) const {
  const std::string* value = required(element, name);
  if (value == nullptr) return std::nullopt;
  const auto index = findChoice(*value, names);
  if (index) return index;
  if (what.empty()) {
    error(element, attributeProblem(
                       name, "expected " + listChoices(names) + ", got " + quotedValue(*value)));
  } else {
    error(element, "unknown " + std::string(what) + " " + quotedValue(*value) + "; expected " +
                       listChoices(names));
  }
  return std::nullopt;
}

std::optional<double> XmlValueReader::textNumber(const XmlElement& element) const {
  const ParsedNumber n = parseFiniteNumber(element.text);
  if (!n.error.empty()) {
    error(element, n.error);
    return std::nullopt;
  }
  return n.value;
}

std::optional<std::vector<double>> XmlValueReader::textNumbers(const XmlElement& element,
                                                               std::size_t count,
                                                               std::string_view meaning) const {
  std::vector<double> values;
  const std::string problem = parseNumbers(element.text, count, meaning, values);
  if (!problem.empty()) {
    error(element, problem);
    return std::nullopt;
  }
  return values;
}

std::optional<std::array<double, 3>> XmlValueReader::textVector3(const XmlElement& element,
                                                                 std::string_view meaning) const {
  const auto values = textNumbers(element, 3, meaning);
  if (!values) return std::nullopt;
  return std::array<double, 3>{(*values)[0], (*values)[1], (*values)[2]};
}

std::optional<bool> XmlValueReader::textBoolean(const XmlElement& element) const {
  const auto b = parseBoolean(element.text);
  if (!b) {
    error(element, "expected true or false, got " + quotedValue(trimXmlSpace(element.text)));
  }
  return b;
}

}  // namespace rw::common
