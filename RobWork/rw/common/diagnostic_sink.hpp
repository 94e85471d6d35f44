#pragma once

#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "rw/common/diagnostic.hpp"

/// XML reading shared by the loaders of RobWork's formats: positions, diagnostics, an
/// element tree, a schema-validating reader and number parsing.
namespace rw::common {

/// A file read by a loader: the name used in messages and the Include chain that led to it.
struct SourceFile {
  /// Path as shown in messages (as given to the loader, or includer folder + Include file).
  std::string displayPath;
  /// "file:line" of each Include that led here, innermost first.
  std::vector<std::string> includedFrom;
};

/// A position in a source file (line and column 1-based; 0 = unknown).
struct SourceLocation {
  /// The file; null for problems not tied to a file.
  std::shared_ptr<const SourceFile> file;
  /// Line, 0 if unknown.
  int line = 0;
  /// Column, 0 if unknown.
  int column = 0;
};

/// Collects the diagnostics of one load. Identical diagnostics (same place, same text) are kept
/// once, so that content expanded several times by Define/Use reports a problem once.
class DiagnosticSink {
 public:
  /// Records an error at `where`.
  void error(const SourceLocation& where, std::string message);
  /// Records a warning at `where`.
  void warning(const SourceLocation& where, std::string message);
  /// Number of errors so far.
  std::size_t errorCount() const { return errors_; }
  /// True once an error was recorded.
  bool hasErrors() const { return errors_ > 0; }
  /// The diagnostics in the order found.
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  /// Moves the diagnostics out.
  std::vector<Diagnostic> take() { return std::move(diagnostics_); }

 private:
  void add(Diagnostic::Severity severity, const SourceLocation& where, std::string message);

  std::vector<Diagnostic> diagnostics_;
  std::set<std::tuple<int, std::string, int, int, std::string>> seen_;
  std::size_t errors_ = 0;
};

/// Makes `text` printable: invalid UTF-8 bytes and control characters become "\xNN".
std::string sanitizeText(std::string_view text);

}  // namespace rw::common
