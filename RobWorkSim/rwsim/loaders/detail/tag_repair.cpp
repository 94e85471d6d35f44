#include "rwsim/loaders/detail/tag_repair.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

namespace rwsim::loaders::detail {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

bool endsName(char c) { return isSpace(c) || c == '/' || c == '>' || c == '<'; }

/// True if an element name may start with this byte (ASCII name-start characters or the lead
/// byte of a multi-byte UTF-8 character).
bool startsName(char c) {
  const auto u = static_cast<unsigned char>(c);
  return std::isalpha(u) != 0 || c == '_' || c == ':' || (u >= 0xC2 && u <= 0xF4);
}

/// Length of the UTF-8 sequence at text[i], or 0 if it is not valid.
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  std::size_t n = 0;
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  if (c >= 0xE0 && c <= 0xEF) n = 3;
  if (c >= 0xF0 && c <= 0xF4) n = 4;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return 0;
  }
  return n;
}

/// True if the text starts with a UTF-16 byte order mark or declares an encoding other than
/// UTF-8.
bool declaresOtherEncoding(std::string_view text) {
  if (text.starts_with("\xFE\xFF") || text.starts_with("\xFF\xFE")) return true;
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  if (!text.starts_with("<?xml")) return false;
  const std::string_view declaration = text.substr(0, text.find("?>"));
  const auto at = declaration.find("encoding");
  if (at == std::string_view::npos) return false;
  const auto quote = declaration.find_first_of("\"'", at);
  if (quote == std::string_view::npos) return false;
  std::string value;
  for (std::size_t i = quote + 1;
       i < declaration.size() && declaration[i] != '"' && declaration[i] != '\''; ++i) {
    value += static_cast<char>(std::tolower(static_cast<unsigned char>(declaration[i])));
  }
  return value != "utf-8" && value != "utf8";
}

std::string hexByte(char c) {
  constexpr char kDigits[] = "0123456789ABCDEF";
  const auto u = static_cast<unsigned char>(c);
  return std::string("0x") + kDigits[u >> 4] + kDigits[u & 0xF];
}

/// Maps byte offsets to line and column (columns in UTF-8 characters).
class LineTable {
 public:
  explicit LineTable(std::string_view text) : text_(text) {
    starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') starts_.push_back(i + 1);
    }
  }

  TextPosition at(std::size_t offset) const {
    const auto it = std::upper_bound(starts_.begin(), starts_.end(), offset);
    const auto line = static_cast<std::size_t>(it - starts_.begin());
    int column = 1;
    for (std::size_t i = starts_[line - 1]; i < offset; ++i) {
      if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) ++column;
    }
    return TextPosition{static_cast<int>(line), column};
  }

 private:
  std::string_view text_;
  std::vector<std::size_t> starts_;
};

/// Walks the markup of a text, keeping a stack of open elements.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text), lines_(text) {}

  TagRepairResult run() {
    bool complete = true;
    std::size_t i = 0;
    while ((i = text_.find('<', i)) != std::string_view::npos) {
      const std::size_t next = step(i);
      if (next == std::string_view::npos) {
        complete = false;
        break;
      }
      i = next;
    }
    result_.text.append(text_.substr(copied_));
    if (complete && !open_.empty()) {
      result_.unclosed = std::make_pair(open_.back().first, lines_.at(open_.back().second));
    }
    return std::move(result_);
  }

 private:
  /// Handles the markup starting at text_[i] == '<'; returns where to continue or npos to stop.
  std::size_t step(std::size_t i) {
    const std::string_view rest = text_.substr(i);
    if (rest.starts_with("<!--")) return after(i + 4, "-->");
    if (rest.starts_with("<![CDATA[")) return after(i + 9, "]]>");
    if (rest.starts_with("<?")) return after(i + 2, "?>");
    if (rest.starts_with("<!")) return std::string_view::npos;
    if (rest.starts_with("</")) return endTag(i);
    return startTag(i);
  }

  std::size_t after(std::size_t from, std::string_view terminator) const {
    const std::size_t end = text_.find(terminator, from);
    return end == std::string_view::npos ? end : end + terminator.size();
  }

  std::size_t nameEnd(std::size_t from) const {
    std::size_t j = from;
    while (j < text_.size() && !endsName(text_[j])) ++j;
    return j;
  }

  std::size_t endTag(std::size_t i) {
    const std::size_t nameStart = i + 2;
    const std::size_t nameStop = nameEnd(nameStart);
    std::size_t j = nameStop;
    while (j < text_.size() && isSpace(text_[j])) ++j;
    if (nameStop == nameStart || j == text_.size() || text_[j] != '>') {
      return std::string_view::npos;
    }
    if (open_.empty()) return j + 1;  // nothing to close: the XML parser reports it
    const std::string_view name = text_.substr(nameStart, nameStop - nameStart);
    const std::string& innermost = open_.back().first;
    if (name != innermost) {
      result_.repairs.push_back(TagRepair{lines_.at(i), std::string(name), innermost});
      result_.text.append(text_.substr(copied_, nameStart - copied_));
      result_.text.append(innermost);
      copied_ = nameStop;
    }
    open_.pop_back();
    return j + 1;
  }

  std::size_t startTag(std::size_t i) {
    const std::size_t nameStart = i + 1;
    const std::size_t nameStop = nameEnd(nameStart);
    if (nameStop == nameStart || !startsName(text_[nameStart])) return std::string_view::npos;
    std::size_t j = nameStop;
    while (j < text_.size()) {
      const char c = text_[j];
      if (c == '"' || c == '\'') {
        j = text_.find(c, j + 1);
        if (j == std::string_view::npos) return j;
        ++j;
      } else if (c == '>') {
        if (text_[j - 1] != '/') {
          open_.emplace_back(std::string(text_.substr(nameStart, nameStop - nameStart)), i);
        }
        return j + 1;
      } else if (c == '<') {
        return std::string_view::npos;
      } else {
        ++j;
      }
    }
    return std::string_view::npos;
  }

  std::string_view text_;
  LineTable lines_;
  TagRepairResult result_;
  std::vector<std::pair<std::string, std::size_t>> open_;
  std::size_t copied_ = 0;
};

}  // namespace

TagRepairResult repairClosingTags(std::string_view text) { return Scanner(text).run(); }

std::optional<CharacterProblem> findInvalidCharacter(std::string_view text) {
  if (declaresOtherEncoding(text)) return std::nullopt;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    const auto u = static_cast<unsigned char>(c);
    const std::size_t n = utf8Length(text, i);
    if (n == 0 || (u < 0x20 && c != '\t' && c != '\n' && c != '\r')) {
      const std::string what = n == 0 ? " is not valid UTF-8" : " is not allowed in XML";
      return CharacterProblem{LineTable(text).at(i), "byte " + hexByte(c) + what};
    }
    i += n;
  }
  return std::nullopt;
}

}  // namespace rwsim::loaders::detail
