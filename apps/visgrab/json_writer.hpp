#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace visgrab::app {

/// Writes one JSON document (RFC 8259) to a stream, indented by two spaces: objects and arrays
/// are opened and closed in order, members are named with key(). Strings are escaped (quote,
/// backslash, control characters as \uXXXX; other bytes, UTF-8 included, pass unchanged).
/// Numbers are written in the shortest form that reads back as the same double; a NaN or
/// infinite number is written as null. An array of numbers (numbers()) goes on one line.
class JsonWriter {
 public:
  /// Writes to `out`, which must outlive this.
  explicit JsonWriter(std::ostream& out) : out_(&out) {}

  /// Opens an object (as a value: after key() in an object, or an array element).
  JsonWriter& beginObject();
  /// Closes the innermost object.
  JsonWriter& endObject();
  /// Opens an array.
  JsonWriter& beginArray();
  /// Closes the innermost array.
  JsonWriter& endArray();
  /// Names the next value of the innermost object.
  JsonWriter& key(std::string_view name);
  /// A string value.
  JsonWriter& value(std::string_view text);
  /// A string value (not a bool).
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  /// A number; null when not finite.
  JsonWriter& value(double number);
  /// An integer.
  JsonWriter& value(std::int64_t number);
  /// An integer.
  JsonWriter& value(int number) { return value(static_cast<std::int64_t>(number)); }
  /// An integer.
  JsonWriter& value(std::size_t number) { return value(static_cast<std::int64_t>(number)); }
  /// true or false.
  JsonWriter& value(bool flag);
  /// null.
  JsonWriter& null();
  /// An array of numbers on one line (each null when not finite).
  JsonWriter& numbers(const std::vector<double>& values);
  /// Ends the document with a newline. @pre every object and array is closed.
  void finish();

  /// `text` as a JSON string literal, quotes included.
  static std::string quoted(std::string_view text);
  /// `number` as a JSON number, or null when it is not finite.
  static std::string number(double number);

 private:
  // Before a value: the comma and line break of an array element (an object member had them
  // at key()).
  void beforeValue();
  void open(char bracket);
  void close(char bracket);
  void newline();

  struct Level {
    char bracket;
    int count;
  };
  std::ostream* out_;
  std::vector<Level> levels_;
  bool afterKey_ = false;
};

}  // namespace visgrab::app
