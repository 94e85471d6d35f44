#include "rw/common/diagnostic_sink.hpp"

#include <cstdio>
#include <utility>

namespace rw::common {

namespace {

// More diagnostics than this are not useful to anybody; the rest are summarised in one line.
constexpr std::size_t kMaxDiagnostics = 500;

// Length of the UTF-8 sequence starting at text[i], or 0 if it is not a valid one.
std::size_t utf8SequenceLength(std::string_view text, std::size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  std::size_t n = 0;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0 && c >= 0xC2) n = 2;
  if ((c & 0xF0) == 0xE0) n = 3;
  if ((c & 0xF8) == 0xF0 && c <= 0xF4) n = 4;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return 0;
  }
  return n;
}

}  // namespace

std::string sanitizeText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8SequenceLength(text, i);
    if (n == 0 || (c < 0x20 && c != '\n' && c != '\t') || c == 0x7F) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\x%02X", static_cast<unsigned>(c));
      out += buffer;
      ++i;
      continue;
    }
    out.append(text.substr(i, n));
    i += n;
  }
  return out;
}

void DiagnosticSink::error(const SourceLocation& where, std::string message) {
  add(Diagnostic::Severity::kError, where, std::move(message));
}

void DiagnosticSink::warning(const SourceLocation& where, std::string message) {
  add(Diagnostic::Severity::kWarning, where, std::move(message));
}

void DiagnosticSink::add(Diagnostic::Severity severity, const SourceLocation& where,
                         std::string message) {
  Diagnostic d;
  d.severity = severity;
  if (where.file) {
    d.file = where.file->displayPath;
    d.includedFrom = where.file->includedFrom;
  }
  d.line = where.line;
  d.column = where.column;
  d.message = sanitizeText(message);
  if (!seen_.emplace(static_cast<int>(severity), d.file, d.line, d.column, d.message).second) {
    return;
  }
  if (severity == Diagnostic::Severity::kError) ++errors_;
  if (diagnostics_.size() == kMaxDiagnostics) {
    Diagnostic more = d;
    more.message = "too many problems; the rest are not shown";
    diagnostics_.push_back(std::move(more));
  }
  if (diagnostics_.size() > kMaxDiagnostics) return;
  diagnostics_.push_back(std::move(d));
}

}  // namespace rw::common
