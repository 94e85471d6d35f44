#include "visgrab/importers/json_value.hpp"

#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

#include "visgrab/importers/nd_array.hpp"

namespace visgrab::importers {

const JsonValue* JsonValue::find(std::string_view key) const {
  if (kind != Kind::kObject) return nullptr;
  const auto it = members.find(key);
  return it == members.end() ? nullptr : &it->second;
}

const char* jsonKindName(JsonValue::Kind kind) {
  switch (kind) {
    case JsonValue::Kind::kNull:
      return "null";
    case JsonValue::Kind::kBool:
      return "true/false";
    case JsonValue::Kind::kNumber:
      return "number";
    case JsonValue::Kind::kString:
      return "string";
    case JsonValue::Kind::kArray:
      return "array";
    case JsonValue::Kind::kObject:
      return "object";
  }
  return "value";
}

namespace {

constexpr int kMaxDepth = 64;

class JsonParser {
 public:
  JsonParser(std::string_view text, const std::string& name, std::size_t maxValues)
      : text_(text), name_(name), maxValues_(maxValues) {}

  JsonValue document() {
    JsonValue v = value(0);
    skipSpace();
    if (at_ != text_.size()) fail("text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw ImportError(name_ + ":" + std::to_string(line_) + ":" +
                      std::to_string(static_cast<int>(at_ - lineStart_) + 1) + ": " + what);
  }
  char peek() const { return at_ < text_.size() ? text_[at_] : '\0'; }
  void skipSpace() {
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (c == '\n') {
        ++line_;
        lineStart_ = at_ + 1;
      } else if (c != ' ' && c != '\t' && c != '\r') {
        return;
      }
      ++at_;
    }
  }
  bool consume(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }

  JsonValue value(int depth) {
    if (depth > kMaxDepth) fail("nested more than " + std::to_string(kMaxDepth) + " deep");
    skipSpace();
    if (++values_ > maxValues_) {
      fail("more than " + std::to_string(maxValues_) +
           " JSON values; a grasp file this large is not read (split it)");
    }
    JsonValue v;
    v.line = line_;
    v.column = static_cast<int>(at_ - lineStart_) + 1;
    const char c = peek();
    if (c == '{') {
      v.kind = JsonValue::Kind::kObject;
      ++at_;
      skipSpace();
      if (peek() == '}') {
        ++at_;
        return v;
      }
      while (true) {
        skipSpace();
        if (peek() != '"') fail("expected a member name in double quotes");
        std::string key = string();
        skipSpace();
        if (peek() != ':') fail("expected ':' after member name \"" + key + "\"");
        ++at_;
        JsonValue member = value(depth + 1);
        if (!v.members.emplace(key, std::move(member)).second) {
          fail("member \"" + key + "\" given twice");
        }
        skipSpace();
        if (peek() == ',') {
          ++at_;
        } else if (peek() == '}') {
          ++at_;
          return v;
        } else {
          fail("expected ',' or '}' in an object");
        }
      }
    }
    if (c == '[') {
      v.kind = JsonValue::Kind::kArray;
      ++at_;
      skipSpace();
      if (peek() == ']') {
        ++at_;
        return v;
      }
      while (true) {
        v.items.push_back(value(depth + 1));
        skipSpace();
        if (peek() == ',') {
          ++at_;
        } else if (peek() == ']') {
          ++at_;
          return v;
        } else {
          fail("expected ',' or ']' in an array");
        }
      }
    }
    if (c == '"') {
      v.kind = JsonValue::Kind::kString;
      v.text = string();
      return v;
    }
    if (consume("true") || consume("false")) {
      v.kind = JsonValue::Kind::kBool;
      v.flag = text_[at_ - 1] == 'e' && text_[at_ - 2] == 'u';
      return v;
    }
    if (consume("null")) return v;
    if (c == '-' || (c >= '0' && c <= '9')) {
      v.kind = JsonValue::Kind::kNumber;
      v.number = number();
      return v;
    }
    fail("expected a JSON value");
  }

  // -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
  double number() {
    const std::size_t start = at_;
    auto digits = [this] {
      const std::size_t from = at_;
      while (peek() >= '0' && peek() <= '9') ++at_;
      return at_ > from;
    };
    if (peek() == '-') ++at_;
    if (peek() == '0') {
      ++at_;
    } else if (!digits()) {
      fail("expected digits in a number");
    }
    if (peek() == '.') {
      ++at_;
      if (!digits()) fail("expected digits after '.'");
    }
    if (peek() == 'e' || peek() == 'E') {
      ++at_;
      if (peek() == '+' || peek() == '-') ++at_;
      if (!digits()) fail("expected digits in the exponent");
    }
    // from_chars, not strtod: the same digits read the same whatever the program's locale.
    const std::string_view literal = text_.substr(start, at_ - start);
    double value = 0.0;
    const auto [end, error] =
        std::from_chars(literal.data(), literal.data() + literal.size(), value);
    if (error != std::errc() || end != literal.data() + literal.size() || !std::isfinite(value)) {
      fail("number " + std::string(literal) + " is out of range");
    }
    return value;
  }

  void appendUtf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  unsigned hex4() {
    unsigned code = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = peek();
      unsigned d = 0;
      if (h >= '0' && h <= '9') {
        d = static_cast<unsigned>(h - '0');
      } else if (h >= 'a' && h <= 'f') {
        d = static_cast<unsigned>(h - 'a' + 10);
      } else if (h >= 'A' && h <= 'F') {
        d = static_cast<unsigned>(h - 'A' + 10);
      } else {
        fail("expected 4 hex digits after \\u");
      }
      code = code * 16 + d;
      ++at_;
    }
    return code;
  }

  std::string string() {
    ++at_;  // the opening quote
    std::string out;
    while (true) {
      if (at_ >= text_.size()) fail("unterminated string");
      const char c = text_[at_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_ >= text_.size()) fail("unterminated string");
      const char e = peek();
      ++at_;
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          unsigned code = hex4();
          if (code >= 0xD800 && code < 0xDC00) {
            if (!consume("\\u")) fail("a lone high surrogate in \\u escapes");
            const unsigned low = hex4();
            if (low < 0xDC00 || low >= 0xE000) fail("expected a low surrogate after \\u");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          } else if (code >= 0xDC00 && code < 0xE000) {
            fail("a lone low surrogate in \\u escapes");
          }
          appendUtf8(out, code);
          break;
        }
        default:
          fail("unknown escape in a string");
      }
    }
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t at_ = 0;
  int line_ = 1;
  std::size_t lineStart_ = 0;
  std::size_t maxValues_;
  std::size_t values_ = 0;
};

}  // namespace

JsonValue parseJson(std::string_view text, const std::string& name, std::size_t maxValues) {
  return JsonParser(text, name, maxValues).document();
}

}  // namespace visgrab::importers
