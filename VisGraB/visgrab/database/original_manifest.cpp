#include "visgrab/database/original_manifest.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <system_error>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"

namespace visgrab::database {

namespace fs = std::filesystem;

namespace {

std::string_view localName(std::string_view name) {
  const auto colon = name.rfind(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

std::string trimmed(std::string_view text) { return std::string(rw::common::trimXmlSpace(text)); }

const rw::common::XmlElement* firstChild(const rw::common::XmlElement& e, std::string_view name) {
  for (const rw::common::XmlElement& c : e.children) {
    if (localName(c.name) == name) return &c;
  }
  return nullptr;
}

// How messages name an element of the manifest: its name only.
std::string bareName(const rw::common::XmlElement& e) { return "<" + e.name + ">"; }

const std::string* attribute(const rw::common::XmlElement& e, std::string_view name) {
  for (const rw::common::XmlAttribute& a : e.attributes) {
    if (localName(a.name) == name) return &a.value;
  }
  return nullptr;
}

// Boost's XML reader (used by the original) accepts undeclared namespace prefixes; Xerces does
// not. Declares every prefix that the text uses but never declares, on the root element's start
// tag (only columns on that line move).
std::string declarePrefixes(std::string_view text) {
  static const std::regex kPrefixed(R"([<\s/]([A-Za-z_][A-Za-z0-9_.\-]*):[A-Za-z_])");
  std::set<std::string> prefixes;
  const std::string owned(text);
  for (auto it = std::sregex_iterator(owned.begin(), owned.end(), kPrefixed);
       it != std::sregex_iterator(); ++it) {
    std::string prefix = (*it)[1].str();
    std::string lower = prefix;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower.rfind("xml", 0) == 0) continue;
    if (owned.find("xmlns:" + prefix + "=") != std::string::npos) continue;
    prefixes.insert(std::move(prefix));
  }
  if (prefixes.empty()) return owned;
  // The root's start tag: the first '<' followed by a name character.
  std::size_t at = 0;
  while ((at = owned.find('<', at)) != std::string::npos) {
    if (at + 1 < owned.size() &&
        (std::isalpha(static_cast<unsigned char>(owned[at + 1])) != 0 || owned[at + 1] == '_')) {
      break;
    }
    ++at;
  }
  if (at == std::string::npos) return owned;
  std::size_t end = at + 1;
  while (end < owned.size() &&
         std::string_view(" \t\r\n/>").find(owned[end]) == std::string::npos) {
    ++end;
  }
  std::string declarations;
  for (const std::string& p : prefixes) {
    declarations += " xmlns:" + p + "=\"urn:visgrab:undeclared-prefix:" + p + "\"";
  }
  return owned.substr(0, end) + declarations + owned.substr(end);
}

class ManifestParser {
 public:
  ManifestParser(rw::common::DiagnosticSink& sink, OriginalManifest& out)
      : sink_(sink), out_(out) {}

  void parse(const std::vector<rw::common::XmlElement>& top,
             const rw::common::SourceLocation& whole) {
    if (top.empty() || localName(top[0].name) != "visgrab") {
      sink_.error(top.empty() ? whole : top[0].location,
                  top.empty() ? std::string("no <visgrab> element: not a VisGraB manifest")
                              : "the root element is <" + top[0].name +
                                    ">; a VisGraB manifest starts with <visgrab>");
      return;
    }
    const rw::common::XmlElement* benchmark = nullptr;
    for (const rw::common::XmlElement& c : top[0].children) {
      if (localName(c.name) != "benchmark") {
        sink_.warning(c.location, "<" + c.name + "> ignored (not part of a VisGraB manifest)");
      } else if (benchmark == nullptr) {
        benchmark = &c;
      } else {
        sink_.warning(c.location, "second <benchmark> ignored (only the first is used)");
      }
    }
    if (benchmark == nullptr) {
      sink_.error(top[0].location, "<visgrab> has no <benchmark> element");
      return;
    }
    const std::string* type = attribute(*benchmark, "type");
    if (type == nullptr) {
      rw::common::XmlValueReader(sink_, bareName).required(*benchmark, "type");
      return;
    }
    if (localName(trimmed(*type)) != "GraspUnknownObject") {
      sink_.error(benchmark->location, "<benchmark>: unknown benchmark type \"" + *type +
                                           "\" (expected GraspUnknownObject)");
      return;
    }
    std::map<std::string, int> lineOf;
    for (const rw::common::XmlElement& c : benchmark->children) {
      if (localName(c.name) != "scene") {
        sink_.warning(c.location, "<" + c.name + "> in <benchmark> ignored");
        continue;
      }
      OriginalScene scene;
      if (!parseScene(c, scene)) continue;
      const auto [it, inserted] = lineOf.emplace(scene.id, scene.line);
      if (!inserted) {
        sink_.warning(c.location, "duplicate scene id \"" + scene.id + "\" (also at line " +
                                      std::to_string(it->second) + "); this later one is used");
        it->second = scene.line;
      }
      out_.scenes.push_back(std::move(scene));
    }
  }

 private:
  // The trimmed text of the first child `group`/`name` of `scene`; reports a missing element.
  std::optional<std::string> text(const rw::common::XmlElement& scene, std::string_view group,
                                  std::string_view name, bool required = true) {
    const rw::common::XmlElement* g = firstChild(scene, group);
    const rw::common::XmlElement* e = g != nullptr ? firstChild(*g, name) : nullptr;
    if (e == nullptr) {
      if (required) {
        sink_.error(g != nullptr ? g->location : scene.location, scene.describe() + ": missing <" +
                                                                     std::string(group) + ">/<" +
                                                                     std::string(name) + ">");
      }
      return std::nullopt;
    }
    return trimmed(e->text);
  }

  fs::path resolve(const std::string& path) const {
    if (path.empty()) return {};
    const fs::path p(path);
    return p.is_absolute() ? p : out_.directory / p;
  }

  void warnUnknown(const rw::common::XmlElement& e, std::initializer_list<std::string_view> known) {
    for (const rw::common::XmlElement& c : e.children) {
      if (std::find(known.begin(), known.end(), localName(c.name)) == known.end()) {
        sink_.warning(c.location, "<" + c.name + "> in <" + e.name + "> ignored");
      }
    }
  }

  bool parseScene(const rw::common::XmlElement& e, OriginalScene& scene) {
    scene.line = e.location.line;
    const std::string* id = attribute(e, "id");
    if (id == nullptr) {
      rw::common::XmlValueReader(sink_, bareName).required(e, "id");
      return false;
    }
    scene.id = trimmed(*id);
    warnUnknown(e, {"info", "input", "simulator"});
    for (const auto* group : {"info", "input", "simulator"}) {
      if (const rw::common::XmlElement* g = firstChild(e, group)) {
        if (std::string_view(group) == "info") {
          warnUnknown(*g,
                      {"sceneLocator", "sceneSet", "sceneSetID", "textureCondition", "sceneID"});
        } else if (std::string_view(group) == "input") {
          warnUnknown(*g, {"leftImg", "rightImg", "disp", "pointCloud"});
        } else {
          warnUnknown(*g, {"wc", "dwc", "collision"});
        }
      }
    }
    const std::size_t errorsBefore = sink_.errorCount();
    const auto get = [&](std::string_view group, std::string_view name) {
      return text(e, group, name).value_or("");
    };
    scene.sceneLocator = get("info", "sceneLocator");
    scene.sceneSet = get("info", "sceneSet");
    scene.sceneSetId = get("info", "sceneSetID");
    scene.textureCondition = get("info", "textureCondition");
    scene.leftImage = resolve(get("input", "leftImg"));
    scene.rightImage = resolve(get("input", "rightImg"));
    scene.disparity = resolve(get("input", "disp"));
    scene.pointCloud = resolve(get("input", "pointCloud"));
    scene.workcell = resolve(get("simulator", "wc"));
    scene.dynamicWorkcell = resolve(get("simulator", "dwc"));
    scene.collision = resolve(text(e, "simulator", "collision", false).value_or(""));
    return sink_.errorCount() == errorsBefore;
  }

  rw::common::DiagnosticSink& sink_;
  OriginalManifest& out_;
};

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::vector<std::string> words(std::string_view text) {
  std::vector<std::string> out;
  std::string current;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0) {
      current += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!current.empty()) {
      out.push_back(std::move(current));
      current.clear();
    }
  }
  if (!current.empty()) out.push_back(std::move(current));
  return out;
}

// An original folder id or one of our ids, possibly at the end of a longer path.
std::optional<SceneConditions> fromPath(std::string_view text) {
  std::string path(text);
  std::replace(path.begin(), path.end(), '\\', '/');
  while (!path.empty() && path.back() == '/') path.pop_back();
  std::size_t start = 0;
  while (true) {
    const std::string_view tail = std::string_view(path).substr(start);
    if (auto c = parseOriginalId(tail)) return c;
    if (auto c = parseSceneId(tail)) return c;
    const auto slash = path.find('/', start);
    if (slash == std::string::npos) return std::nullopt;
    start = slash + 1;
  }
}

std::optional<Texture> textureOf(std::string_view condition) {
  const std::string t = lower(rw::common::trimXmlSpace(condition));
  if (t == "textured" || t == "cluttered") return Texture::kTextured;
  if (t == "non-textured" || t == "nontextured" || t == "non_textured" || t == "plain" ||
      t == "untextured") {
    return Texture::kPlain;
  }
  return std::nullopt;
}

}  // namespace

