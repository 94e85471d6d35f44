#include "rwsim/loaders/detail/dwc_document.hpp"

#include <algorithm>
#include <fstream>
#include <system_error>
#include <utility>

#include "rwsim/loaders/detail/dwc_parser.hpp"
#include "rwsim/loaders/detail/tag_repair.hpp"

namespace rwsim::loaders::detail {

namespace fs = std::filesystem;
using rw::common::SourceFile;
using rw::common::SourceLocation;
using rw::common::XmlElement;

namespace {

constexpr std::size_t kMaxFilesRead = 10'000;

std::string displayPathOf(const fs::path& file) { return file.lexically_normal().string(); }

/// What identifies a file for cycle detection: its canonical path if it can be found.
std::string identityOf(const fs::path& file) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(file, ec);
  if (ec) canonical = fs::absolute(file, ec).lexically_normal();
  return canonical.string();
}

bool isFile(const fs::path& file) {
  std::error_code ec;
  return fs::is_regular_file(file, ec);
}

}  // namespace

/// The file being expanded: its source, folder and the chain of files that include it.
struct DocumentReader::Context {
  std::shared_ptr<const SourceFile> source;
  fs::path dir;
  std::vector<std::string> identities;
  int depth = 0;
};

std::optional<DynamicWorkCellDocument> DocumentReader::read(std::string_view text,
                                                            const fs::path& file) {
  topDir_ = file.parent_path();
  auto source = std::make_shared<const SourceFile>(SourceFile{displayPathOf(file), {}});
  auto root = parseRoot(text, source, "DynamicWorkcell");
  if (!root) return std::nullopt;
  DynamicWorkCellDocument document;
  std::vector<XmlElement> children = std::move(root->children);
  root->children.clear();
  document.root = std::move(*root);
  expand(children, Context{source, file.parent_path(), {identityOf(file)}, 0}, document.topLevel);
  if (sink_.hasErrors()) return std::nullopt;
  return document;
}

std::optional<XmlElement> DocumentReader::parseRoot(std::string_view text,
                                                    const std::shared_ptr<const SourceFile>& source,
                                                    std::string_view expectedRoot) {
  if (const auto bad = findInvalidCharacter(text)) {
    sink_.error(SourceLocation{source, bad->where.line, bad->where.column},
                "not well-formed XML: " + bad->message);
    return std::nullopt;
  }
  const TagRepairResult repaired = repairClosingTags(text);
  for (const TagRepair& r : repaired.repairs) {
    sink_.warning(SourceLocation{source, r.where.line, r.where.column},
                  "</" + r.written + "> closes <" + r.closes + ">; read as </" + r.closes +
                      ">, as RobWork does");
  }
  if (repaired.unclosed) {
    const auto& [name, where] = *repaired.unclosed;
    sink_.error(SourceLocation{source, where.line, where.column},
                "<" + name + "> is not closed before the end of the file");
    return std::nullopt;
  }
  auto elements = reader_.parse(repaired.text, source, sink_);
  if (!elements) return std::nullopt;
  const std::string expected(expectedRoot);
  if (elements->empty()) {
    sink_.error(SourceLocation{source, 0, 0}, "the file has no <" + expected + "> element");
    return std::nullopt;
  }
  XmlElement& root = elements->front();
  if (root.name != expected) {
    std::string message = "the root element must be <" + expected + ">, found <" + root.name + ">";
    if (root.name == "IncludeData") {
      message +=
          " (a file meant to be included; a dynamic workcell file starts with "
          "<DynamicWorkcell workcell=\"...\">)";
    }
    sink_.error(root.location, message);
    return std::nullopt;
  }
  return std::move(root);
}

void DocumentReader::expand(const std::vector<XmlElement>& elements, const Context& context,
                            std::vector<XmlElement>& out) {
  for (const XmlElement& e : elements) {
    if (e.name == "Include") {
      include(e, context, out);
    } else {
      out.push_back(e);
    }
  }
}

void DocumentReader::include(const XmlElement& element, const Context& context,
                             std::vector<XmlElement>& out) {
  const std::string what = describeElement(element) + ": ";
  if (context.depth + 1 > kMaxIncludeDepth) {
    sink_.error(element.location,
                what + "Includes are nested deeper than " + std::to_string(kMaxIncludeDepth));
    return;
  }
  const std::string file = element.attributeOr("file", "");
  // A redirect applies to the file as RobWork resolves it (the top-level file's folder), or,
  // when that does not exist, to the file found next to the including file.
  const fs::path relative(file);
  const fs::path primary = relative.is_absolute() ? relative : topDir_ / relative;
  std::optional<fs::path> replacement = rw::loaders::redirectedInclude(redirects_, primary);
  std::string redirectNote = " (redirected from \"" + displayPathOf(primary) + "\")";
  std::optional<fs::path> path;
  if (!replacement) {
    path = resolveInclude(element, file, context);
    if (!path) return;
    replacement = rw::loaders::redirectedInclude(redirects_, *path);
    redirectNote = " (redirected from \"" + displayPathOf(*path) + "\")";
  }
  if (replacement) {
    path = *replacement;
  } else {
    redirectNote.clear();
  }
  const std::string identity = identityOf(*path);
  if (std::find(context.identities.begin(), context.identities.end(), identity) !=
      context.identities.end()) {
    sink_.error(element.location, what + "\"" + displayPathOf(*path) + "\" includes itself");
    return;
  }
  if (++filesRead_ > kMaxFilesRead) {
    sink_.error(element.location,
                what + "more than " + std::to_string(kMaxFilesRead) + " files are included");
    return;
  }
  std::string text;
  const std::string problem = readTextFile(*path, text);
  if (!problem.empty()) {
    sink_.error(element.location, what + "cannot read \"" + displayPathOf(*path) + "\"" +
                                      redirectNote + ": " + problem);
    return;
  }
  SourceFile included{displayPathOf(*path), {}};
  included.includedFrom.push_back(context.source->displayPath + ":" +
                                  std::to_string(element.location.line));
  for (const std::string& outer : context.source->includedFrom) {
    included.includedFrom.push_back(outer);
  }
  auto source = std::make_shared<const SourceFile>(std::move(included));
  auto root = parseRoot(text, source, "IncludeData");
  if (!root) return;
  Context inner{source, path->parent_path(), context.identities, context.depth + 1};
  inner.identities.push_back(identity);
  expand(root->children, inner, out);
}

std::optional<fs::path> DocumentReader::resolveInclude(const XmlElement& element,
                                                       const std::string& file,
                                                       const Context& context) {
  const fs::path relative(file);
  if (relative.is_absolute()) return relative;
  const fs::path primary = topDir_ / relative;
  if (isFile(primary)) return primary;
  const fs::path secondary = context.dir / relative;
  const bool differs = secondary.lexically_normal() != primary.lexically_normal();
  if (differs && isFile(secondary)) {
    sink_.warning(element.location,
                  describeElement(element) + ": \"" + displayPathOf(primary) +
                      "\" does not exist (RobWork resolves Include paths against the top-level "
                      "file's folder); using \"" +
                      displayPathOf(secondary) + "\", relative to the including file");
    return secondary;
  }
  if (!differs) return primary;  // reading it reports why it failed
  sink_.error(element.location,
              describeElement(element) + ": cannot read \"" + displayPathOf(primary) +
                  "\": no such file (Include paths are relative to the top-level file's "
                  "folder, as in RobWork; \"" +
                  displayPathOf(secondary) +
                  "\", relative to the including file, does not "
                  "exist either)");
  return std::nullopt;
}

}  // namespace rwsim::loaders::detail
