#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_tree.hpp"

/// Typed reading of XML attribute values and element text, shared by every parser of the
/// project: the same checks and the same messages ("<Box>: attribute z: "a" is not a number",
/// "<RPY>: expected 3 numbers, got 2", "<Box>: missing required attribute "z"") everywhere.
namespace rw::common {

/// A whole number read from text, or why it could not be read.
struct ParsedInteger {
  /// The value (valid when `error` is empty).
  long long value = 0;
  /// Empty on success, else a message such as `expected a positive integer, got "1.5"`.
  std::string error;
};

/// Reads one whole number in [min, max] (decimal, optional sign, surrounding whitespace
/// allowed). The message names the range: "a positive integer" (min 1, no upper bound),
/// "a non-negative integer" (min 0), "an integer" (no bounds), else "an integer from MIN to MAX".
ParsedInteger parseInteger(std::string_view text,
                           long long min = std::numeric_limits<long long>::min(),
                           long long max = std::numeric_limits<long long>::max());

/// Reads whitespace-separated finite numbers into `values` (cleared first). With `count` > 0
/// there must be exactly that many. Returns an empty string on success, else the problem: the
/// first bad token (`"abc" is not a number`) or `expected 3 numbers (x y z), got 2` (the bracket
/// holds `meaning`, left out when empty).
std::string parseNumbers(std::string_view text, std::size_t count, std::string_view meaning,
                         std::vector<double>& values);

/// Reads "true"/"false"/"1"/"0" (surrounding whitespace allowed); nullopt for anything else.
std::optional<bool> parseBoolean(std::string_view text);

/// The index of `text` in `names`, or nullopt.
std::optional<std::size_t> findChoice(std::string_view text,
                                      std::span<const std::string_view> names);

/// `"a", "b" or "c"`: the choices as a message lists them.
std::string listChoices(std::span<const std::string_view> names);

/// What kind of value an attribute holds, for explainAttributeValues.
enum class ValueKind {
  /// One finite number.
  kNumber,
  /// Finite numbers separated by whitespace (`count` of them when it is > 0).
  kNumbers,
  /// A whole number in [min, max].
  kInteger,
  /// true, false, 1 or 0.
  kBoolean,
  /// One of `choices`.
  kChoice,
};

/// One attribute and the kind of value it holds.
struct AttributeRule {
  /// Attribute name.
  std::string_view name;
  /// Kind of value.
  ValueKind kind = ValueKind::kNumber;
  /// kNumbers: how many (0 = any).
  std::size_t count = 0;
  /// kNumbers: what the numbers mean, for the message ("x y z").
  std::string_view meaning = {};
  /// kInteger: smallest value.
  long long min = std::numeric_limits<long long>::min();
  /// kInteger: largest value.
  long long max = std::numeric_limits<long long>::max();
  /// kChoice: the accepted values.
  std::span<const std::string_view> choices = {};
};

/// The problem with one attribute value under `rule`, or an empty string.
std::string checkAttributeValue(const AttributeRule& rule, std::string_view value);

/// For XmlReaderOptions::explainValueError: "attribute NAME: PROBLEM" for the first attribute of
/// `element` (in document order) that has a rule and breaks it, or an empty string.
std::string explainAttributeValues(const XmlElement& element, std::span<const AttributeRule> rules);

/// Reads typed attribute values and element text, reporting each problem to a sink at the
/// element as "DESCRIPTION: PROBLEM" (DESCRIPTION is XmlElement::describe() unless the parser
/// gives its own). Every reader returns nullopt after reporting; an absent optional attribute
/// gives nullopt without a report.
class XmlValueReader {
 public:
  /// How messages name an element.
  using Describe = std::function<std::string(const XmlElement&)>;

  /// Reports to `sink`; `describe` replaces XmlElement::describe() when given.
  explicit XmlValueReader(DiagnosticSink& sink, Describe describe = {});

  /// Records "DESCRIPTION: message" at the element.
  void error(const XmlElement& element, std::string_view message) const;
  /// Records a warning "DESCRIPTION: message" at the element.
  void warning(const XmlElement& element, std::string_view message) const;
  /// The element as messages name it.
  std::string describe(const XmlElement& element) const;

  /// The attribute's value; reports `missing required attribute "NAME"` if absent.
  const std::string* required(const XmlElement& element, std::string_view name) const;
  /// A required finite number attribute.
  std::optional<double> number(const XmlElement& element, std::string_view name) const;
  /// An optional finite number attribute.
  std::optional<double> optionalNumber(const XmlElement& element, std::string_view name) const;
  /// Required finite number attributes read in order; nullopt if any is missing or bad (each
  /// reported).
  std::optional<std::vector<double>> numbers(const XmlElement& element,
                                             std::initializer_list<std::string_view> names) const;
  /// A required list of finite numbers (`count` > 0: exactly that many, `meaning` in the
  /// message).
  std::optional<std::vector<double>> numberList(const XmlElement& element, std::string_view name,
                                                std::size_t count = 0,
                                                std::string_view meaning = {}) const;
  /// An optional list of finite numbers.
  std::optional<std::vector<double>> optionalNumberList(const XmlElement& element,
                                                        std::string_view name,
                                                        std::size_t count = 0,
                                                        std::string_view meaning = {}) const;
  /// A required attribute of three finite numbers.
  std::optional<std::array<double, 3>> vector3(const XmlElement& element, std::string_view name,
                                               std::string_view meaning = {}) const;
  /// A required whole number in [min, max].
  std::optional<long long> integer(const XmlElement& element, std::string_view name,
                                   long long min = std::numeric_limits<long long>::min(),
                                   long long max = std::numeric_limits<long long>::max()) const;
  /// An optional true/false/1/0 attribute.
  std::optional<bool> optionalBoolean(const XmlElement& element, std::string_view name) const;
  /// A required attribute that must be one of `names`; returns its index. Reports
  /// `unknown WHAT "VALUE"; expected "a", "b" or "c"` (WHAT defaults to `NAME`).
  std::optional<std::size_t> choice(const XmlElement& element, std::string_view name,
                                    std::span<const std::string_view> names,
                                    std::string_view what = {}) const;

  /// The element's text as one finite number.
  std::optional<double> textNumber(const XmlElement& element) const;
  /// The element's text as finite numbers (`count` > 0: exactly that many).
  std::optional<std::vector<double>> textNumbers(const XmlElement& element, std::size_t count = 0,
                                                 std::string_view meaning = {}) const;
  /// The element's text as three finite numbers.
  std::optional<std::array<double, 3>> textVector3(const XmlElement& element,
                                                   std::string_view meaning = {}) const;
  /// The element's text as true/false/1/0.
  std::optional<bool> textBoolean(const XmlElement& element) const;

  /// The sink the reader reports to.
  DiagnosticSink& sink() const { return sink_; }

 private:
  DiagnosticSink& sink_;
  Describe describe_;
};

}  // namespace rw::common
