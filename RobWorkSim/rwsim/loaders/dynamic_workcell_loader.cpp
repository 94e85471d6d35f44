#include "rwsim/loaders/dynamic_workcell_loader.hpp"

#include <exception>
#include <new>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "rwsim/loaders/detail/dwc_builder.hpp"
#include "rwsim/loaders/detail/dwc_document.hpp"
#include "rwsim/loaders/detail/dwc_parser.hpp"
#include "rwsim/loaders/detail/dwc_schema.hpp"

namespace rwsim::loaders {

namespace fs = std::filesystem;
using rw::common::Diagnostic;
using rw::common::DiagnosticSink;
using rw::common::SourceFile;
using rw::common::SourceLocation;
using rwsim::dynamics::DynamicWorkCell;

namespace {

std::string absoluteName(const fs::path& file) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(file, ec);
  return (ec ? file : absolute).lexically_normal().string();
}

/// Re-reports a diagnostic of the workcell loader, adding the dynamic workcell that names the
/// workcell file to its include chain.
void forward(const Diagnostic& d, const std::string& referencedFrom, DiagnosticSink& sink) {
  SourceFile file{d.file, d.includedFrom};
  file.includedFrom.push_back(referencedFrom);
  const SourceLocation where{std::make_shared<const SourceFile>(std::move(file)), d.line, d.column};
  if (d.severity == Diagnostic::Severity::kError) {
    sink.error(where, d.message);
  } else {
    sink.warning(where, d.message);
  }
}

/// Loads the workcell the dynamic workcell names; forwards its diagnostics.
std::unique_ptr<rw::models::WorkCell> loadReferencedWorkCell(
    const detail::DynamicWorkCellDesc& desc, const fs::path& dwcFile,
    std::optional<std::string_view> workcellText, const DynamicWorkCellLoadOptions& options,
    DiagnosticSink& sink) {
  const fs::path file = dwcFile.parent_path() / desc.workcellFile;
  const std::string root = "<DynamicWorkcell workcell=\"" + desc.workcellFile + "\">: ";
  std::error_code ec;
  if (!workcellText && !fs::is_regular_file(file, ec)) {
    sink.error(desc.rootLocation,
               root + "cannot read the workcell file \"" + file.lexically_normal().string() +
                   "\": " + (fs::exists(file, ec) ? "it is not a file" : "no such file"));
    return nullptr;
  }
  const std::string referencedFrom =
      desc.rootLocation.file->displayPath + ":" + std::to_string(desc.rootLocation.line);
  std::vector<Diagnostic> warnings;
  try {
    const rw::loaders::WorkCellLoadOptions workcellOptions{options.includeRedirects};
    auto workcell = workcellText ? rw::loaders::loadWorkCellFromString(*workcellText, file,
                                                                       workcellOptions, &warnings)
                                 : rw::loaders::loadWorkCell(file, workcellOptions, &warnings);
    for (const Diagnostic& d : warnings) forward(d, referencedFrom, sink);
    return workcell;
  } catch (const rw::common::LoadError& e) {
    for (const Diagnostic& d : e.diagnostics()) forward(d, referencedFrom, sink);
  }
  return nullptr;
}

// The whole pipeline: text (tag repair, schema, Includes), description, workcell, model.
std::unique_ptr<DynamicWorkCell> load(const fs::path& file, std::optional<std::string_view> text,
                                      std::optional<std::string_view> workcellText,
                                      const DynamicWorkCellLoadOptions& options,
                                      DiagnosticSink& sink) {
  const auto source =
      std::make_shared<const SourceFile>(SourceFile{file.lexically_normal().string(), {}});
  const SourceLocation whole{source, 0, 0};
  try {
    if (file.empty()) {
      sink.error(SourceLocation{}, "no dynamic workcell file name given");
      return nullptr;
    }
    std::string content;
    if (!text) {
      const std::string problem = detail::readTextFile(file, content);
      if (!problem.empty()) {
        sink.error(whole, "cannot read the file: " + problem);
        return nullptr;
      }
      text = content;
    }
    rw::common::XmlReader reader(rw::common::XmlReaderOptions{
        std::string(detail::dynamicWorkCellSchema()), detail::explainDynamicWorkCellValueError});
    detail::DocumentReader documents(reader, sink, options.includeRedirects);
    const auto document = documents.read(*text, file);
    if (!document) return nullptr;
    const auto desc =
        detail::parseDynamicWorkCellDescription(document->root, document->topLevel, sink);
    if (!desc) return nullptr;
    auto workcell = loadReferencedWorkCell(*desc, file, workcellText, options, sink);
    if (!workcell || sink.hasErrors()) return nullptr;
    auto dwc = detail::buildDynamicWorkCell(*desc, std::move(workcell), sink);
    if (!dwc || sink.hasErrors()) return nullptr;
    dwc->setFileName(absoluteName(file));
    return dwc;
  } catch (const std::bad_alloc&) {
    sink.error(whole, "out of memory while loading the dynamic workcell");
  } catch (const std::exception& e) {
    sink.error(whole,
               std::string("internal error while loading the dynamic workcell: ") + e.what());
  }
  return nullptr;
}

std::unique_ptr<DynamicWorkCell> loadOrThrow(const fs::path& file,
                                             std::optional<std::string_view> text,
                                             std::optional<std::string_view> workcellText,
                                             const DynamicWorkCellLoadOptions& options,
                                             std::vector<Diagnostic>* warnings) {
  DiagnosticSink sink;
  auto dwc = load(file, text, workcellText, options, sink);
  if (!dwc && !sink.hasErrors()) {
    sink.error(SourceLocation{}, "the dynamic workcell could not be loaded");
  }
  if (warnings != nullptr) {
    for (const Diagnostic& d : sink.diagnostics()) {
      if (d.severity == Diagnostic::Severity::kWarning) warnings->push_back(d);
    }
  }
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  return dwc;
}

}  // namespace

std::unique_ptr<DynamicWorkCell> loadDynamicWorkCell(const fs::path& file,
                                                     std::vector<Diagnostic>* warnings) {
  return loadOrThrow(file, std::nullopt, std::nullopt, DynamicWorkCellLoadOptions{}, warnings);
}

std::unique_ptr<DynamicWorkCell> loadDynamicWorkCell(const fs::path& file,
                                                     const DynamicWorkCellLoadOptions& options,
                                                     std::vector<Diagnostic>* warnings) {
  return loadOrThrow(file, std::nullopt, std::nullopt, options, warnings);
}

std::unique_ptr<DynamicWorkCell> loadDynamicWorkCellFromString(std::string_view xml,
                                                               const fs::path& virtualFile,
                                                               std::vector<Diagnostic>* warnings) {
  return loadOrThrow(virtualFile, xml, std::nullopt, DynamicWorkCellLoadOptions{}, warnings);
}

std::unique_ptr<DynamicWorkCell> loadDynamicWorkCellFromStrings(std::string_view xml,
                                                                std::string_view workcellXml,
                                                                const fs::path& virtualFile,
                                                                std::vector<Diagnostic>* warnings) {
  return loadOrThrow(virtualFile, xml, workcellXml, DynamicWorkCellLoadOptions{}, warnings);
}

std::vector<Diagnostic> checkDynamicWorkCell(const fs::path& file) {
  DiagnosticSink sink;
  try {
    (void)load(file, std::nullopt, std::nullopt, DynamicWorkCellLoadOptions{}, sink);
  } catch (...) {
    // load() reports what it can; nothing may escape a check.
  }
  return sink.take();
}

}  // namespace rwsim::loaders
