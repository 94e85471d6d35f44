#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_tree.hpp"

namespace rw::common {

/// Name of the element every file is wrapped in before parsing, so that a file may hold several
/// top-level elements (RobWork's Include is textual). Declared, as internal, in the schema.
inline constexpr std::string_view kFragmentElement = "IncludeFragment";

/// Deepest element nesting accepted in one file.
inline constexpr int kMaxElementDepth = 100;

/// How an XmlReader checks documents.
struct XmlReaderOptions {
  /// XSD text to validate against; empty for a well-formedness check only. Its global elements
  /// must include kFragmentElement.
  std::string schema;
  /// Turns a schema datatype error on an element into a precise message (for example which
  /// attribute is not a number); returns an empty string when it cannot tell.
  std::function<std::string(const XmlElement&)> explainValueError;
};

/// Parses XML text with Xerces-C (SAX2) into XmlElement trees with positions. One reader
/// parses files one after the other; use one reader per thread.
class XmlReader {
 public:
  /// A reader with the given options (the schema is compiled on first use).
  explicit XmlReader(XmlReaderOptions options);
  ~XmlReader();
  XmlReader(const XmlReader&) = delete;
  XmlReader& operator=(const XmlReader&) = delete;

  /// Parses `text`, the content of `file`, and returns its top-level elements (any number).
  /// On the first well-formedness or validation problem it reports one error to `sink` (at the
  /// element concerned) and returns nullopt.
  std::optional<std::vector<XmlElement>> parse(std::string_view text,
                                               const std::shared_ptr<const SourceFile>& file,
                                               DiagnosticSink& sink);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rw::common
