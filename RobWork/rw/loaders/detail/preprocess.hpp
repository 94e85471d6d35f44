#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"

namespace rw::loaders::detail {

/// Deepest Include nesting accepted.
inline constexpr int kMaxIncludeDepth = 32;

using rw::common::readTextFile;

/// How a file is named in messages: the path as given, lexically normalised.
std::string displayPathOf(const std::filesystem::path& file);

/// Expands RobWork's pre-parser constructs on element trees, file by file (reference §1.2):
/// `<Include file>` is replaced by the elements of that file (relative to the including file,
/// cycles and depth checked), `<Define id>` stores its elements for `<Use id>` later in the same
/// file (Define/Use scope is one file, a Use needs an earlier Define). Elements keep the file
/// and line they were written at; files reached through Include carry the include chain. An
/// Include whose file has a redirect (IncludeRedirects) reads the replacement instead.
class Preprocessor {
 public:
  /// Uses `reader` to parse every file; reports problems to `sink`; `redirects` must outlive
  /// the preprocessor.
  Preprocessor(common::XmlReader& reader, common::DiagnosticSink& sink,
               const IncludeRedirects& redirects)
      : reader_(reader), sink_(sink), redirects_(redirects) {}

  /// Reads, parses and expands `file`; nullopt after an error in any file.
  std::optional<std::vector<common::XmlElement>> expandFile(const std::filesystem::path& file);

  /// Same for text that stands for `virtualFile` (relative Includes start in its folder).
  std::optional<std::vector<common::XmlElement>> expandText(
      std::string_view text, const std::filesystem::path& virtualFile);

 private:
  struct FileScope;

  std::optional<std::vector<common::XmlElement>> expandTopLevel(std::string_view text,
                                                                const std::filesystem::path& file);
  std::vector<common::XmlElement> expandList(std::vector<common::XmlElement> elements,
                                             FileScope& scope);
  void expandUse(const common::XmlElement& use, FileScope& scope,
                 std::vector<common::XmlElement>& out);
  void expandInclude(const common::XmlElement& include, FileScope& scope,
                     std::vector<common::XmlElement>& out);
  bool spendBudget(std::size_t elements, const common::SourceLocation& where);

  common::XmlReader& reader_;
  common::DiagnosticSink& sink_;
  const IncludeRedirects& redirects_;
  std::size_t elementBudgetUsed_ = 0;
  std::size_t filesRead_ = 0;
  bool overBudget_ = false;
};

}  // namespace rw::loaders::detail
