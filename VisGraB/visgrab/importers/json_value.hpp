#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace visgrab::importers {

/// A JSON value as the strict reader (parseJson) gives it.
struct JsonValue {
  /// What the value is.
  enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject };
  /// Its kind.
  Kind kind = Kind::kNull;
  /// kBool: the value.
  bool flag = false;
  /// kNumber: the value.
  double number = 0.0;
  /// kString: the text (UTF-8).
  std::string text;
  /// kArray: the elements.
  std::vector<JsonValue> items;
  /// kObject: the members by name.
  std::map<std::string, JsonValue, std::less<>> members;
  /// 1-based line and column where the value starts (for messages).
  int line = 0;
  /// See line.
  int column = 0;

  /// The member `key` of an object, or nullptr (also when this is not an object).
  const JsonValue* find(std::string_view key) const;
};

/// The kind's name in messages: "null", "true/false", "number", "string", "array", "object".
const char* jsonKindName(JsonValue::Kind kind);

/// The most values parseJson reads by default. A JsonValue takes about 130 bytes and the text
/// of a number as little as 2 ("0,"), so without a cap a file near the importer's size limit
/// would ask for many times the machine's memory. 4 Mi values (about 0.5 GB parsed) hold
/// 260,000 grasps of 16 numbers; ACRONYM's files have 2,000.
inline constexpr std::size_t kMaxJsonValues = std::size_t{1} << 22;

/// Reads RFC 8259 JSON strictly (no comments, no trailing commas, no duplicate keys, nesting at
/// most 64 deep, at most `maxValues` values; numbers beyond a double's range, too large or too
/// small, are errors; the same text reads the same whatever the C locale). `name` names the
/// text in messages.
/// @throws ImportError "NAME:LINE:COLUMN: what was expected".
JsonValue parseJson(std::string_view text, const std::string& name,
                    std::size_t maxValues = kMaxJsonValues);

}  // namespace visgrab::importers
