#include "rw/loaders/detail/preprocess.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <system_error>
#include <utility>

namespace rw::loaders::detail {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxExpandedElements = 250'000;
constexpr std::size_t kMaxFilesRead = 10'000;

// What identifies a file for cycle detection: its canonical path if it can be found.
std::string identityOf(const fs::path& file) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(file, ec);
  if (ec) canonical = fs::absolute(file, ec).lexically_normal();
  return canonical.string();
}

std::size_t totalSize(const std::vector<common::XmlElement>& elements) {
  std::size_t n = 0;
  for (const common::XmlElement& e : elements) n += e.subtreeSize();
  return n;
}

// An Include's file with every `${NAME}` replaced by the environment variable NAME (this
// project's extension: a hand folder can name RobWork's files where they lie, without copying
// them). nullopt after an error: NAME unset or empty, or a `${` without its `}`.
std::optional<std::string> withEnvironment(const common::XmlElement& include,
                                           const std::string& file, common::DiagnosticSink& sink) {
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = file.find("${", at);
    out += file.substr(at, open == std::string::npos ? std::string::npos : open - at);
    if (open == std::string::npos) return out;
    const std::size_t close = file.find('}', open + 2);
    if (close == std::string::npos) {
      sink.error(include.location, include.describe() + ": \"${\" without its \"}\" in the file " +
                                       "name (an environment variable is written ${NAME})");
      return std::nullopt;
    }
    const std::string name = file.substr(open + 2, close - open - 2);
    const char* value = name.empty() ? nullptr : std::getenv(name.c_str());
    if (value == nullptr || *value == '\0') {
      sink.error(include.location,
                 include.describe() + ": the environment variable " +
                     (name.empty() ? std::string("name is empty") : name + " is not set") +
                     " (the file name \"" + file + "\" needs it)");
      return std::nullopt;
    }
    out += value;
    at = close + 1;
  }
}

}  // namespace

std::string displayPathOf(const fs::path& file) { return file.lexically_normal().string(); }

struct Preprocessor::FileScope {
  struct Definition {
    std::vector<common::XmlElement> elements;
    common::SourceLocation location;
  };
  std::shared_ptr<const common::SourceFile> file;
  fs::path dir;
  std::map<std::string, Definition> defines;
  std::vector<std::string> identities;
  std::vector<std::string> displays;
  int depth = 0;
};

std::optional<std::vector<common::XmlElement>> Preprocessor::expandFile(const fs::path& file) {
  std::string text;
  const std::string problem = readTextFile(file, text);
  if (!problem.empty()) {
    auto source = std::make_shared<common::SourceFile>(common::SourceFile{displayPathOf(file), {}});
    sink_.error(common::SourceLocation{source, 0, 0}, "cannot read the file: " + problem);
    return std::nullopt;
  }
  return expandTopLevel(text, file);
}

std::optional<std::vector<common::XmlElement>> Preprocessor::expandText(
    std::string_view text, const fs::path& virtualFile) {
  return expandTopLevel(text, virtualFile);
}

std::optional<std::vector<common::XmlElement>> Preprocessor::expandTopLevel(std::string_view text,
                                                                            const fs::path& file) {
  FileScope scope;
  scope.file = std::make_shared<common::SourceFile>(common::SourceFile{displayPathOf(file), {}});
  scope.dir = fs::path(scope.file->displayPath).parent_path();
  scope.identities.push_back(identityOf(file));
  scope.displays.push_back(scope.file->displayPath);
  auto parsed = reader_.parse(text, scope.file, sink_);
  if (!parsed) return std::nullopt;
  if (!spendBudget(totalSize(*parsed), common::SourceLocation{scope.file, 0, 0}))
    return std::nullopt;
  std::vector<common::XmlElement> expanded = expandList(std::move(*parsed), scope);
  if (sink_.hasErrors()) return std::nullopt;
  return expanded;
}

bool Preprocessor::spendBudget(std::size_t elements, const common::SourceLocation& where) {
  if (overBudget_) return false;
  elementBudgetUsed_ += elements;
  if (elementBudgetUsed_ <= kMaxExpandedElements) return true;
  overBudget_ = true;
  sink_.error(where, "the workcell grows beyond " + std::to_string(kMaxExpandedElements) +
                         " elements when Include and Use are expanded");
  return false;
}