const OriginalScene* OriginalManifest::find(std::string_view id) const {
  for (auto it = scenes.rbegin(); it != scenes.rend(); ++it) {
    if (it->id == id) return &*it;
  }
  return nullptr;
}

OriginalManifest parseOriginalManifest(std::string_view text, const fs::path& file) {
  rw::common::DiagnosticSink sink;
  auto source =
      std::make_shared<const rw::common::SourceFile>(rw::common::SourceFile{file.string(), {}});
  const rw::common::SourceLocation whole{source, 0, 0};
  OriginalManifest manifest;
  std::error_code ec;
  const fs::path absolute = fs::absolute(file, ec);
  manifest.directory = (ec ? file : absolute).parent_path();
  try {
    rw::common::XmlReader reader(rw::common::XmlReaderOptions{});
    const auto top = reader.parse(declarePrefixes(text), source, sink);
    if (top && !sink.hasErrors()) ManifestParser(sink, manifest).parse(*top, whole);
  } catch (const std::exception& e) {
    sink.error(whole, std::string("internal error while reading the manifest: ") + e.what());
  }
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  manifest.warnings = sink.take();
  return manifest;
}

OriginalManifest readOriginalManifest(const fs::path& file) {
  std::string text;
  const std::string why = rw::common::readTextFile(file, text);
  if (!why.empty()) {
    throw rw::common::LoadError({rw::common::Diagnostic{rw::common::Diagnostic::Severity::kError,
                                                        file.string(),
                                                        0,
                                                        0,
                                                        "cannot read the VisGraB manifest: " + why,
                                                        {}}});
  }
  return parseOriginalManifest(text, file);
}

