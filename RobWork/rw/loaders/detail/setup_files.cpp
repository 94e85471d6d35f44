#include "rw/loaders/detail/setup_files.hpp"

#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rw/common/xml_attributes.hpp"
#include "rw/loaders/detail/preprocess.hpp"

namespace rw::loaders::detail {

using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;

namespace {

// A default setup larger than this is cut (it only makes collision checking slower).
constexpr std::size_t kMaxDefaultPairs = 1'000'000;

void warnUnknownAttributes(const common::XmlElement& e,
                           std::initializer_list<std::string_view> known,
                           common::DiagnosticSink& sink) {
  for (const common::XmlAttribute& a : e.attributes) {
    bool ok = false;
    for (std::string_view k : known) ok = ok || a.name == k;
    if (!ok) {
      sink.warning(e.location, e.describe() + ": unknown attribute \"" + a.name + "\" is ignored");
    }
  }
}

// Reads a setup file and returns its root element if it is `rootName`.
std::optional<common::XmlElement> readSetupRoot(const SetupRef& ref, const char* rootName,
                                                common::XmlReader& reader,
                                                common::DiagnosticSink& sink) {
  std::string text;
  const std::string problem = readTextFile(ref.path, text);
  if (!problem.empty()) {
    sink.error(ref.origin.location,
               ref.origin.element + ": cannot read \"" + ref.path + "\": " + problem);
    return std::nullopt;
  }
  auto file = std::make_shared<common::SourceFile>();
  file->displayPath = ref.path;
  const common::SourceLocation& at = ref.origin.location;
  if (at.file) {
    file->includedFrom.push_back(at.file->displayPath + ":" + std::to_string(at.line));
    file->includedFrom.insert(file->includedFrom.end(), at.file->includedFrom.begin(),
                              at.file->includedFrom.end());
  }
  auto elements = reader.parse(text, file, sink);
  if (!elements) return std::nullopt;
  if (elements->size() != 1 || elements->front().name != rootName) {
    const common::SourceLocation where = elements->empty()
                                             ? common::SourceLocation{file, 1, 0}
                                             : (*elements)[elements->size() > 1 ? 1 : 0].location;
    sink.error(where,
               std::string("a ") + rootName + " file holds exactly one <" + rootName + "> element");
    return std::nullopt;
  }
  return std::move(elements->front());
}

void warnUnknownFrame(const common::XmlElement& e, const std::string& name, const FrameTree& frames,
                      common::DiagnosticSink& sink) {
  if (!frames.find(name).valid()) {
    sink.warning(e.location,
                 e.describe() + ": there is no frame \"" + name + "\"; this entry has no effect");
  }
}

void readExclude(const common::XmlElement& exclude, const std::string& prefix,
                 const FrameTree& frames, rw::models::CollisionSetup& setup,
                 common::DiagnosticSink& sink) {
  for (const common::XmlElement& pair : exclude.children) {
    if (pair.name != "FramePair") {
      sink.error(pair.location, "unknown element <" + pair.name +
                                    "> in <Exclude>; expected "
                                    "<FramePair first second/>");
      continue;
    }
    warnUnknownAttributes(pair, {"first", "second"}, sink);
    const std::string* first = common::XmlValueReader(sink).required(pair, "first");
    const std::string* second = common::XmlValueReader(sink).required(pair, "second");
    if (first == nullptr || second == nullptr) continue;
    setup.excludePairs.emplace_back(prefix + *first, prefix + *second);
    warnUnknownFrame(pair, prefix + *first, frames, sink);
    warnUnknownFrame(pair, prefix + *second, frames, sink);
  }
}

// Old format: <CollisionSetup> with Exclude/FramePair, Volatile and ExcludeStaticPairs.
void readCollisionSetup(const SetupRef& ref, common::XmlReader& reader, const FrameTree& frames,
                        rw::models::CollisionSetup& setup, common::DiagnosticSink& sink) {
  const auto root = readSetupRoot(ref, "CollisionSetup", reader, sink);
  if (!root) return;
  for (const common::XmlElement& child : root->children) {
    if (child.name == "Exclude") {
      readExclude(child, ref.prefix, frames, setup, sink);
    } else if (child.name == "Volatile") {
      const std::string name = ref.prefix + std::string(common::trimXmlSpace(child.text));
      setup.volatileFrames.push_back(name);
      warnUnknownFrame(child, name, frames, sink);
    } else if (child.name == "ExcludeStaticPairs") {
      setup.excludeStaticPairs = true;
    } else {
      sink.error(child.location, "unknown element <" + child.name +
                                     "> in <CollisionSetup>; expected Exclude, Volatile or "
                                     "ExcludeStaticPairs");
    }
  }
}

// A pattern taken in a device's scope: the prefix goes in front; a REGEX pattern gets it
// escaped, right after the REGEX marker.
std::string scopedPattern(const std::string& prefix, const std::string& pattern) {
  if (prefix.empty()) return pattern;
  if (pattern.rfind("REGEX", 0) != 0) return prefix + pattern;
  std::string escaped;
  for (char c : prefix) {
    if (std::string_view(".[]{}()\\*+?^$|").find(c) != std::string_view::npos) escaped += '\\';
    escaped += c;
  }
  return "REGEX" + escaped + pattern.substr(5);
}

// New format: <ProximitySetup> with Include/Exclude PatternA PatternB rules.
void readProximitySetup(const SetupRef& ref, common::XmlReader& reader,
                        std::vector<rw::models::ProximityRule>& rules,
                        common::DiagnosticSink& sink) {
  const auto root = readSetupRoot(ref, "ProximitySetup", reader, sink);
  if (!root) return;
  warnUnknownAttributes(*root, {"UseIncludeAll", "UseExcludeStaticPairs"}, sink);
  if (root->has("UseIncludeAll") || root->has("UseExcludeStaticPairs")) {
    sink.warning(root->location, root->describe() +
                                     ": UseIncludeAll and UseExcludeStaticPairs of a "
                                     "ProximitySetup file are not used by the workcell (RobWork "
                                     "merges only the rules)");
  }
  for (const common::XmlElement& child : root->children) {
    if (child.name != "Include" && child.name != "Exclude") {
      sink.error(child.location, "unknown element <" + child.name +
                                     "> in <ProximitySetup>; expected Include or Exclude");
      continue;
    }
    warnUnknownAttributes(child, {"PatternA", "PatternB"}, sink);
    const std::string* a = common::XmlValueReader(sink).required(child, "PatternA");
    const std::string* b = common::XmlValueReader(sink).required(child, "PatternB");
    if (a == nullptr || b == nullptr) continue;
    rules.push_back(
        {scopedPattern(ref.prefix, *a), scopedPattern(ref.prefix, *b), child.name == "Include"});
  }
}

}  // namespace

rw::models::CollisionSetup defaultCollisionSetup(const FrameTree& frames) {
  // Frames in the order RobWork's stack walk discovers them (a parent before its children).
  std::vector<FrameId> discovered;
  std::vector<FrameId> stack{FrameTree::kWorld};
  while (!stack.empty()) {
    const FrameId f = stack.back();
    stack.pop_back();
    for (const FrameId c : frames.children(f)) {
      if (frames.frame(c).isDaf()) continue;
      stack.push_back(c);
      discovered.push_back(c);
    }
  }
  rw::models::CollisionSetup setup;
  for (const FrameId b : discovered) {
    const FrameId p = frames.frame(b).parent();
    if (p == FrameTree::kWorld) continue;
    for (const FrameId a : frames.children(frames.frame(p).parent())) {
      if (frames.frame(a).isDaf()) continue;
      if (setup.excludePairs.size() == kMaxDefaultPairs) return setup;
      setup.excludePairs.emplace_back(frames.frame(b).name(), frames.frame(a).name());
    }
  }
  return setup;
}

void buildSetups(rw::models::WorkCell& wc, const WorkCellDesc& desc, common::XmlReader& reader,
                 common::DiagnosticSink& sink) {
  rw::models::CollisionSetup collision;
  for (const SetupRef& ref : desc.collisionSetups) {
    readCollisionSetup(ref, reader, wc.frames(), collision, sink);
  }
  if (desc.collisionSetups.empty() && desc.proximitySetups.empty()) {
    collision = defaultCollisionSetup(wc.frames());
  }
  rw::models::ProximitySetup proximity;
  proximity.useIncludeAll = true;
  proximity.useExcludeStaticPairs = collision.excludeStaticPairs;
  for (const auto& [a, b] : collision.excludePairs) proximity.rules.push_back({a, b, false});
  for (const SetupRef& ref : desc.proximitySetups) {
    readProximitySetup(ref, reader, proximity.rules, sink);
  }
  wc.collisionSetup() = std::move(collision);
  wc.proximitySetup() = std::move(proximity);
}

}  // namespace rw::loaders::detail
