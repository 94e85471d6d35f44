#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"

namespace rwsim::loaders::detail {

/// Deepest Include nesting accepted.
inline constexpr int kMaxIncludeDepth = 32;

using rw::common::readTextFile;

/// A dynamic workcell file and its includes, read into one list of top-level elements.
struct DynamicWorkCellDocument {
  /// The <DynamicWorkcell> root (its children are not used; see `topLevel`).
  rw::common::XmlElement root;
  /// The root's children with every Include replaced by the included file's children, in
  /// document order; each element keeps the file and line it was written at.
  std::vector<rw::common::XmlElement> topLevel;
};

/// Reads dynamic workcell files: repairs mismatched closing tags (with a warning each, as
/// RobWork reads them), validates against the schema and expands <Include file> elements:
/// the file must have the root <IncludeData>; its path is relative to the top-level file's
/// folder (RobWork's rule, reference §2.1), or, if not found there, relative to the including
/// file (with a warning); cycles and nesting deeper than kMaxIncludeDepth are errors. An Include
/// whose file has a redirect (rw::loaders::IncludeRedirects) reads the replacement instead.
class DocumentReader {
 public:
  /// Uses `reader` (with the dynamic workcell schema) and reports to `sink`; `redirects` must
  /// outlive the reader.
  DocumentReader(rw::common::XmlReader& reader, rw::common::DiagnosticSink& sink,
                 const rw::loaders::IncludeRedirects& redirects)
      : reader_(reader), sink_(sink), redirects_(redirects) {}

  /// Reads the top-level file `file` whose content is `text`; nullopt after an error.
  std::optional<DynamicWorkCellDocument> read(std::string_view text,
                                              const std::filesystem::path& file);

 private:
  struct Context;

  std::optional<rw::common::XmlElement> parseRoot(
      std::string_view text, const std::shared_ptr<const rw::common::SourceFile>& source,
      std::string_view expectedRoot);
  void expand(const std::vector<rw::common::XmlElement>& elements, const Context& context,
              std::vector<rw::common::XmlElement>& out);
  void include(const rw::common::XmlElement& element, const Context& context,
               std::vector<rw::common::XmlElement>& out);
  std::optional<std::filesystem::path> resolveInclude(const rw::common::XmlElement& element,
                                                      const std::string& file,
                                                      const Context& context);

  rw::common::XmlReader& reader_;
  rw::common::DiagnosticSink& sink_;
  const rw::loaders::IncludeRedirects& redirects_;
  std::filesystem::path topDir_;
  std::size_t filesRead_ = 0;
};

}  // namespace rwsim::loaders::detail
