#include "visgrab/database/detail/opencv_yaml.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <limits>
#include <map>
#include <system_error>
#include <utility>

namespace visgrab::database::detail {

namespace {

/// Deeper nesting than any calibration needs is refused (no stack overflow on hostile input).
constexpr int kMaxDepth = 16;

/// A line with content: its number, indentation and text without the comment and trailing
/// blanks.
struct Line {
  int number = 0;
  std::size_t indent = 0;
  std::string_view text;
};

std::string shown(std::string_view text) {
  constexpr std::size_t kMax = 40;
  return "'" + std::string(text.substr(0, kMax)) + (text.size() > kMax ? "...'" : "'");
}

std::string_view trimRight(std::string_view s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) {
    s.remove_suffix(1);
  }
  return s;
}

std::string_view trimLeft(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

/// `text` without a comment: from a '#' at its start or after a blank, outside "...".
std::string_view stripComment(std::string_view text) {
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') quoted = !quoted;
    if (c == '#' && !quoted && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t')) {
      return text.substr(0, i);
    }
  }
  return text;
}

bool isDirective(std::string_view text) {
  if (text.rfind("%YAML", 0) != 0) return false;
  const std::string_view rest = text.substr(5);
  return rest.size() >= 4 && (rest[0] == ':' || rest[0] == ' ') && rest.substr(1, 2) == "1.";
}

/// The lines with content, after the optional directive and document start.
std::vector<Line> contentLines(std::string_view text) {
  std::vector<Line> lines;
  bool started = false;  // a key was seen (directive and "---" only before)
  bool directiveAllowed = true;
  std::size_t start = 0;
  for (int number = 1; start <= text.size(); ++number) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view raw = text.substr(start, end - start);
    start = end + 1;
    if (raw.find('\0') != std::string_view::npos) throw YamlError(number, "a NUL byte");
    const std::string_view body = trimRight(stripComment(raw));
    std::size_t indent = 0;
    while (indent < body.size() && body[indent] == ' ') ++indent;
    if (indent == body.size()) continue;  // blank or comment only
    if (body[indent] == '\t') {
      throw YamlError(number, "a tab in the indentation (YAML indents with spaces)");
    }
    const std::string_view content = body.substr(indent);
    if (content.front() == '%') {
      if (!directiveAllowed || !isDirective(content)) {
        throw YamlError(number, "unexpected directive " + shown(content) +
                                    " (only '%YAML:1.0' on the first line)");
      }
      directiveAllowed = false;
      continue;
    }
    directiveAllowed = false;
    if (content == "---") {
      if (started) throw YamlError(number, "a second document ('---'); expected one document");
      started = true;
      continue;
    }
    if (content == "...") {
      // End of the document: nothing may follow but comments.
      for (std::size_t s = start; s <= text.size();) {
        ++number;
        const std::size_t e = std::min(text.find('\n', s), text.size());
        if (!trimLeft(trimRight(stripComment(text.substr(s, e - s)))).empty()) {
          throw YamlError(number, "text after the end of the document ('...')");
        }
        s = e + 1;
      }
      break;
    }
    started = true;
    lines.push_back({number, indent, content});
  }
  return lines;
}

bool isKeyStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_'; }

bool isKeyChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.';
}

/// A scalar item: "..." (no escapes but \" and \\) or plain text.
std::string scalarText(std::string_view text, int line) {
  if (text.empty() || text.front() != '"') {
    if (text.find(": ") != std::string_view::npos || (!text.empty() && text.back() == ':')) {
      throw YamlError(line, "a value cannot hold ': ' (nested mappings go on their own lines)");
    }
    return std::string(text);
  }
  std::string out;
  for (std::size_t i = 1; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\\' && i + 1 < text.size() && (text[i + 1] == '"' || text[i + 1] == '\\')) {
      out += text[++i];
    } else if (c == '"') {
      if (!trimLeft(text.substr(i + 1)).empty()) {
        throw YamlError(line, "text after a closing quote: " + shown(text.substr(i + 1)));
      }
      return out;
    } else {
      out += c;
    }
  }
  throw YamlError(line, "a quoted value is not closed");
}

