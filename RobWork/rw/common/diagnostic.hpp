#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace rw::common {

/// One problem found in an input file, located at file:line:column.
struct Diagnostic {
  /// How bad it is: errors stop a load, warnings do not.
  enum class Severity { kError, kWarning };

  /// Error or warning.
  Severity severity = Severity::kError;
  /// The file the problem is in, as it was named to the loader (or derived from an Include).
  std::string file;
  /// 1-based line; 0 when the problem concerns the whole file.
  int line = 0;
  /// 1-based column; 0 when unknown.
  int column = 0;
  /// What is wrong and, where it helps, what was expected.
  std::string message;
  /// The Include chain that led to `file`, innermost first: each entry is "file:line" of an
  /// <Include> element; empty for the file given to the loader.
  std::vector<std::string> includedFrom;

  /// Compiler-style text: one "in file included from FILE:LINE" line per include level
  /// (innermost first), then "FILE:LINE:COL: error: MESSAGE" (":COL" omitted when 0, ":LINE"
  /// too when 0).
  std::string format() const;
};

/// Thrown when a file cannot be loaded; carries every diagnostic found (errors and warnings).
class LoadError : public std::runtime_error {
 public:
  /// Makes the error; what() is the formatted errors of `diagnostics`, one per line.
  explicit LoadError(std::vector<Diagnostic> diagnostics);
  /// All diagnostics, in the order they were found.
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace rw::common