std::vector<common::XmlElement> Preprocessor::expandList(std::vector<common::XmlElement> elements,
                                                         FileScope& scope) {
  std::vector<common::XmlElement> out;
  out.reserve(elements.size());
  for (common::XmlElement& e : elements) {
    if (overBudget_) break;
    if (e.name == "Define") {
      const std::string id = e.attributeOr("id", "");
      std::vector<common::XmlElement> content = expandList(std::move(e.children), scope);
      const auto previous = scope.defines.find(id);
      if (previous != scope.defines.end()) {
        sink_.warning(e.location, e.describe() + " replaces the Define of the same id at line " +
                                      std::to_string(previous->second.location.line));
      }
      scope.defines[id] = FileScope::Definition{std::move(content), e.location};
    } else if (e.name == "Use") {
      expandUse(e, scope, out);
    } else if (e.name == "Include") {
      expandInclude(e, scope, out);
    } else {
      e.children = expandList(std::move(e.children), scope);
      out.push_back(std::move(e));
    }
  }
  return out;
}

void Preprocessor::expandUse(const common::XmlElement& use, FileScope& scope,
                             std::vector<common::XmlElement>& out) {
  const std::string id = use.attributeOr("id", "");
  const auto it = scope.defines.find(id);
  if (it == scope.defines.end()) {
    sink_.error(use.location, use.describe() + ": no <Define id=\"" + id +
                                  "\"> before it in this file (a Define is visible only in its "
                                  "own file, after it)");
    return;
  }
  if (!spendBudget(totalSize(it->second.elements), use.location)) return;
  out.insert(out.end(), it->second.elements.begin(), it->second.elements.end());
}

void Preprocessor::expandInclude(const common::XmlElement& include, FileScope& scope,
                                 std::vector<common::XmlElement>& out) {
  const auto expandedName = withEnvironment(include, include.attributeOr("file", ""), sink_);
  if (!expandedName) return;
  const fs::path name(*expandedName);
  fs::path path = (name.is_absolute() ? name : scope.dir / name).lexically_normal();
  // A redirected Include names the file it replaces in its messages.
  std::string redirectNote;
  if (const auto replacement = redirectedInclude(redirects_, path)) {
    redirectNote = " (redirected from \"" + path.string() + "\")";
    path = replacement->lexically_normal();
  }
  const std::string display = path.string();
  if (scope.depth + 1 > kMaxIncludeDepth) {
    sink_.error(include.location, include.describe() + ": includes are nested deeper than " +
                                      std::to_string(kMaxIncludeDepth) + " levels");
    return;
  }
  const std::string identity = identityOf(path);
  const auto seen = std::find(scope.identities.begin(), scope.identities.end(), identity);
  if (seen != scope.identities.end()) {
    std::string chain;
    for (auto i = static_cast<std::size_t>(seen - scope.identities.begin());
         i < scope.displays.size(); ++i) {
      chain += scope.displays[i] + " -> ";
    }
    sink_.error(include.location, include.describe() + ": include cycle: " + chain + display);
    return;
  }
  if (++filesRead_ > kMaxFilesRead) {
    sink_.error(include.location, include.describe() + ": more than " +
                                      std::to_string(kMaxFilesRead) + " files are included");
    overBudget_ = true;
    return;
  }
  std::string text;
  const std::string problem = readTextFile(path, text);
  if (!problem.empty()) {
    sink_.error(include.location, include.describe() + ": cannot read \"" + display + "\"" +
                                      redirectNote + ": " + problem);
    return;
  }
  auto source = std::make_shared<common::SourceFile>();
  source->displayPath = display;
  source->includedFrom.push_back(scope.file->displayPath + ":" +
                                 std::to_string(include.location.line));
  source->includedFrom.insert(source->includedFrom.end(), scope.file->includedFrom.begin(),
                              scope.file->includedFrom.end());
  auto parsed = reader_.parse(text, source, sink_);
  if (!parsed) return;
  if (parsed->empty()) {
    sink_.warning(include.location, include.describe() + ": the included file holds no elements");
  }
  if (!spendBudget(totalSize(*parsed), include.location)) return;
  FileScope child;
  child.file = source;
  child.dir = path.parent_path();
  child.identities = scope.identities;
  child.identities.push_back(identity);
  child.displays = scope.displays;
  child.displays.push_back(display);
  child.depth = scope.depth + 1;
  std::vector<common::XmlElement> expanded = expandList(std::move(*parsed), child);
  for (common::XmlElement& e : expanded) out.push_back(std::move(e));
}

}  // namespace rw::loaders::detail