class Parser {
 public:
  explicit Parser(std::vector<Line> lines) : lines_(std::move(lines)) {}

  YamlNode document() {
    YamlNode root;
    root.kind = YamlNode::Kind::kMap;
    root.line = 1;
    if (lines_.empty()) return root;
    root.line = lines_.front().number;
    root = mapping(lines_.front().indent, 0);
    if (pos_ < lines_.size()) {
      const Line& l = lines_[pos_];
      throw YamlError(l.number, "less indented than the first key (" +
                                    std::to_string(lines_.front().indent) +
                                    " spaces): " + shown(l.text));
    }
    return root;
  }

 private:
  YamlNode mapping(std::size_t indent, int depth) {
    if (depth > kMaxDepth) {
      throw YamlError(lines_[pos_].number,
                      "mappings nested deeper than " + std::to_string(kMaxDepth) + " levels");
    }
    YamlNode map;
    map.kind = YamlNode::Kind::kMap;
    map.line = lines_[pos_].number;
    std::map<std::string, int, std::less<>> seen;
    while (pos_ < lines_.size() && lines_[pos_].indent == indent) {
      const Line line = lines_[pos_++];
      auto [key, rest] = splitKey(line);
      YamlNode value = valueOf(line, rest, indent, depth);
      const auto [it, inserted] = seen.emplace(key, line.number);
      if (!inserted) {
        throw YamlError(line.number, "key '" + key + "' is given twice (first at line " +
                                         std::to_string(it->second) + ")");
      }
      if (pos_ < lines_.size() && lines_[pos_].indent > indent) {
        throw YamlError(lines_[pos_].number, "unexpected indentation: expected a key at column " +
                                                 std::to_string(indent + 1) + ", found " +
                                                 shown(lines_[pos_].text));
      }
      value.key = std::move(key);
      map.items.push_back(std::move(value));
    }
    return map;
  }

  static std::pair<std::string, std::string_view> splitKey(const Line& line) {
    const std::string_view t = line.text;
    if (t.front() == ':') {
      throw YamlError(line.number,
                      "a value without a key (the line starts with ':'); expected "
                      "KEY: VALUE");
    }
    if (t.front() == '-' && (t.size() == 1 || t[1] == ' ')) {
      throw YamlError(line.number,
                      "a block sequence item ('- ...'); expected KEY: VALUE (sequences are "
                      "written [ a, b ])");
    }
    std::size_t i = 0;
    if (isKeyStart(t[0])) {
      while (i < t.size() && isKeyChar(t[i])) ++i;
    }
    if (i == 0 || i >= t.size() || t[i] != ':' || (i + 1 < t.size() && t[i + 1] != ' ')) {
      throw YamlError(line.number,
                      "expected KEY: VALUE (a key is a letter or '_' followed by "
                      "letters, digits, '_', '-', '.'), found " +
                          shown(t));
    }
    return {std::string(t.substr(0, i)), trimLeft(t.substr(i + 1))};
  }

  YamlNode valueOf(const Line& line, std::string_view rest, std::size_t indent, int depth) {
    YamlNode value;
    value.line = line.number;
    if (rest.rfind("!!", 0) == 0) {
      const std::size_t end = std::min(rest.find(' '), rest.size());
      value.tag = std::string(rest.substr(2, end - 2));
      if (value.tag.empty()) throw YamlError(line.number, "an empty tag '!!'");
      rest = trimLeft(rest.substr(end));
    } else if (!rest.empty() && rest.front() == '!') {
      throw YamlError(line.number, "a local tag " + shown(rest) + " (expected '!!name')");
    }
    if (rest.empty()) {
      if (pos_ < lines_.size() && lines_[pos_].indent > indent) {
        YamlNode map = mapping(lines_[pos_].indent, depth + 1);
        map.line = line.number;
        map.tag = std::move(value.tag);
        return map;
      }
      return value;  // an empty scalar
    }
    switch (rest.front()) {
      case '[':
        sequence(value, line, rest, indent);
        return value;
      case '{':
        throw YamlError(line.number,
                        "a flow mapping '{ ... }' (write the entries on their own "
                        "lines, indented)");
      case '&':
      case '*':
      case '|':
      case '>':
        throw YamlError(line.number, std::string("'") + rest.front() +
                                         "' (anchors, aliases and block scalars are not "
                                         "supported)");
      case '-':
        if (rest.size() == 1 || rest[1] == ' ') {
          throw YamlError(line.number,
                          "a block sequence item after a key; expected a value or "
                          "[ a, b ]");
        }
        break;
      default:
        break;
    }
    value.scalar = scalarText(rest, line.number);
    return value;
  }

