#include "rw/loaders/detail/wc_parser.hpp"

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "rw/common/strings.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/detail/wc_elements.hpp"

namespace rw::loaders::detail {

using rw::kinematics::FrameType;

namespace {

const std::string kWorld(rw::kinematics::FrameTree::kWorldName);

// Children each context accepts, for "expected one of" in messages.
constexpr const char* kWorkCellChildren =
    "SerialDevice, TreeDevice, ParallelDevice, Frame, Drawable, CollisionModel, CollisionSetup, "
    "ProximitySetup, "
    "Property, Calibration, Camera";
constexpr const char* kDeviceChildren =
    "Frame, Joint, DHJoint, SerialChain, Drawable, CollisionModel, PosLimit, VelLimit, AccLimit, "
    "Property, CollisionSetup, ProximitySetup, Q";
constexpr const char* kParallelChildren =
    "Frame, Joint, DHJoint, SerialChain, Drawable, CollisionModel, PosLimit, VelLimit, AccLimit, "
    "Property, CollisionSetup, ProximitySetup, Junction, Q";
constexpr const char* kChainChildren =
    "Frame, Joint, DHJoint, SerialChain, Drawable, CollisionModel, PosLimit, VelLimit, AccLimit, "
    "Property, CollisionSetup, ProximitySetup";
constexpr const char* kFrameChildren = "RPY, Pos, Transform, Property, Drawable, CollisionModel";
constexpr const char* kJointChildren =
    "RPY, Pos, Transform, PosLimit, VelLimit, AccLimit, Depend, Property, Drawable, "
    "CollisionModel";
constexpr const char* kDhJointChildren =
    "PosLimit, VelLimit, AccLimit, Depend, Property, Drawable, CollisionModel";
constexpr const char* kModelChildren =
    "RPY, Pos, Transform, RGB, Box, Sphere, Cylinder, Tube, Cone, Plane, Custom, Polytope";

bool isLimit(const std::string& name) {
  return name == "PosLimit" || name == "VelLimit" || name == "AccLimit";
}

bool isModel(const std::string& name) { return name == "Drawable" || name == "CollisionModel"; }

bool isDevice(const std::string& name) {
  return name == "SerialDevice" || name == "TreeDevice" || name == "ParallelDevice";
}

// Walks the expanded element tree and fills a WorkCellDesc.
class DescriptionParser {
 public:
  explicit DescriptionParser(common::DiagnosticSink& sink) : sink_(sink) {}

  std::optional<WorkCellDesc> run(const std::vector<common::XmlElement>& topLevel,
                                  const common::SourceLocation& file);

 private:
  struct DeviceState {
    int index = -1;
    bool tree = false;
    std::string lastFrame;
    int frameElements = 0;
  };

  void notAllowed(const common::XmlElement& child, const common::XmlElement& parent,
                  const char* expected);
  void unsupportedDevice(const common::XmlElement& element);
  void parseWorkCell(const common::XmlElement& element);
  void parseDevice(const common::XmlElement& element);
  void parseDeviceBody(const common::XmlElement& element, bool isChain);
  void parseFrame(const common::XmlElement& element);
  bool parseFrameChild(const common::XmlElement& child, const common::XmlElement& element,
                       FrameDesc& frame, TransformReader& transform);
  void attach(const common::XmlElement& element, FrameDesc& frame);
  bool readFrameAttributes(const common::XmlElement& element, FrameDesc& frame);
  bool readColor(const common::XmlElement& model, const common::XmlElement& rgb, ModelDesc& desc);
  void parseModel(const common::XmlElement& element, const std::string& ownerFrame);
  void parseDeviceLimit(const common::XmlElement& element);
  void parseJunction(const common::XmlElement& element);
  void addSetup(const common::XmlElement& element);
  std::string scoped(const std::string& name) const;
  std::string scopePrefix() const;

