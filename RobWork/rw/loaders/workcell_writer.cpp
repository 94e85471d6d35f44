#include "rw/loaders/workcell_writer.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "rw/common/number_text.hpp"
#include "rw/common/strings.hpp"
#include "rw/math/rpy.hpp"

namespace rw::loaders {
namespace {

namespace fs = std::filesystem;
using rw::geometry::Geometry;
using rw::geometry::GeometryType;
using rw::kinematics::Frame;
using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::kinematics::JointLimits;
using rw::kinematics::PropertyMap;
using rw::kinematics::State;
using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rw::models::Device;
using rw::models::GeometryInstance;
using rw::models::Object;
using rw::models::WorkCell;

/// Properties a loader adds on its own (reference §1.5 step 8); writing them back would be stale.
constexpr std::array<std::string_view, 3> kLoaderProperties = {
    "WorkCellFileName", "ProximitySetupFilePath", "ProximitySetupRelFilePath"};

// ------------------------------------------------------------------------------ text helpers

// Shortest text that reads back to the same double ("0" for both zeros).
std::string formatNumber(double v) {
  if (v == 0.0) return "0";
  return rw::common::shortestText(v);
}

// Degrees from radians; values within 1e-12 (relative) of a multiple of 1e-9 degrees are
// snapped to it, so that 90 deg is written as "90" and not "90.00000000000001".
double toDegrees(double radians) {
  const double degrees = radians * rw::math::kRad2Deg;
  const double snapped = std::round(degrees * 1e9) / 1e9;
  return std::abs(snapped - degrees) <= 1e-12 * std::max(1.0, std::abs(degrees)) ? snapped
                                                                                 : degrees;
}

std::string formatTriple(double a, double b, double c) {
  return formatNumber(a) + " " + formatNumber(b) + " " + formatNumber(c);
}

std::string formatList(const Q& q) {
  std::string text;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (i > 0) text += ' ';
    text += formatNumber(q[i]);
  }
  return text;
}

/// A minimal indenting XML writer; attributes are written in the order given.
class XmlWriter {
 public:
  using Attributes = std::vector<std::pair<std::string_view, std::string>>;

  void declaration() { out_ += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"; }
  void comment(std::string_view text) {
    indent();
    out_ += "<!-- ";
    out_ += text;
    out_ += " -->\n";
  }
  void open(std::string_view tag, const Attributes& attributes = {}) {
    indent();
    start(tag, attributes);
    out_ += ">\n";
    stack_.emplace_back(tag);
  }
  void close() {
    const std::string tag = std::move(stack_.back());
    stack_.pop_back();
    indent();
    out_ += "</" + tag + ">\n";
  }
  void leaf(std::string_view tag, const Attributes& attributes = {}) {
    indent();
    start(tag, attributes);
    out_ += "/>\n";
  }
  void text(std::string_view tag, const Attributes& attributes, std::string_view body) {
    indent();
    start(tag, attributes);
    out_ += '>';
    out_ += rw::common::escapeXml(body);
    out_ += "</";
    out_ += tag;
    out_ += ">\n";
  }
  std::string take() { return std::move(out_); }

 private:
  void indent() { out_.append(2 * stack_.size(), ' '); }
  void start(std::string_view tag, const Attributes& attributes) {
    out_ += '<';
    out_ += tag;
    for (const auto& [name, value] : attributes) {
      out_ += ' ';
      out_ += name;
      out_ += "=\"";
      out_ += rw::common::escapeXml(value);
      out_ += '"';
    }
  }

  std::string out_;
  std::vector<std::string> stack_;
};

// ------------------------------------------------------------------------------ model helpers

bool sameGeometry(const Geometry& a, const Geometry& b) {
  return &a == &b || (a.type() == b.type() && a.parameters() == b.parameters() &&
                      a.sourceFile() == b.sourceFile());
}

// A Drawable appears in both lists of an Object; this pairs its two entries.
bool sameInstance(const GeometryInstance& a, const GeometryInstance& b) {
  return a.name == b.name && a.X_frame_geometry.matrix() == b.X_frame_geometry.matrix() &&
         a.geometry != nullptr && b.geometry != nullptr && sameGeometry(*a.geometry, *b.geometry);
}

bool contains(const std::vector<FrameId>& ids, FrameId id) {
  return std::find(ids.begin(), ids.end(), id) != ids.end();
}

// The file name of `file` without its ".wc.xml" (or ".xml") ending.
std::string stemOf(const fs::path& file) {
  std::string name = file.filename().string();
  for (const std::string_view ending : {std::string_view(".wc.xml"), std::string_view(".xml")}) {
    if (name.size() > ending.size() && name.ends_with(ending)) {
      name.resize(name.size() - ending.size());
      break;
    }
  }
  return name;
}

// ------------------------------------------------------------------------------ the renderer

/// Writes one work cell; used once per render.
class Renderer {
 public:
  Renderer(const WorkCell& wc, const fs::path& targetDir)
      : wc_(wc), tree_(wc.frames()), state_(wc.defaultState()) {
    if (!targetDir.empty()) targetDir_ = fs::weakly_canonical(fs::absolute(targetDir));
    assignDevices();
  }

