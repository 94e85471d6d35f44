#include "visgrab/results/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "rw/common/number_text.hpp"

namespace visgrab::results {

namespace {

/// Where the reader is in the text: byte, line and the byte where that line starts.
struct Cursor {
  std::string_view text;
  std::size_t pos = 0;
  int line = 1;
  std::size_t lineStart = 0;
};

/// How a record ended.
enum class RecordEnd {
  kLineBreak,  ///< an unquoted line feed or CR LF (consumed)
  kEndOfText,  ///< the text ended first; `openQuote` tells whether inside a quoted field
};

CsvSyntaxError syntaxError(const Cursor& c, int recordLine, const std::string& what) {
  return CsvSyntaxError(recordLine, c.line, static_cast<int>(c.pos - c.lineStart) + 1, c.pos, what);
}

/// Reads one record from `c` into `fields`. `openQuote` is set to the cursor at the opening
/// quote when the text ends inside a quoted field.
RecordEnd readRecord(Cursor& c, std::vector<std::string>& fields, Cursor* openQuote) {
  const int recordLine = c.line;
  const std::string_view text = c.text;
  while (true) {
    std::string field;
    if (c.pos < text.size() && text[c.pos] == '"') {
      const Cursor open = c;
      ++c.pos;
      while (true) {
        if (c.pos >= text.size()) {
          if (openQuote) *openQuote = open;
          return RecordEnd::kEndOfText;
        }
        const char ch = text[c.pos];
        if (ch == '"') {
          if (c.pos + 1 < text.size() && text[c.pos + 1] == '"') {
            field += '"';
            c.pos += 2;
            continue;
          }
          ++c.pos;
          break;
        }
        field += ch;
        ++c.pos;
        if (ch == '\n') {
          ++c.line;
          c.lineStart = c.pos;
        }
      }
      const bool atSeparator =
          c.pos >= text.size() || text[c.pos] == ',' || text[c.pos] == '\n' ||
          (text[c.pos] == '\r' && (c.pos + 1 >= text.size() || text[c.pos + 1] == '\n'));
      if (!atSeparator) {
        throw syntaxError(c, recordLine,
                          "text after a closing quote (expected ',' or the end of the line)");
      }
    } else {
      while (c.pos < text.size()) {
        const char ch = text[c.pos];
        if (ch == ',' || ch == '\n') break;
        if (ch == '\r') {
          if (c.pos + 1 >= text.size() || text[c.pos + 1] == '\n') break;
          throw syntaxError(c, recordLine,
                            "carriage return outside quotes (allowed only before a line feed)");
        }
        if (ch == '"') throw syntaxError(c, recordLine, "quote inside an unquoted field");
        field += ch;
        ++c.pos;
      }
    }
    fields.push_back(std::move(field));
    if (c.pos >= text.size()) return RecordEnd::kEndOfText;
    const char separator = text[c.pos];
    if (separator == ',') {
      ++c.pos;
      continue;
    }
    if (separator == '\r') {
      if (c.pos + 1 >= text.size()) return RecordEnd::kEndOfText;  // cut between CR and LF
      ++c.pos;
    }
    ++c.pos;  // the line feed
    ++c.line;
    c.lineStart = c.pos;
    return RecordEnd::kLineBreak;
  }
}

}  // namespace

CsvSyntaxError::CsvSyntaxError(int recordLine, int line, int column, std::size_t offset,
                               const std::string& what)
    : std::invalid_argument(
          (line == recordLine ? std::string() : "line " + std::to_string(line) + ", ") + "column " +
          std::to_string(column) + ": " + what),
      recordLine_(recordLine),
      line_(line),
      column_(column),
      offset_(offset) {}

std::string csvField(std::string_view text, bool alwaysQuote) {
  const bool quote = alwaysQuote || text.find_first_of(",\"\n\r") != std::string_view::npos ||
                     (!text.empty() && (text.front() == ' ' || text.back() == ' '));
  if (!quote) return std::string(text);
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

std::string csvRecord(const std::vector<std::string>& fields) {
  std::string text;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i > 0) text += ',';
    text += csvField(fields[i]);
  }
  return text + "\n";
}

std::vector<std::string> splitCsvLine(std::string_view line) {
  Cursor c;
  c.text = line;
  std::vector<std::string> fields;
  Cursor open;
  open.pos = std::string_view::npos;
  const RecordEnd end = readRecord(c, fields, &open);
  if (open.pos != std::string_view::npos) throw syntaxError(open, 1, "quoted field is not closed");
  if (end == RecordEnd::kLineBreak) {
    throw std::invalid_argument("column " + std::to_string(c.pos) +
                                ": line break inside one line of CSV");
  }
  return fields;
}

std::vector<std::string> splitLegacyCsvLine(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  auto columnError = [](std::size_t at, const std::string& what) {
    return std::invalid_argument("column " + std::to_string(at + 1) + ": " + what);
  };
  while (true) {
    std::string field;
    if (i < line.size() && line[i] == '"') {
      const std::size_t open = i++;
      bool closed = false;
      while (i < line.size()) {
        const char c = line[i];
        if (c == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        if (c == '\\') {
          if (i + 1 >= line.size()) throw columnError(i, "backslash at the end of the line");
          const char e = line[i + 1];
          if (e == '\\') {
            field += '\\';
          } else if (e == 'n') {
            field += '\n';
          } else if (e == 'r') {
            field += '\r';
          } else {
            throw columnError(i,
                              std::string("unknown escape \\") + e + " (expected \\\\, \\n, \\r)");
          }
          i += 2;
          continue;
        }
        field += c;
        ++i;
      }
      if (!closed) throw columnError(open, "quoted field is not closed");
      if (i < line.size() && line[i] != ',') {
        throw columnError(i, "text after a closing quote (expected ',' or the end of the line)");
      }
    } else {
      const std::size_t end = std::min(line.find(',', i), line.size());
      field.assign(line.substr(i, end - i));
      if (field.find('"') != std::string::npos) {
        throw columnError(i + field.find('"'), "quote inside an unquoted field");
      }
      i = end;
    }
    fields.push_back(std::move(field));
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return fields;
}

CsvText parseCsv(std::string_view text) {
  CsvText out;
  Cursor c;
  c.text = text;
  while (c.pos < text.size()) {
    const std::size_t begin = c.pos;
    CsvRecord record;
    record.line = c.line;
    RecordEnd end = RecordEnd::kEndOfText;
    try {
      end = readRecord(c, record.fields, nullptr);
    } catch (const CsvSyntaxError& e) {
      // No line break after the error: the record was never finished (a torn write).
      if (text.find('\n', e.offset()) != std::string_view::npos) throw;
    }
    if (end == RecordEnd::kEndOfText) {
      out.torn = true;
      out.tornLine = record.line;
      break;
    }
    record.blank = record.fields.size() == 1 && record.fields[0].empty() && text[begin] != '"';
    out.records.push_back(std::move(record));
    out.completeBytes = c.pos;
  }
  return out;
}

std::string formatDouble(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return rw::common::shortestText(value);
}

double parseDouble(std::string_view text) {
  if (text == "nan") return std::nan("");
  if (text == "inf") return HUGE_VAL;
  if (text == "-inf") return -HUGE_VAL;
  double value = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size()) {
    throw std::invalid_argument("'" + std::string(text) + "' is not a number");
  }
  return value;
}

int parseInt(std::string_view text) {
  int value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || result.ec != std::errc() || result.ptr != text.data() + text.size()) {
    throw std::invalid_argument("'" + std::string(text) + "' is not an integer");
  }
  return value;
}

}  // namespace visgrab::results