  common::DiagnosticSink& sink_;
  WorkCellDesc desc_;
  std::vector<std::string> scope_;
  std::optional<DeviceState> device_;
  std::string lastWorkCellFrame_;
  bool seenWorkCellFrame_ = false;
  std::map<std::string, common::SourceLocation> deviceNames_;
};

std::string DescriptionParser::scopePrefix() const {
  std::string prefix;
  for (const std::string& s : scope_) prefix += s + ".";
  return prefix;
}

std::string DescriptionParser::scoped(const std::string& name) const {
  return scopePrefix() + name;
}

void DescriptionParser::notAllowed(const common::XmlElement& child,
                                   const common::XmlElement& parent, const char* expected) {
  std::vector<std::string> names;
  for (const std::string_view name : common::split(expected, ',')) {
    names.emplace_back(name.substr(name.find_first_not_of(' ')));
  }
  const std::string_view meant = common::closestMatch(child.name, names);
  sink_.error(child.location,
              "<" + child.name + "> is not allowed in " + parent.describe() +
                  (meant.empty() ? std::string() : "; did you mean <" + std::string(meant) + ">?") +
                  "; expected one of: " + expected);
}

void DescriptionParser::unsupportedDevice(const common::XmlElement& element) {
  sink_.error(element.location, element.describe() + ": <" + element.name +
                                    "> is not supported by this project (SerialDevice, "
                                    "TreeDevice and ParallelDevice are)");
}

std::optional<WorkCellDesc> DescriptionParser::run(const std::vector<common::XmlElement>& topLevel,
                                                   const common::SourceLocation& file) {
  if (topLevel.empty()) {
    sink_.error(common::SourceLocation{file.file, 1, 0},
                "the file holds no element; expected <WorkCell> or a device as its root");
    return std::nullopt;
  }
  if (topLevel.size() > 1) {
    sink_.error(topLevel[1].location, "<" + topLevel[1].name + "> after the root element " +
                                          topLevel[0].describe() +
                                          ": a workcell file has one root element");
    return std::nullopt;
  }
  const common::XmlElement& root = topLevel.front();
  if (root.name == "WorkCell") {
    desc_.name = root.attributeOr("name", "");
    parseWorkCell(root);
  } else if (isDevice(root.name)) {
    parseDevice(root);
  } else if (root.name == "MobileDevice") {
    unsupportedDevice(root);
  } else {
    sink_.error(root.location, "<" + root.name +
                                   "> cannot be the root element; expected <WorkCell>, "
                                   "<SerialDevice>, <TreeDevice> or <ParallelDevice>");
  }
  if (sink_.hasErrors()) return std::nullopt;
  return std::move(desc_);
}

void DescriptionParser::parseWorkCell(const common::XmlElement& element) {
  for (const common::XmlElement& child : element.children) {
    const std::string& n = child.name;
    if (isDevice(n)) {
      parseDevice(child);
    } else if (n == "MobileDevice") {
      unsupportedDevice(child);
    } else if (n == "Frame") {
      parseFrame(child);
    } else if (isModel(n)) {
      parseModel(child, "");
    } else if (n == "CollisionSetup" || n == "ProximitySetup") {
      addSetup(child);
    } else if (n == "Property") {
      if (child.has("refframe")) {
        sink_.warning(child.location, child.describe() +
                                          ": refframe is ignored; a workcell-level property "
                                          "belongs to the workcell");
      }
      if (auto p = readProperty(child, sink_)) desc_.properties.push_back(std::move(*p));
    } else if (n == "Calibration" || n == "Camera") {
      sink_.warning(child.location, child.describe() + " is read and ignored, as RobWork does");
    } else {
      notAllowed(child, element, kWorkCellChildren);
    }
  }
}

void DescriptionParser::parseDevice(const common::XmlElement& element) {
  DeviceDesc device;
  device.origin = originOf(element);
  device.name = element.attributeOr("name", "");
  device.tree = element.name == "TreeDevice";
  device.parallel = element.name == "ParallelDevice";
  const auto [it, fresh] = deviceNames_.emplace(device.name, element.location);
  if (!fresh) {
    sink_.error(element.location,
                element.describe() + ": a device named \"" + device.name +
                    "\" is already declared at line " + std::to_string(it->second.line) +
                    (it->second.file && element.location.file &&
                             it->second.file->displayPath != element.location.file->displayPath
                         ? " of " + it->second.file->displayPath
                         : std::string()));
    return;
  }
  desc_.devices.push_back(std::move(device));
  // A ParallelDevice attaches its frames as a TreeDevice does (RobWork's AddFrameToDevice).
  device_ = DeviceState{static_cast<int>(desc_.devices.size()) - 1,
                        element.name == "TreeDevice" || element.name == "ParallelDevice", "", 0};
  scope_.push_back(desc_.devices.back().name);
  parseDeviceBody(element, false);
  scope_.pop_back();
  if (device_->frameElements == 0) {
    sink_.error(element.location, element.describe() + ": the device has no frames");
  }
  device_.reset();
}

void DescriptionParser::parseDeviceBody(const common::XmlElement& element, bool isChain) {
  DeviceDesc& device = desc_.devices[static_cast<std::size_t>(device_->index)];
  for (const common::XmlElement& child : element.children) {
    const std::string& n = child.name;
    if (n == "Frame" || n == "Joint" || n == "DHJoint") {
      parseFrame(child);
    } else if (n == "SerialChain") {
      scope_.push_back(child.attributeOr("name", ""));
      parseDeviceBody(child, true);
      scope_.pop_back();
    } else if (isModel(n)) {
      parseModel(child, "");
    } else if (isLimit(n)) {
      parseDeviceLimit(child);
    } else if (n == "Property") {
      if (child.has("refframe")) {
        sink_.warning(child.location, child.describe() +
                                          ": refframe is ignored; a device-level property "
                                          "belongs to the device, as in RobWork");
      }
      if (auto p = readProperty(child, sink_)) device.properties.push_back(std::move(*p));
    } else if (n == "CollisionSetup" || n == "ProximitySetup") {
      addSetup(child);
    } else if (n == "Q" && !isChain) {
      if (auto q = readQ(child, sink_)) device.configurations.push_back(std::move(*q));
    } else if (n == "Junction" && !isChain && device.parallel) {
      parseJunction(child);
    } else {
      notAllowed(
          child, element,
          isChain ? kChainChildren : (device.parallel ? kParallelChildren : kDeviceChildren));
    }
  }
}

void DescriptionParser::parseDeviceLimit(const common::XmlElement& element) {
  auto limit = readLimit(element, "", sink_);
  if (!limit) return;
  const std::string* refjoint = element.attribute("refjoint");
  if (refjoint == nullptr || refjoint->empty()) {
    sink_.warning(element.location, element.describe() +
                                        ": a device-level limit without refjoint applies to no "
                                        "joint; it is ignored, as in RobWork");
    return;
  }
  limit->joint = scoped(*refjoint);
  desc_.devices[static_cast<std::size_t>(device_->index)].limits.push_back(std::move(*limit));
}

// <Junction><Chains>A B</Chains><Chains>C</Chains></Junction>: each Chains is one leg made of
// the named SerialChains; the names are resolved by the builder.
void DescriptionParser::parseJunction(const common::XmlElement& element) {
  JunctionDesc junction;
  junction.origin = originOf(element);
  bool ok = true;
  for (const common::XmlElement& child : element.children) {
    if (child.name != "Chains") {
      notAllowed(child, element, "Chains");
      ok = false;
      continue;
    }
    ChainsDesc leg;
    leg.origin = originOf(child);
    std::string word;
    for (const char c : child.text + " ") {
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r') {
        word += c;
      } else if (!word.empty()) {
        leg.names.push_back(std::move(word));
        word.clear();
      }
    }
    if (leg.names.empty()) {
      sink_.error(child.location, child.describe() +
                                      ": names no SerialChain; expected the names of the "
                                      "chains that make one leg, separated by spaces");
      ok = false;
      continue;
    }
    junction.legs.push_back(std::move(leg));
  }
  if (ok && junction.legs.size() < 2) {
    sink_.error(element.location, element.describe() +
                                      ": a junction joins at least two legs (<Chains> "
                                      "elements), got " +
                                      std::to_string(junction.legs.size()));
    return;
  }
  if (ok) desc_.devices[static_cast<std::size_t>(device_->index)].junctions.push_back(junction);
}

void DescriptionParser::addSetup(const common::XmlElement& element) {
  SetupRef ref;
  ref.origin = originOf(element);
  ref.file = element.attributeOr("file", "");
  const std::filesystem::path dir =
      std::filesystem::path(element.location.file ? element.location.file->displayPath : "")
          .parent_path();
  const std::filesystem::path name(ref.file);
  ref.path = (name.is_absolute() ? name : dir / name).lexically_normal().string();
  ref.prefix = scopePrefix();
  if (element.name == "CollisionSetup") {
    desc_.collisionSetups.push_back(std::move(ref));
  } else {
    desc_.proximitySetups.push_back(std::move(ref));
  }
}

void DescriptionParser::parseModel(const common::XmlElement& element,
                                   const std::string& ownerFrame) {
  ModelDesc model;
  model.origin = originOf(element);
  model.name = element.attributeOr("name", "");
  model.visual = element.name == "Drawable";
  model.collision =
      element.name == "CollisionModel" || element.attributeOr("colmodel", "Enabled") != "Disabled";
  const std::string* refframe = element.attribute("refframe");
  if (!ownerFrame.empty()) {
    model.frame = ownerFrame;
    if (refframe != nullptr && scoped(*refframe) != ownerFrame) {
      sink_.warning(element.location, element.describe() + ": refframe \"" + *refframe +
                                          "\" is ignored; the model belongs to the enclosing "
                                          "frame \"" +
                                          ownerFrame + "\"");
    }
  } else if (refframe == nullptr || refframe->empty()) {
    if (device_) {
      sink_.warning(element.location, element.describe() +
                                          ": a device-level model without refframe belongs to "
                                          "no frame; it is ignored, as in RobWork");
    } else {
      sink_.error(element.location, element.describe() +
                                        ": a workcell-level model needs a refframe naming its "
                                        "frame");
    }
    return;
  } else {
    model.frame = scoped(*refframe);
  }
  TransformReader transform;
  bool ok = true;
  for (const common::XmlElement& child : element.children) {
    if (transform.take(element, child, sink_)) continue;
    if (child.name == "RGB") {
      if (!readColor(element, child, model)) ok = false;
      continue;
    }
    if (isGeometryElement(child.name)) {
      auto g = readGeometry(child, sink_);
      if (g) {
        model.geometries.push_back(std::move(*g));
      } else {
        ok = false;
      }
      continue;
    }
    notAllowed(child, element, kModelChildren);
  }
  const auto X = transform.finish(element, sink_);
  if (!X || !ok) return;
  model.transform = *X;
  desc_.models.push_back(std::move(model));
}

bool DescriptionParser::readColor(const common::XmlElement& model, const common::XmlElement& rgb,
                                  ModelDesc& desc) {
  if (desc.color) {
    sink_.error(rgb.location, model.describe() + ": more than one <RGB>");
    return false;
  }
  const auto values = common::XmlValueReader(sink_).textNumbers(rgb);
  if (!values) return false;
  if (values->size() != 3 && values->size() != 4) {
    sink_.error(rgb.location, rgb.describe() +
                                  ": expected 3 numbers (red green blue) or 4 (and "
                                  "alpha), got " +
                                  std::to_string(values->size()));
    return false;
  }
  for (const double v : *values) {
    if (!(v >= 0.0 && v <= 1.0)) {
      sink_.error(rgb.location, rgb.describe() + ": colour components must be in [0, 1]");
      return false;
    }
  }
  if (model.name == "CollisionModel") {
    sink_.warning(rgb.location, rgb.describe() +
                                    ": a CollisionModel is not drawn; the colour "
                                    "is ignored");
    return true;
  }
  if (values->size() == 4 && (*values)[3] < 1.0) {
    sink_.warning(rgb.location, rgb.describe() + ": transparency (alpha " +
                                    std::to_string((*values)[3]) + ") is not drawn");
  }
  desc.color =
      std::array<float, 3>{static_cast<float>((*values)[0]), static_cast<float>((*values)[1]),
                           static_cast<float>((*values)[2])};
  return true;
}

bool DescriptionParser::readFrameAttributes(const common::XmlElement& element, FrameDesc& frame) {
  bool ok = true;
  if (element.name == "DHJoint") {
    if (const auto dh = readDhJoint(element, sink_)) {
      frame.type = dh->type;
      frame.transform = dh->transform;
    } else {
      ok = false;
    }
  } else {
    const std::string fallback = element.name == "Frame" ? "Fixed" : "";
    if (const auto kind = readFrameType(element, element.attributeOr("type", fallback), sink_)) {
      frame.type = kind->type;
      frame.endEffector = kind->endEffector;
    } else {
      ok = false;
    }
  }
  const common::XmlValueReader read(sink_);
  if (element.has("state")) {
    constexpr std::array<std::string_view, 2> kStates{"Active", "Passive"};
    const auto state = read.choice(element, "state", kStates);
    ok = ok && state.has_value();
    frame.passive = state == 1u;
  }
  frame.daf = read.optionalBoolean(element, "daf").value_or(false);
  return ok;
}

void DescriptionParser::parseFrame(const common::XmlElement& element) {
  FrameDesc frame;
  frame.origin = originOf(element);
  frame.name = scoped(element.attributeOr("name", ""));
  frame.device = device_ ? device_->index : -1;
  if (device_ && scope_.size() > 1) frame.chain = scope_.back();
  bool ok = readFrameAttributes(element, frame);
  TransformReader transform;
  for (const common::XmlElement& child : element.children) {
    ok = parseFrameChild(child, element, frame, transform) && ok;
  }
  if (element.name == "DHJoint" && transform.any()) {
    sink_.error(element.location, element.describe() +
                                      ": a DHJoint is placed by its DH parameters; it takes no "
                                      "RPY, Pos or Transform");
    ok = false;
  } else if (element.name != "DHJoint") {
    const auto X = transform.finish(element, sink_);
    if (X) frame.transform = *X;
    ok = ok && X.has_value();
  }
  if (frame.depend && frame.type != FrameType::kRevolute && frame.type != FrameType::kPrismatic) {
    sink_.error(frame.depend->origin.location,
                element.describe() +
                    ": only Revolute and Prismatic joints can <Depend> on "
                    "another joint");
    ok = false;
  }
  if (frame.depend && !frame.limits.empty()) {
    // RobWork creates dependent joints without applying the limits written inside them.
    sink_.warning(frame.limits.front().origin.location,
                  element.describe() +
                      ": limits inside a dependent joint are ignored, as in "
                      "RobWork (device-level limits still apply)");
    frame.limits.clear();
  }
  attach(element, frame);
  if (device_) {
    device_->lastFrame = frame.name;
    ++device_->frameElements;
  } else {
    lastWorkCellFrame_ = frame.name;
  }
  if (!ok) return;
  if (device_) {
    desc_.devices[static_cast<std::size_t>(device_->index)].frames.push_back(
        static_cast<int>(desc_.frames.size()));
  }
  desc_.frames.push_back(std::move(frame));
}

bool DescriptionParser::parseFrameChild(const common::XmlElement& child,
                                        const common::XmlElement& element, FrameDesc& frame,
                                        TransformReader& transform) {
  const bool isJointElement = element.name != "Frame";
  if (transform.take(element, child, sink_)) return true;
  if (child.name == "Property") {
    if (auto p = readProperty(child, sink_)) frame.properties.push_back(std::move(*p));
    return true;
  }
  if (isModel(child.name)) {
    parseModel(child, frame.name);
    return true;
  }
  if (isJointElement && isLimit(child.name)) {
    auto limit = readLimit(child, element.describe(), sink_);
    if (!limit) return false;
    const std::string* refjoint = child.attribute("refjoint");
    if (refjoint != nullptr && scoped(*refjoint) != frame.name) {
      sink_.warning(child.location, element.describe() + ": <" + child.name + "> refjoint \"" +
                                        *refjoint + "\" is ignored inside a joint");
    }
    frame.limits.push_back(std::move(*limit));
    return true;
  }
  if (isJointElement && child.name == "Depend") {
    if (frame.depend) {
      sink_.error(child.location, element.describe() + ": more than one <Depend>");
      return false;
    }
    auto depend = readDepend(child, sink_);
    if (!depend) return false;
    depend->scope = scope_;
    frame.depend = std::move(*depend);
    return true;
  }
  notAllowed(child, element,
             element.name == "Frame"
                 ? kFrameChildren
                 : (element.name == "Joint" ? kJointChildren : kDhJointChildren));
  return false;
}

// RobWork's attachment rules (reference §1.3, §1.4; XMLParserUtil's AddFrameToWorkcell,
// AddFrameToDevice and AddDeviceToWorkcell).
void DescriptionParser::attach(const common::XmlElement& element, FrameDesc& frame) {
  const std::string* refframe = element.attribute("refframe");
  const bool given = refframe != nullptr && !refframe->empty();
  if (!device_) {
    // The first workcell-level frame always hangs on WORLD; later ones without refframe too.
    if (!seenWorkCellFrame_) {
      seenWorkCellFrame_ = true;
      frame.parent = kWorld;
      if (given && *refframe != kWorld) {
        sink_.warning(element.location, element.describe() +
                                            ": the first frame of a workcell is always attached "
                                            "to WORLD (as in RobWork); refframe \"" +
                                            *refframe + "\" is ignored");
      }
      return;
    }
    frame.parent = given ? *refframe : kWorld;
    frame.parentFromRefframe = given;
    return;
  }
  if (device_->lastFrame.empty()) {
    // Device base: on the last workcell-level frame declared before the device, or WORLD.
    frame.parent = lastWorkCellFrame_.empty() ? kWorld : lastWorkCellFrame_;
    if (given) {
      sink_.warning(element.location, element.describe() +
                                          ": the base frame of a device is attached to the last "
                                          "workcell frame before the device (here \"" +
                                          frame.parent + "\"), as in RobWork; refframe \"" +
                                          *refframe + "\" is ignored");
    }
    return;
  }
  if (!device_->tree) {
    frame.parent = device_->lastFrame;
    if (given && scoped(*refframe) != frame.parent) {
      sink_.warning(element.location, element.describe() +
                                          ": in a SerialDevice every frame is attached to the "
                                          "previous one (\"" +
                                          frame.parent + "\"); refframe \"" + *refframe +
                                          "\" is ignored");
    }
    return;
  }
  frame.parent = given ? scoped(*refframe) : device_->lastFrame;
  frame.parentFromRefframe = given;
}

}  // namespace

std::optional<WorkCellDesc> parseWorkCellDescription(
    const std::vector<common::XmlElement>& topLevel, const common::SourceLocation& file,
    common::DiagnosticSink& sink) {
  return DescriptionParser(sink).run(topLevel, file);
}

}  // namespace rw::loaders::detail
