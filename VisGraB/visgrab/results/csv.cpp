#include "visgrab/results/csv.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "rw/common/number_text.hpp"

namespace visgrab::results {

std::string csvField(std::string_view text, bool alwaysQuote) {
  bool quote = alwaysQuote || text.find_first_of(",\"\\\n\r") != std::string_view::npos ||
               (!text.empty() && (text.front() == ' ' || text.back() == ' '));
  if (!quote) return std::string(text);
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\"\"";
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
      default:
        out += c;
    }
  }
  out += '"';
  return out;
}

std::vector<std::string> splitCsvLine(std::string_view line) {
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
