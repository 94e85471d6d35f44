#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/loaders/detail/diagnostic_sink.hpp"
#include "rw/loaders/detail/xml_reader.hpp"
#include "rw/loaders/detail/xml_tree.hpp"
#include "rw/loaders/xml/text_file.hpp"

namespace rw::loaders::detail {

/// Deepest Include nesting accepted.
inline constexpr int kMaxIncludeDepth = 32;

using rw::loaders::xml::readTextFile;

/// How a file is named in messages: the path as given, lexically normalised.
std::string displayPathOf(const std::filesystem::path& file);

/// Expands RobWork's pre-parser constructs on element trees, file by file (reference §1.2):
/// `<Include file>` is replaced by the elements of that file (relative to the including file,
/// cycles and depth checked), `<Define id>` stores its elements for `<Use id>` later in the same
/// file (Define/Use scope is one file, a Use needs an earlier Define). Elements keep the file
/// and line they were written at; files reached through Include carry the include chain.
class Preprocessor {
 public:
  /// Uses `reader` to parse every file; reports problems to `sink`.
  Preprocessor(XmlReader& reader, DiagnosticSink& sink) : reader_(reader), sink_(sink) {}

  /// Reads, parses and expands `file`; nullopt after an error in any file.
  std::optional<std::vector<XmlElement>> expandFile(const std::filesystem::path& file);

  /// Same for text that stands for `virtualFile` (relative Includes start in its folder).
  std::optional<std::vector<XmlElement>> expandText(std::string_view text,
                                                    const std::filesystem::path& virtualFile);

 private:
  struct FileScope;

  std::optional<std::vector<XmlElement>> expandTopLevel(std::string_view text,
                                                        const std::filesystem::path& file);
  std::vector<XmlElement> expandList(std::vector<XmlElement> elements, FileScope& scope);
  void expandUse(const XmlElement& use, FileScope& scope, std::vector<XmlElement>& out);
  void expandInclude(const XmlElement& include, FileScope& scope, std::vector<XmlElement>& out);
  bool spendBudget(std::size_t elements, const SourceLocation& where);

  XmlReader& reader_;
  DiagnosticSink& sink_;
  std::size_t elementBudgetUsed_ = 0;
  std::size_t filesRead_ = 0;
  bool overBudget_ = false;
};

}  // namespace rw::loaders::detail
