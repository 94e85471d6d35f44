#include "rw/loaders/workcell_loader.hpp"

#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/loaders/detail/preprocess.hpp"
#include "rw/loaders/detail/wc_builder.hpp"
#include "rw/loaders/detail/wc_elements.hpp"
#include "rw/loaders/detail/wc_parser.hpp"
#include "rw/loaders/detail/workcell_schema.hpp"

namespace rw::loaders {

namespace fs = std::filesystem;
using rw::models::WorkCell;

namespace {

std::string absoluteName(const fs::path& file) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(file, ec);
  return (ec ? file : absolute).lexically_normal().string();
}

// The whole pipeline: XML and schema (per file), Include/Define/Use, description, model.
// `text` is the top-level file's content when it does not come from disk.
std::unique_ptr<WorkCell> load(const fs::path& file, std::optional<std::string_view> text,
                               const WorkCellLoadOptions& options, common::DiagnosticSink& sink) {
  auto source =
      std::make_shared<common::SourceFile>(common::SourceFile{detail::displayPathOf(file), {}});
  try {
    if (file.empty()) {
      sink.error(common::SourceLocation{}, "no workcell file name given");
      return nullptr;
    }
    common::XmlReader reader(common::XmlReaderOptions{std::string(detail::workcellSchema()),
                                                      detail::explainWorkCellValueError});
    detail::Preprocessor preprocessor(reader, sink, options.includeRedirects);
    const auto elements =
        text ? preprocessor.expandText(*text, file) : preprocessor.expandFile(file);
    if (!elements || sink.hasErrors()) return nullptr;
    const auto desc =
        detail::parseWorkCellDescription(*elements, common::SourceLocation{source, 0, 0}, sink);
    if (!desc || sink.hasErrors()) return nullptr;
    common::XmlReader setupReader(common::XmlReaderOptions{});
    auto wc = detail::buildWorkCell(*desc, setupReader, absoluteName(file), sink);
    if (sink.hasErrors()) return nullptr;
    return wc;
  } catch (const std::bad_alloc&) {
    sink.error(common::SourceLocation{source, 0, 0}, "out of memory while loading the workcell");
  } catch (const std::exception& e) {
    sink.error(common::SourceLocation{source, 0, 0},
               std::string("internal error while loading the workcell: ") + e.what());
  }
  return nullptr;
}

std::unique_ptr<WorkCell> loadOrThrow(const fs::path& file, std::optional<std::string_view> text,
                                      const WorkCellLoadOptions& options,
                                      std::vector<common::Diagnostic>* warnings) {
  common::DiagnosticSink sink;
  auto wc = load(file, text, options, sink);
  if (!wc && !sink.hasErrors()) {
    sink.error(common::SourceLocation{}, "the workcell could not be loaded");
  }
  if (warnings != nullptr) {
    for (const common::Diagnostic& d : sink.diagnostics()) {
      if (d.severity == common::Diagnostic::Severity::kWarning) warnings->push_back(d);
    }
  }
  if (sink.hasErrors()) throw common::LoadError(sink.take());
  return wc;
}

// What identifies a file for a redirect: its canonical path if it can be found.
fs::path identityOf(const fs::path& file) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(file, ec);
  if (ec) canonical = fs::absolute(file, ec).lexically_normal();
  return canonical;
}

}  // namespace

std::optional<fs::path> redirectedInclude(const IncludeRedirects& redirects,
                                          const fs::path& resolved) {
  if (redirects.empty()) return std::nullopt;
  const fs::path identity = identityOf(resolved);
  for (const auto& [from, to] : redirects) {
    if (identityOf(from) == identity) return to;
  }
  return std::nullopt;
}

std::unique_ptr<WorkCell> loadWorkCell(const fs::path& file,
                                       std::vector<common::Diagnostic>* warnings) {
  return loadOrThrow(file, std::nullopt, WorkCellLoadOptions{}, warnings);
}

std::unique_ptr<WorkCell> loadWorkCell(const fs::path& file, const WorkCellLoadOptions& options,
                                       std::vector<common::Diagnostic>* warnings) {
  return loadOrThrow(file, std::nullopt, options, warnings);
}

std::unique_ptr<WorkCell> loadWorkCellFromString(std::string_view xml, const fs::path& virtualFile,
                                                 std::vector<common::Diagnostic>* warnings) {
  return loadOrThrow(virtualFile, xml, WorkCellLoadOptions{}, warnings);
}

std::unique_ptr<WorkCell> loadWorkCellFromString(std::string_view xml, const fs::path& virtualFile,
                                                 const WorkCellLoadOptions& options,
                                                 std::vector<common::Diagnostic>* warnings) {
  return loadOrThrow(virtualFile, xml, options, warnings);
}

std::vector<common::Diagnostic> checkWorkCell(const fs::path& file) {
  common::DiagnosticSink sink;
  try {
    (void)load(file, std::nullopt, WorkCellLoadOptions{}, sink);
  } catch (...) {
    // load() reports what it can; nothing may escape a check.
  }
  return sink.take();
}

}  // namespace rw::loaders
