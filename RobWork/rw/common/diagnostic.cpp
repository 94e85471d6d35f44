#include "rw/common/diagnostic.hpp"

#include <utility>

namespace rw::common {

namespace {

std::string joinErrors(const std::vector<Diagnostic>& diagnostics) {
  std::string text;
  for (const Diagnostic& d : diagnostics) {
    if (d.severity != Diagnostic::Severity::kError) continue;
    if (!text.empty()) text += '\n';
    text += d.format();
  }
  return text.empty() ? std::string("load failed") : text;
}

}  // namespace

std::string Diagnostic::format() const {
  std::string text;
  for (const std::string& includer : includedFrom) {
    text += "in file included from " + includer + "\n";
  }
  if (!file.empty()) {
    text += file;
    if (line > 0) {
      text += ':' + std::to_string(line);
      if (column > 0) text += ':' + std::to_string(column);
    }
    text += ": ";
  }
  text += severity == Severity::kError ? "error: " : "warning: ";
  text += message;
  return text;
}

LoadError::LoadError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(joinErrors(diagnostics)), diagnostics_(std::move(diagnostics)) {}

}  // namespace rw::common