  /// A flow sequence starting at `rest` ('['); later lines, more indented, continue it.
  void sequence(YamlNode& seq, const Line& line, std::string_view rest, std::size_t indent) {
    seq.kind = YamlNode::Kind::kSequence;
    int number = line.number;
    std::string_view text = rest.substr(1);
    std::string item;
    bool quoted = false;
    bool itemStarted = false;
    bool closedQuote = false;
    auto finishItem = [&](bool last) {
      std::string_view t = trimRight(item);
      if (!itemStarted) {
        if (last && seq.items.empty()) return;  // [ ]
        throw YamlError(number, "an empty item in [ ... ]");
      }
      YamlNode scalar;
      scalar.line = number;
      scalar.scalar = std::string(t);
      seq.items.push_back(std::move(scalar));
      item.clear();
      itemStarted = false;
      closedQuote = false;
    };
    while (true) {
      for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
          if (c == '"') {
            quoted = false;
            closedQuote = true;
          } else {
            item += c;
          }
          continue;
        }
        if (c == ' ' || c == '\t') {
          if (itemStarted && !closedQuote) item += c;
          continue;
        }
        if (c == ',' || c == ']') {
          finishItem(c == ']');
          if (c == ']') {
            if (!trimLeft(text.substr(i + 1)).empty()) {
              throw YamlError(number, "text after ']': " + shown(trimLeft(text.substr(i + 1))));
            }
            return;
          }
          continue;
        }
        if (closedQuote) throw YamlError(number, "text after a closing quote in [ ... ]");
        if (c == '[' || c == '{') {
          throw YamlError(number, std::string("'") + c +
                                      "' inside [ ... ] (nested sequences and mappings are not "
                                      "supported)");
        }
        if (c == '"' && !itemStarted) {
          quoted = true;
          itemStarted = true;
          continue;
        }
        item += c;
        itemStarted = true;
      }
      if (quoted) throw YamlError(number, "a quoted item in [ ... ] is not closed on its line");
      if (pos_ >= lines_.size() || lines_[pos_].indent <= indent) {
        throw YamlError(line.number, "'[' is not closed (expected ']')");
      }
      // The sequence goes on: a line break separates nothing, as a blank does.
      if (itemStarted) item += ' ';
      number = lines_[pos_].number;
      text = lines_[pos_++].text;
    }
  }

  std::vector<Line> lines_;
  std::size_t pos_ = 0;
};

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

const YamlNode* YamlNode::find(std::string_view name) const {
  if (kind != Kind::kMap) return nullptr;
  for (const YamlNode& entry : items) {
    if (entry.key == name) return &entry;
  }
  return nullptr;
}

std::optional<double> YamlNode::number() const {
  if (kind != Kind::kScalar || scalar.empty()) return std::nullopt;
  const std::string l = lower(scalar);
  if (l == ".nan") return std::numeric_limits<double>::quiet_NaN();
  if (l == ".inf" || l == "+.inf") return std::numeric_limits<double>::infinity();
  if (l == "-.inf") return -std::numeric_limits<double>::infinity();
  std::string_view t = scalar;
  if (t.front() == '+') t.remove_prefix(1);
  if (t.empty() || t.front() == '+') return std::nullopt;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec != std::errc() || ptr != t.data() + t.size()) return std::nullopt;
  return value;
}

std::optional<int> YamlNode::integer() const {
  if (kind != Kind::kScalar || scalar.empty()) return std::nullopt;
  std::string_view t = scalar;
  if (t.front() == '+') t.remove_prefix(1);
  int value = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec != std::errc() || ptr != t.data() + t.size()) return std::nullopt;
  return value;
}

YamlNode parseOpencvYaml(std::string_view text) { return Parser(contentLines(text)).document(); }

}  // namespace visgrab::database::detail