std::optional<SceneConditions> deriveConditions(const OriginalScene& scene) {
  const auto texture = textureOf(scene.textureCondition);
  const std::string set = lower(rw::common::trimXmlSpace(scene.sceneSet));
  const auto agrees = [&](const SceneConditions& c) {
    if (texture && *texture != c.texture) return false;
    if (set == "single" && c.kind != SceneKind::kSingle) return false;
    if (set == "double" && c.kind != SceneKind::kDouble) return false;
    return true;
  };
  for (const std::string* text : {&scene.sceneLocator, &scene.id}) {
    if (auto c = fromPath(*text)) return agrees(*c) ? c : std::nullopt;
  }
  if (!texture) return std::nullopt;
  // Words: object names and the last number 1..8 (also "img03"), locator first.
  std::vector<int> objects;
  std::optional<int> pose;
  for (const std::string* text : {&scene.sceneLocator, &scene.id}) {
    std::vector<int> found;
    std::optional<int> number;
    for (std::string w : words(*text)) {
      if (const auto id = objectIdByName(w)) {
        if (std::find(found.begin(), found.end(), *id) == found.end()) found.push_back(*id);
        continue;
      }
      if (w.rfind("img", 0) == 0) w = w.substr(3);
      if (!w.empty() && w.size() <= 2 &&
          std::all_of(w.begin(), w.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        const int value = std::stoi(w);
        if (value >= 1 && value <= kPosesPerSubject) number = value;
      }
    }
    if (objects.empty() && !found.empty()) objects = found;
    if (!pose && number) pose = number;
  }
  if (!pose) return std::nullopt;
  SceneConditions c;
  if (objects.size() == 1) {
    c = SceneConditions::single(*texture, objects[0], *pose);
  } else if (objects.size() == 2) {
    const auto pair = pairOfObjects(objects[0], objects[1]);
    if (!pair) return std::nullopt;
    c = SceneConditions::pairScene(*texture, pair->letter, *pose);
  } else {
    return std::nullopt;
  }
  return agrees(c) ? std::optional(c) : std::nullopt;
}

}  // namespace visgrab::database