  WorkCellFiles render(std::string_view stem, bool withSetups);

 private:
  struct Item {
    bool isDevice = false;
    std::size_t index = 0;  // device index or frame index
  };

  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("cannot write workcell \"" + wc_.name() + "\": " + what);
  }
  std::string quoted(FrameId id) const { return "\"" + tree_.frame(id).name() + "\""; }
  int ownerOf(FrameId id) const { return owner_[static_cast<std::size_t>(id.index)]; }
  FrameId workcellParent(FrameId id) const;

  void assignDevices();
  void checkDevice(std::size_t index) const;
  void checkTreeEnds(const Device& device) const;
  void markEnds(const Device& device);
  bool writtenAsEnd(FrameId id) const { return endMark_[static_cast<std::size_t>(id.index)]; }
  std::vector<Item> planOrder() const;
  std::string nameInDevice(FrameId id, const Device& device) const;

  void writeWorkCellFrame(FrameId id);
  void writeDevice(std::size_t index);
  void writeParallelDevice(const Device& device);
  void enterChains(const std::vector<std::string>& scope, std::vector<std::string>& open);
  std::optional<std::string> parallelRef(FrameId id, FrameId previous, const Device& device) const;
  void writeFrameElement(FrameId id, const Device* device, const std::optional<std::string>& ref);
  void writeTransform(const Transform3D& X);
  void writeLimits(const Frame& frame, const std::string* refjoint);
  void writeDepend(const Frame& frame, const Device* device);
  void writeProperties(const PropertyMap& properties, const std::map<std::string, Q>* implied,
                       bool workcellLevel);
  void writeModels(FrameId id, const std::string* refframe);
  void writeModel(std::string_view tag, const GeometryInstance& instance,
                  const std::string* refframe, bool visualOnly);
  void writeGeometry(const Geometry& geometry);
  std::string meshPath(const std::string& source) const;

  std::string collisionSetupText() const;
  std::optional<std::string> proximitySetupText() const;

