#include "json_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "rw/common/number_text.hpp"

namespace visgrab::app {

std::string JsonWriter::quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string JsonWriter::number(double number) {
  if (!std::isfinite(number)) return "null";
  return rw::common::shortestText(number);
}

void JsonWriter::newline() { *out_ << "\n" << std::string(2 * levels_.size(), ' '); }

void JsonWriter::beforeValue() {
  if (afterKey_) {
    afterKey_ = false;
    return;
  }
  if (levels_.empty()) return;
  if (levels_.back().bracket != '[') throw std::logic_error("JsonWriter: a member needs key()");
  if (levels_.back().count++ > 0) *out_ << ",";
  newline();
}

void JsonWriter::open(char bracket) {
  beforeValue();
  *out_ << bracket;
  levels_.push_back({bracket, 0});
}

void JsonWriter::close(char bracket) {
  if (levels_.empty() || levels_.back().bracket != bracket || afterKey_) {
    throw std::logic_error("JsonWriter: unbalanced close");
  }
  const bool empty = levels_.back().count == 0;
  levels_.pop_back();
  if (!empty) newline();
  *out_ << (bracket == '{' ? '}' : ']');
}

JsonWriter& JsonWriter::beginObject() {
  open('{');
  return *this;
}

JsonWriter& JsonWriter::endObject() {
  close('{');
  return *this;
}

JsonWriter& JsonWriter::beginArray() {
  open('[');
  return *this;
}

JsonWriter& JsonWriter::endArray() {
  close('[');
  return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
  if (levels_.empty() || levels_.back().bracket != '{' || afterKey_) {
    throw std::logic_error("JsonWriter: key() outside an object");
  }
  if (levels_.back().count++ > 0) *out_ << ",";
  newline();
  *out_ << quoted(name) << ": ";
  afterKey_ = true;
  return *this;
}

JsonWriter& JsonWriter::value(std::string_view text) {
  beforeValue();
  *out_ << quoted(text);
  return *this;
}

JsonWriter& JsonWriter::value(double number) {
  beforeValue();
  *out_ << JsonWriter::number(number);
  return *this;
}

JsonWriter& JsonWriter::value(std::int64_t number) {
  beforeValue();
  *out_ << number;
  return *this;
}

JsonWriter& JsonWriter::value(bool flag) {
  beforeValue();
  *out_ << (flag ? "true" : "false");
  return *this;
}

JsonWriter& JsonWriter::null() {
  beforeValue();
  *out_ << "null";
  return *this;
}

JsonWriter& JsonWriter::numbers(const std::vector<double>& values) {
  beforeValue();
  *out_ << "[";
  for (std::size_t i = 0; i < values.size(); ++i) *out_ << (i ? ", " : "") << number(values[i]);
  *out_ << "]";
  return *this;
}

void JsonWriter::finish() {
  if (!levels_.empty() || afterKey_) throw std::logic_error("JsonWriter: unclosed document");
  *out_ << "\n";
}

}  // namespace visgrab::app