  const WorkCell& wc_;
  const FrameTree& tree_;
  State state_;
  fs::path targetDir_;
  std::vector<int> owner_;  // device index per frame, -1 for frames outside every device
  std::vector<bool> written_;
  std::vector<bool> endMark_;  // frames written with type="EndEffector"
  std::string chainPrefix_;    // open SerialChain scopes ("A.B."), relative to the device
  XmlWriter xml_;
};

void Renderer::assignDevices() {
  owner_.assign(tree_.size(), -1);
  written_.assign(tree_.size(), false);
  written_[0] = true;  // WORLD
  endMark_.assign(tree_.size(), false);
  for (const Frame& frame : tree_.frames()) {
    endMark_[static_cast<std::size_t>(frame.id().index)] =
        frame.type() == FrameType::kFixed && frame.isEndEffector();
  }
  const auto& devices = wc_.devices();
  for (std::size_t d = 0; d < devices.size(); ++d) {
    for (const FrameId id : devices[d]->frames()) {
      int& owner = owner_[static_cast<std::size_t>(id.index)];
      if (owner >= 0) {
        fail("frame " + quoted(id) + " belongs to devices \"" + devices[owner]->name() +
             "\" and \"" + devices[d]->name() + "\"");
      }
      owner = static_cast<int>(d);
    }
  }
  for (std::size_t d = 0; d < devices.size(); ++d) {
    markEnds(*devices[d]);
    checkDevice(d);
  }
}

// The frame a workcell-level frame is written under: a DAF's parent in the default state.
FrameId Renderer::workcellParent(FrameId id) const {
  const Frame& frame = tree_.frame(id);
  return frame.isDaf() ? state_.parentOf(id) : frame.parent();
}

void Renderer::checkDevice(std::size_t index) const {
  const Device& device = *wc_.devices()[index];
  const std::string prefix = device.name() + ".";
  for (const FrameId id : device.frames()) {
    if (!tree_.frame(id).name().starts_with(prefix) ||
        tree_.frame(id).name().size() == prefix.size()) {
      fail("frame " + quoted(id) + " of device \"" + device.name() + "\" is not named \"" + prefix +
           "<name>\"");
    }
    if (id != device.base() && ownerOf(tree_.frame(id).parent()) != static_cast<int>(index)) {
      fail("frame " + quoted(id) + " of device \"" + device.name() + "\" hangs below " +
           quoted(tree_.frame(id).parent()) + ", outside the device");
    }
  }
  const FrameId mount = tree_.frame(device.base()).parent();
  if (mount != FrameTree::kWorld && ownerOf(mount) >= 0) {
    fail("the base of device \"" + device.name() + "\" is mounted on " + quoted(mount) +
         " of another device; RobWork mounts devices on workcell-level frames only");
  }
  if (device.kind() == Device::Kind::kSerial) {
    const auto& frames = device.frames();
    for (std::size_t i = 1; i < frames.size(); ++i) {
      if (tree_.frame(frames[i]).parent() != frames[i - 1]) {
        fail("SerialDevice \"" + device.name() + "\" is not a chain at frame " + quoted(frames[i]));
      }
    }
    if (device.ends().size() != 1 || device.ends().front() != frames.back()) {
      fail("the end of SerialDevice \"" + device.name() + "\" is not its last frame");
    }
  } else if (device.kind() == Device::Kind::kTree) {
    checkTreeEnds(device);
  }
}

// Fixed frames flagged as end effectors keep the flag. A TreeDevice's ends are marked too,
// unless RobWork's fallback (no EndEffector frame: the last frame is the end) gives them.
void Renderer::markEnds(const Device& device) {
  if (device.kind() != Device::Kind::kTree) return;
  const auto& frames = device.frames();
  const bool anyMarked = std::any_of(frames.begin(), frames.end(), [&](FrameId id) {
    return endMark_[static_cast<std::size_t>(id.index)];
  });
  if (!anyMarked && device.ends() == std::vector<FrameId>{frames.back()}) return;
  for (const FrameId id : device.ends()) {
    if (tree_.frame(id).type() == FrameType::kFixed) {
      endMark_[static_cast<std::size_t>(id.index)] = true;
    }
  }
}

// RobWork takes a TreeDevice's ends from its EndEffector frames in document order (else its
// last frame) and lists, per end, the joints on the way from the base not yet listed. The
// frames are written in id order; the joint order that gives must be the device's.
void Renderer::checkTreeEnds(const Device& device) const {
  std::vector<FrameId> ends;
  for (const FrameId id : device.frames()) {
    if (writtenAsEnd(id)) ends.push_back(id);
  }
  if (ends.empty()) ends.push_back(device.frames().back());
  std::vector<FrameId> joints;
  for (const FrameId end : ends) {
    std::vector<FrameId> path;
    for (FrameId f = end; f != device.base(); f = tree_.frame(f).parent()) path.push_back(f);
    for (auto it = path.rbegin(); it != path.rend(); ++it) {
      if (tree_.frame(*it).isJoint() && !contains(joints, *it)) joints.push_back(*it);
    }
  }
  if (joints != device.joints()) {
    fail("the end effectors of TreeDevice \"" + device.name() +
         "\", written in frame order, would give another joint order");
  }
}

// Devices mounted on WORLD first (no workcell-level frame may precede them), then the
// workcell-level frames in id order, a child of WORLD first, each followed by the devices
// mounted on it.
std::vector<Renderer::Item> Renderer::planOrder() const {
  std::vector<Item> items;
  std::map<int, std::vector<std::size_t>> mounted;
  const auto& devices = wc_.devices();
  for (std::size_t d = 0; d < devices.size(); ++d) {
    const FrameId mount = tree_.frame(devices[d]->base()).parent();
    if (mount == FrameTree::kWorld) {
      items.push_back({true, d});
    } else {
      mounted[mount.index].push_back(d);
    }
  }
  std::vector<FrameId> frames;
  for (const Frame& frame : tree_.frames()) {
    if (frame.id() != FrameTree::kWorld && ownerOf(frame.id()) < 0) frames.push_back(frame.id());
  }
  if (!frames.empty()) {
    const auto first = std::find_if(frames.begin(), frames.end(), [&](FrameId id) {
      return workcellParent(id) == FrameTree::kWorld;
    });
    if (first == frames.end()) {
      fail("no workcell-level frame hangs on WORLD; RobWork attaches the first one to WORLD");
    }
    std::rotate(frames.begin(), first, first + 1);
  }
  for (const FrameId id : frames) {
    items.push_back({false, static_cast<std::size_t>(id.index)});
    if (const auto it = mounted.find(id.index); it != mounted.end()) {
      for (const std::size_t d : it->second) items.push_back({true, d});
    }
  }
  return items;
}

// The name as written at the current place: relative to the device and to the open
// SerialChain scopes (RobWork prefixes both).
std::string Renderer::nameInDevice(FrameId id, const Device& device) const {
  std::string name = tree_.frame(id).name().substr(device.name().size() + 1);
  if (!chainPrefix_.empty() && name.starts_with(chainPrefix_)) name.erase(0, chainPrefix_.size());
  return name;
}

WorkCellFiles Renderer::render(std::string_view stem, bool withSetups) {
  WorkCellFiles files;
  xml_.declaration();
  xml_.comment("Written by VisGraB's workcell writer.");
  xml_.open("WorkCell", {{"name", wc_.name()}});
  writeProperties(wc_.properties(), nullptr, true);
  for (const Item& item : planOrder()) {
    if (item.isDevice) {
      writeDevice(item.index);
    } else {
      writeWorkCellFrame(FrameId{static_cast<std::int32_t>(item.index)});
    }
  }
  const std::string world(FrameTree::kWorldName);
  writeModels(FrameTree::kWorld, &world);
  if (withSetups) {
    const std::string collisionName = std::string(stem) + ".collision.xml";
    xml_.leaf("CollisionSetup", {{"file", collisionName}});
    files.setupFiles.emplace_back(collisionName, collisionSetupText());
    if (auto proximity = proximitySetupText()) {
      const std::string proximityName = std::string(stem) + ".proximity.xml";
      xml_.leaf("ProximitySetup", {{"file", proximityName}});
      files.setupFiles.emplace_back(proximityName, std::move(*proximity));
    }
  }
  xml_.close();
  files.workcell = xml_.take();
  return files;
}

void Renderer::writeWorkCellFrame(FrameId id) {
  const Frame& frame = tree_.frame(id);
  if (frame.isJoint()) {
    const JointLimits& limits = frame.limits();
    const bool limited = std::isfinite(limits.lower) || std::isfinite(limits.upper) ||
                         std::isfinite(limits.velocity) || std::isfinite(limits.acceleration);
    if (limited || frame.isDependent() || frame.isPassive()) {
      fail("joint " + quoted(id) +
           " belongs to no device; RobWork's workcell-level <Frame> cannot carry its limits, "
           "coupling or passive state");
    }
  }
  writeFrameElement(id, nullptr, tree_.frame(workcellParent(id)).name());
}

void Renderer::writeDevice(std::size_t index) {
  const Device& device = *wc_.devices()[index];
  if (device.parallel() != nullptr) {
    writeParallelDevice(device);
    return;
  }
  const bool serial = device.kind() == Device::Kind::kSerial;
  xml_.open(serial ? "SerialDevice" : "TreeDevice", {{"name", device.name()}});
  for (const FrameId id : device.frames()) {
    // A base's refframe is ignored by RobWork, and so are all refframes in a SerialDevice.
    std::optional<std::string> ref;
    if (id != device.base() && !serial) ref = nameInDevice(tree_.frame(id).parent(), device);
    writeFrameElement(id, &device, ref);
  }
  writeProperties(device.properties(), &device.configurations(), false);
  for (const auto& [name, q] : device.configurations()) {
    xml_.text("Q", {{"name", name}}, formatList(q));
  }
  xml_.close();
}

// Opens and closes SerialChain elements so that exactly `scope` is open.
void Renderer::enterChains(const std::vector<std::string>& scope, std::vector<std::string>& open) {
  std::size_t common = 0;
  while (common < open.size() && common < scope.size() && open[common] == scope[common]) ++common;
  for (; open.size() > common; open.pop_back()) xml_.close();
  for (; open.size() < scope.size(); open.push_back(scope[open.size()])) {
    xml_.open("SerialChain", {{"name", scope[open.size()]}});
  }
  chainPrefix_.clear();
  for (const std::string& s : open) chainPrefix_ += s + ".";
}

// A frame that hangs on the frame written before it needs no refframe (RobWork attaches it
// there); any other parent must be nameable from the open SerialChain scope.
std::optional<std::string> Renderer::parallelRef(FrameId id, FrameId previous,
                                                 const Device& device) const {
  const FrameId parent = tree_.frame(id).parent();
  if (!previous.valid() || parent == previous) return std::nullopt;
  const std::string relative = tree_.frame(parent).name().substr(device.name().size() + 1);
  if (!relative.starts_with(chainPrefix_)) {
    fail("frame " + quoted(id) + " of ParallelDevice \"" + device.name() + "\" hangs on " +
         quoted(parent) + ", which is neither the frame before it nor in its SerialChain");
  }
  return relative.substr(chainPrefix_.size());
}

// Frames in document order, inside the SerialChain scopes their names give (the chains RobWork
// splits the device into, and the names the Junctions use, come from these scopes), then the
// Junctions (left out for RobWork's form without them: one junction of unnamed legs).
void Renderer::writeParallelDevice(const Device& device) {
  xml_.open("ParallelDevice", {{"name", device.name()}});
  std::vector<std::string> open;
  FrameId previous;
  for (const FrameId id : device.parallel()->frames()) {
    const std::string relative = tree_.frame(id).name().substr(device.name().size() + 1);
    std::vector<std::string> scope;
    for (const std::string_view part : rw::common::split(relative, '.')) scope.emplace_back(part);
    scope.pop_back();
    enterChains(scope, open);
    writeFrameElement(id, &device, parallelRef(id, previous, device));
    previous = id;
  }
  enterChains({}, open);
  // RobWork's grammar: the body (properties included), then the Junctions, then the Qs.
  writeProperties(device.properties(), &device.configurations(), false);
  for (const auto& junction : device.parallel()->junctions()) {
    const bool named = std::all_of(junction.legs.begin(), junction.legs.end(),
                                   [](const auto& leg) { return !leg.chains.empty(); });
    if (!named) continue;
    xml_.open("Junction", {});
    for (const auto& leg : junction.legs) {
      std::string chains;
      for (const std::string& c : leg.chains) chains += (chains.empty() ? "" : " ") + c;
      xml_.text("Chains", {}, chains);
    }
    xml_.close();
  }
  for (const auto& [name, q] : device.configurations()) {
    xml_.text("Q", {{"name", name}}, formatList(q));
  }
  xml_.close();
}

void Renderer::writeFrameElement(FrameId id, const Device* device,
                                 const std::optional<std::string>& ref) {
  const Frame& frame = tree_.frame(id);
  const bool asJoint = device != nullptr && frame.isJoint();
  const std::string name = device != nullptr ? nameInDevice(id, *device) : frame.name();
  XmlWriter::Attributes attributes{{"name", name}};
  if (ref) attributes.emplace_back("refframe", *ref);
  if (asJoint) {
    attributes.emplace_back("type",
                            frame.type() == FrameType::kRevolute ? "Revolute" : "Prismatic");
    if (frame.isPassive()) attributes.emplace_back("state", "Passive");
  } else {
    switch (frame.type()) {
      case FrameType::kFixed:
        if (writtenAsEnd(id)) attributes.emplace_back("type", "EndEffector");
        break;
      case FrameType::kMovable:
        attributes.emplace_back("type", "Movable");
        break;
      case FrameType::kRevolute:
        attributes.emplace_back("type", "Revolute");
        break;
      case FrameType::kPrismatic:
        attributes.emplace_back("type", "Prismatic");
        break;
    }
    if (frame.isDaf()) attributes.emplace_back("daf", "true");
  }
  xml_.open(asJoint ? "Joint" : "Frame", attributes);
  writeTransform(frame.type() == FrameType::kMovable ? frame.movableTransform(state_)
                                                     : frame.fixedTransform());
  if (asJoint && !frame.isDependent()) writeLimits(frame, nullptr);
  if (asJoint && frame.isDependent()) writeDepend(frame, device);
  const bool isBase = device != nullptr && id == device->base();
  writeProperties(frame.properties(), isBase ? &device->configurations() : nullptr, false);
  writeModels(id, nullptr);
  xml_.close();
  // RobWork ignores limits inside a dependent joint; at device level it keeps them as written.
  if (asJoint && frame.isDependent()) writeLimits(frame, &name);
  written_[static_cast<std::size_t>(id.index)] = true;
}

void Renderer::writeTransform(const Transform3D& X) {
  const Vector3D rpy = rw::math::rotationToRpy(X.linear());
  xml_.text("RPY", {}, formatTriple(toDegrees(rpy[0]), toDegrees(rpy[1]), toDegrees(rpy[2])));
  const Vector3D& p = X.translation();
  xml_.text("Pos", {}, formatTriple(p.x(), p.y(), p.z()));
}

// Limits inside a joint (refjoint null): degrees for revolute joints. Device-level limits
// (refjoint set, written for dependent joints only): raw, as RobWork stores them (reference
// §1.9). An infinite bound of a finite range is written as the largest double.
void Renderer::writeLimits(const Frame& frame, const std::string* refjoint) {
  const JointLimits& limits = frame.limits();
  const bool degrees = refjoint == nullptr && frame.type() == FrameType::kRevolute;
  const auto value = [&](double v) {
    if (std::isinf(v)) {
      return formatNumber(v > 0 ? std::numeric_limits<double>::max()
                                : std::numeric_limits<double>::lowest());
    }
    return formatNumber(degrees ? toDegrees(v) : v);
  };
  const auto attributes = [&] {
    XmlWriter::Attributes a;
    if (refjoint != nullptr) a.emplace_back("refjoint", *refjoint);
    return a;
  };
  if (std::isfinite(limits.lower) || std::isfinite(limits.upper)) {
    auto a = attributes();
    a.emplace_back("min", value(limits.lower));
    a.emplace_back("max", value(limits.upper));
    xml_.leaf("PosLimit", a);
  }
  if (std::isfinite(limits.velocity)) {
    auto a = attributes();
    a.emplace_back("max", value(limits.velocity));
    xml_.leaf("VelLimit", a);
  }
  if (std::isfinite(limits.acceleration)) {
    auto a = attributes();
    a.emplace_back("max", value(limits.acceleration));
    xml_.leaf("AccLimit", a);
  }
}

// RobWork looks the owner up in the device's scope first, then unscoped: a joint of the same
// device is named relative to it, any other by its full name.
void Renderer::writeDepend(const Frame& frame, const Device* device) {
  const auto& dependency = *frame.dependency();
  const FrameId owner = dependency.owner;
  if (!written_[static_cast<std::size_t>(owner.index)]) {
    fail("joint " + quoted(frame.id()) + " depends on " + quoted(owner) +
         ", which would be written after it");
  }
  const bool sameDevice = device != nullptr && device->contains(owner);
  xml_.leaf("Depend",
            {{"on", sameDevice ? nameInDevice(owner, *device) : tree_.frame(owner).name()},
             {"gain", formatNumber(dependency.gain)},
             {"offset", formatNumber(dependency.offset)}});
}

// `implied`: the device's named configurations, which RobWork also stores as Q properties of the
// device and its base; such properties are left out (the <Q> elements bring them back).
void Renderer::writeProperties(const PropertyMap& properties,
                               const std::map<std::string, Q>* implied, bool workcellLevel) {
  for (const auto& [name, property] : properties) {
    if (workcellLevel && std::find(kLoaderProperties.begin(), kLoaderProperties.end(), name) !=
                             kLoaderProperties.end()) {
      continue;
    }
    const Q* q = std::get_if<Q>(&property.value);
    if (implied != nullptr && q != nullptr) {
      const auto it = implied->find(name);
      if (it != implied->end() && it->second.size() == q->size() && it->second == *q) continue;
    }
    XmlWriter::Attributes attributes{{"name", name}};
    std::string text;
    if (const auto* s = std::get_if<std::string>(&property.value)) {
      attributes.emplace_back("type", "string");
      text = *s;
    } else if (const auto* d = std::get_if<double>(&property.value)) {
      attributes.emplace_back("type", "double");
      text = formatNumber(*d);
    } else {
      attributes.emplace_back("type", "Q");
      text = formatList(*q);
    }
    if (!property.description.empty()) attributes.emplace_back("desc", property.description);
    xml_.text("Property", attributes, text);
  }
}

// A visual instance with a twin among the collision instances is a Drawable; a visual one
// without is a Drawable with colmodel="Disabled"; the remaining collision ones are
// CollisionModels.
void Renderer::writeModels(FrameId id, const std::string* refframe) {
  const Object* object = wc_.findObject(id);
  if (object == nullptr) return;
  std::vector<bool> paired(object->collision.size(), false);
  for (const GeometryInstance& visual : object->visual) {
    bool twin = false;
    for (std::size_t i = 0; i < object->collision.size() && !twin; ++i) {
      if (!paired[i] && sameInstance(visual, object->collision[i])) paired[i] = twin = true;
    }
    writeModel("Drawable", visual, refframe, !twin);
  }
  for (std::size_t i = 0; i < object->collision.size(); ++i) {
    if (!paired[i]) writeModel("CollisionModel", object->collision[i], refframe, false);
  }
}

void Renderer::writeModel(std::string_view tag, const GeometryInstance& instance,
                          const std::string* refframe, bool visualOnly) {
  if (instance.geometry == nullptr) {
    fail("geometry \"" + instance.name + "\" has no shape");
  }
  XmlWriter::Attributes attributes{{"name", instance.name}};
  if (refframe != nullptr) attributes.emplace_back("refframe", *refframe);
  if (visualOnly) attributes.emplace_back("colmodel", "Disabled");
  xml_.open(tag, attributes);
  writeTransform(instance.X_frame_geometry);
  if (tag == "Drawable" && instance.color != GeometryInstance{}.color) {
    xml_.text("RGB", {}, formatTriple(instance.color[0], instance.color[1], instance.color[2]));
  }
  writeGeometry(*instance.geometry);
  xml_.close();
}

void Renderer::writeGeometry(const Geometry& geometry) {
  const std::vector<double>& p = geometry.parameters();
  const auto need = [&](std::size_t n) {
    if (p.size() != n) {
      fail(std::string(rw::geometry::geometryTypeName(geometry.type())) + " with " +
           std::to_string(p.size()) + " parameters");
    }
  };
  switch (geometry.type()) {
    case GeometryType::kBox:
      need(3);
      xml_.leaf("Box",
                {{"x", formatNumber(p[0])}, {"y", formatNumber(p[1])}, {"z", formatNumber(p[2])}});
      break;
    case GeometryType::kSphere:
      need(1);
      xml_.leaf("Sphere", {{"radius", formatNumber(p[0])}});
      break;
    case GeometryType::kCylinder:
    case GeometryType::kCone:
      need(2);
      xml_.leaf(geometry.type() == GeometryType::kCylinder ? "Cylinder" : "Cone",
                {{"radius", formatNumber(p[0])}, {"z", formatNumber(p[1])}});
      break;
    case GeometryType::kTube:
      need(3);
      xml_.leaf("Tube", {{"radius", formatNumber(p[0])},
                         {"thickness", formatNumber(p[1])},
                         {"z", formatNumber(p[2])}});
      break;
    case GeometryType::kFrustum:
      need(3);
      xml_.leaf("Custom", {{"type", "Frustum"},
                           {"param", formatNumber(p[0]) + " " + formatNumber(p[1]) + " " +
                                         formatNumber(p[2])}});
      break;
    case GeometryType::kPlane:
      xml_.leaf("Plane");
      break;
    case GeometryType::kMesh:
      if (geometry.sourceFile().empty()) fail("a mesh without a source file");
      xml_.leaf("Polytope", {{"file", meshPath(geometry.sourceFile())}});
      break;
  }
}

// Relative to the target folder when the two share a folder below the file system's root,
// else absolute (a path that climbs to the root is no more portable than an absolute one);
// '/' separators.
std::string Renderer::meshPath(const std::string& source) const {
  const fs::path path(source);
  if (targetDir_.empty() || !path.is_absolute()) return path.generic_string();
  const fs::path mesh = fs::weakly_canonical(path);
  auto m = mesh.begin();
  auto t = targetDir_.begin();
  int shared = 0;
  for (; m != mesh.end() && t != targetDir_.end() && *m == *t; ++m, ++t) ++shared;
  if (shared < 2) return mesh.generic_string();
  const fs::path relative = mesh.lexically_relative(targetDir_);
  return relative.empty() ? mesh.generic_string() : relative.generic_string();
}

std::string Renderer::collisionSetupText() const {
  const auto& setup = wc_.collisionSetup();
  XmlWriter xml;
  xml.declaration();
  xml.open("CollisionSetup");
  if (!setup.excludePairs.empty()) {
    xml.open("Exclude");
    for (const auto& [first, second] : setup.excludePairs) {
      xml.leaf("FramePair", {{"first", first}, {"second", second}});
    }
    xml.close();
  }
  for (const std::string& frame : setup.volatileFrames) xml.text("Volatile", {}, frame);
  if (setup.excludeStaticPairs || wc_.proximitySetup().useExcludeStaticPairs) {
    xml.leaf("ExcludeStaticPairs");
  }
  xml.close();
  return xml.take();
}

// The proximity rules beyond the collision setup. A loader may keep the collision setup's
// excludes as the first rules (RobWork's merge does); those come back from the collision setup
// file and are not repeated.
std::optional<std::string> Renderer::proximitySetupText() const {
  const auto& excludes = wc_.collisionSetup().excludePairs;
  const auto& proximity = wc_.proximitySetup();
  std::size_t skip = 0;
  if (proximity.rules.size() >= excludes.size()) {
    while (skip < excludes.size() && !proximity.rules[skip].include &&
           proximity.rules[skip].patternA == excludes[skip].first &&
           proximity.rules[skip].patternB == excludes[skip].second) {
      ++skip;
    }
    if (skip != excludes.size()) skip = 0;
  }
  if (skip == proximity.rules.size()) return std::nullopt;
  XmlWriter xml;
  xml.declaration();
  // No UseIncludeAll/UseExcludeStaticPairs: RobWork merges only a file's rules (reference §1.5);
  // the workcell's flags come from the collision setup.
  xml.open("ProximitySetup");
  for (std::size_t i = skip; i < proximity.rules.size(); ++i) {
    const auto& rule = proximity.rules[i];
    xml.leaf(rule.include ? "Include" : "Exclude",
             {{"PatternA", rule.patternA}, {"PatternB", rule.patternB}});
  }
  xml.close();
  return xml.take();
}

void writeText(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) {
    throw std::runtime_error("cannot write " + file.string() + ": " +
                             std::error_code(errno, std::generic_category()).message());
  }
}

}  // namespace

WorkCellFiles renderWorkCell(const WorkCell& wc, const fs::path& targetDir, std::string_view stem) {
  return Renderer(wc, targetDir).render(stem, true);
}

std::string writeWorkCell(const WorkCell& wc, const fs::path& targetDir) {
  return Renderer(wc, targetDir).render({}, false).workcell;
}

void saveWorkCell(const WorkCell& wc, const fs::path& file) {
  const fs::path target = fs::absolute(file);
  const WorkCellFiles files = renderWorkCell(wc, target.parent_path(), stemOf(target));
  writeText(target, files.workcell);
  for (const auto& [name, text] : files.setupFiles) writeText(target.parent_path() / name, text);
}

}  // namespace rw::loaders
