#include "rwsim/loaders/detail/dwc_builder.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rw/geometry/mass_properties.hpp"

namespace rwsim::loaders::detail {

namespace {

using rw::common::DiagnosticSink;
using rw::kinematics::FrameId;
using rw::kinematics::FrameType;
using rw::models::Device;
using rwsim::dynamics::Body;
using rwsim::dynamics::BodyId;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DeviceId;
using rwsim::dynamics::DynamicWorkCell;

const char* frameTypeName(FrameType type) {
  switch (type) {
    case FrameType::kFixed:
      return "Fixed";
    case FrameType::kMovable:
      return "Movable";
    case FrameType::kRevolute:
      return "Revolute";
    case FrameType::kPrismatic:
      return "Prismatic";
  }
  return "unknown";
}

BodyKind kindOf(const std::string& tag) {
  if (tag == "FixedBody" || tag == "FixedBase") return BodyKind::kFixed;
  if (tag == "KinematicBody" || tag == "KinematicBase") return BodyKind::kKinematic;
  return BodyKind::kRigid;
}

bool isLink(const std::string& tag) { return tag == "RigidJoint" || tag == "Link"; }

/// A body to create: its description, its frame and the scope of its names ("Device." for
/// device parts, empty otherwise).
struct PlannedBody {
  const BodyDesc* desc = nullptr;
  FrameId frame;
  std::string prefix;
};

/// A device whose names resolved: its bodies and force limits in joints() order.
struct PlannedDevice {
  const DeviceDesc* desc = nullptr;
  const Device* device = nullptr;
  std::optional<PlannedBody> base;
  std::vector<PlannedBody> links;
  std::vector<double> forceLimits;
};

class Builder {
 public:
  Builder(const DynamicWorkCellDesc& desc, std::unique_ptr<rw::models::WorkCell> workcell,
          DiagnosticSink& sink)
      : desc_(desc), sink_(sink), dwc_(std::make_unique<DynamicWorkCell>(std::move(workcell))) {}

  std::unique_ptr<DynamicWorkCell> run() {
    dwc_->materials() = desc_.materials;
    dwc_->setGravity(desc_.gravity);
    for (const auto& [name, value] : desc_.engineProperties) dwc_->setEngineProperty(name, value);
    for (const BodyDesc& b : desc_.bodies) planFreeBody(b);
    for (const DeviceDesc& d : desc_.devices) planDevice(d);
    for (const PlannedBody& p : freeBodies_) addBody(p);
    for (const PlannedDevice& d : devices_) addDevice(d);
    for (const ControllerDesc& c : desc_.controllers) addController(c);
    for (const ConstraintDesc& c : desc_.constraints) addConstraint(c);
    if (sink_.hasErrors()) return nullptr;
    return std::move(dwc_);
  }

 private:
  const rw::kinematics::FrameTree& tree() const { return dwc_->workcell().frames(); }

  void error(const BodyDesc& b, const std::string& message) {
    sink_.error(b.location, b.element + ": " + message);
  }

  std::optional<FrameId> claimFrame(const BodyDesc& b, const std::string& name);
  std::optional<std::string> baseFrameName(const Device& device, const BodyDesc& base,
                                           const std::string& prefix);
  void planFreeBody(const BodyDesc& b);
  void planDevice(const DeviceDesc& d);
  bool planForceLimits(PlannedDevice& planned);
  std::optional<FrameId> deviceJoint(const Device& device, const BodyDesc& link);
  void addBody(const PlannedBody& p);
  std::optional<Body> makeBody(const PlannedBody& p);
  bool addGeometryFrames(const PlannedBody& p, Body& body);
  bool setMaterial(const BodyDesc& b, Body& body);
  bool setMassProperties(const BodyDesc& b, Body& body);
  void addDevice(const PlannedDevice& d);
  void addController(const ControllerDesc& c);
  void addConstraint(const ConstraintDesc& c);

  const DynamicWorkCellDesc& desc_;
  DiagnosticSink& sink_;
  std::unique_ptr<DynamicWorkCell> dwc_;
  std::vector<PlannedBody> freeBodies_;
  std::vector<PlannedDevice> devices_;
  std::vector<FrameId> bodyFrames_;
  std::vector<const BodyDesc*> bodyFrameOwners_;
  std::vector<std::string> failedDevices_;
};

/// Resolves a body's frame and records it as a body frame; checks it carries no other body.
std::optional<FrameId> Builder::claimFrame(const BodyDesc& b, const std::string& name) {
  const FrameId id = dwc_->workcell().findFrame(name);
  if (!id.valid()) {
    error(b, "unknown frame \"" + name + "\"");
    return std::nullopt;
  }
  const auto it = std::find(bodyFrames_.begin(), bodyFrames_.end(), id);
  if (it != bodyFrames_.end()) {
    const BodyDesc* other = bodyFrameOwners_[static_cast<std::size_t>(it - bodyFrames_.begin())];
    error(b, "frame \"" + name + "\" already carries the body of " + other->element + " (line " +
                 std::to_string(other->location.line) + ")");
    return std::nullopt;
  }
  const FrameType type = tree().frame(id).type();
  const BodyKind kind = kindOf(b.tag);
  if ((kind == BodyKind::kKinematic || b.tag == "RigidBody" || b.tag == "RigidBase") &&
      type != FrameType::kMovable) {
    error(b, "frame \"" + name + "\" is " + frameTypeName(type) + "; a " + b.tag +
                 " needs a Movable frame");
    return std::nullopt;
  }
  bodyFrames_.push_back(id);
  bodyFrameOwners_.push_back(&b);
  return id;
}

void Builder::planFreeBody(const BodyDesc& b) {
  if (auto id = claimFrame(b, b.frame)) freeBodies_.push_back(PlannedBody{&b, *id, ""});
}

/// The frame of a device's base element: the device's own frame of that name (RobWork), else
/// (this project's extension) a frame outside the device that holds the device's base rigidly,
/// such as a Movable mount frame put before a device file that cannot be edited. nullopt after
/// an error (a frame outside the device that does not hold its base).
std::optional<std::string> Builder::baseFrameName(const Device& device, const BodyDesc& base,
                                                  const std::string& prefix) {
  const std::string scoped = prefix + base.frame;
  const auto& wc = dwc_->workcell();
  const FrameId outside = wc.findFrame(base.frame);
  if (wc.findFrame(scoped).valid() || !outside.valid()) return scoped;
  for (FrameId f = device.base(); f.valid(); f = tree().frame(f).parent()) {
    if (f == outside) return base.frame;
    if (f != device.base() && tree().frame(f).type() != FrameType::kFixed) break;
  }
  error(base, "frame \"" + base.frame + "\" is neither a frame of device \"" + device.name() +
                  "\" nor a frame that holds its base \"" + tree().frame(device.base()).name() +
                  "\" rigidly");
  return std::nullopt;
}

void Builder::planDevice(const DeviceDesc& d) {
  PlannedDevice planned;
  planned.desc = &d;
  planned.device = dwc_->workcell().findDevice(d.name);
  if (planned.device == nullptr) {
    std::string known;
    for (const auto& device : dwc_->workcell().devices()) {
      known += (known.empty() ? "" : ", ") + device->name();
    }
    sink_.error(d.location, d.element + ": unknown device \"" + d.name + "\" (the workcell has " +
                                (known.empty() ? std::string("none") : known) + ")");
    failedDevices_.push_back(d.name);
    return;
  }
  const std::string prefix = d.name + ".";
  bool ok = planForceLimits(planned);
  if (d.base && d.base->tag != "RefBase") {
    const auto name = baseFrameName(*planned.device, *d.base, prefix);
    auto id = name ? claimFrame(*d.base, *name) : std::nullopt;
    if (id) planned.base = PlannedBody{&*d.base, *id, prefix};
    ok = ok && id.has_value();
  } else if (d.base) {
    planned.base = PlannedBody{&*d.base, FrameId{}, prefix};
  }
  for (const BodyDesc& link : d.links) {
    auto joint = deviceJoint(*planned.device, link);
    if (joint && !claimFrame(link, tree().frame(*joint).name())) joint.reset();
    if (joint) planned.links.push_back(PlannedBody{&link, *joint, prefix});
    ok = ok && joint.has_value();
  }
  if (!ok || !d.base) {
    failedDevices_.push_back(d.name);
    return;
  }
  devices_.push_back(std::move(planned));
}

bool Builder::planForceLimits(PlannedDevice& planned) {
  const DeviceDesc& d = *planned.desc;
  const auto& joints = planned.device->joints();
  planned.forceLimits.assign(joints.size(), -1.0);
  bool ok = true;
  for (const ForceLimitDesc& f : d.forceLimits) {
    const FrameId id = dwc_->workcell().findFrame(d.name + "." + f.joint);
    const auto it = std::find(joints.begin(), joints.end(), id);
    if (it == joints.end()) {
      sink_.error(f.location, "<ForceLimit joint=\"" + f.joint + "\">: \"" + f.joint +
                                  "\" is not a joint of device \"" + d.name + "\"");
      ok = false;
      continue;
    }
    planned.forceLimits[static_cast<std::size_t>(it - joints.begin())] = f.value;
  }
  std::string missing;
  const bool parallel = planned.device->parallel() != nullptr;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (planned.forceLimits[j] >= 0.0) continue;
    if (parallel && tree().frame(joints[j]).isPassive()) {
      planned.forceLimits[j] = 0.0;  // a free joint of a loop: no motor (RobWork: active only)
      continue;
    }
    const std::string& full = tree().frame(joints[j]).name();
    missing += (missing.empty() ? "" : ", ") + std::string("<ForceLimit joint=\"") +
               full.substr(d.name.size() + 1) + "\">";
  }
  if (!missing.empty()) {
    sink_.error(d.location, d.element + ": missing " + missing +
                                " (RobWork needs one for every joint, dependent ones included)");
    ok = false;
  }
  return ok;
}

std::optional<FrameId> Builder::deviceJoint(const Device& device, const BodyDesc& link) {
  const FrameId id = dwc_->workcell().findFrame(device.name() + "." + link.frame);
  const auto& joints = device.joints();
  if (std::find(joints.begin(), joints.end(), id) != joints.end()) return id;
  if (link.tag == "Link" && id.valid()) {
    error(link, "\"" + link.frame + "\" is not a joint of device \"" + device.name() +
                    "\" (this project simulates links on joint frames only)");
  } else {
    error(link, "\"" + link.frame + "\" is not a joint of device \"" + device.name() + "\"");
  }
  return std::nullopt;
}

void Builder::addBody(const PlannedBody& p) {
  auto body = makeBody(p);
  if (!body) return;
  try {
    dwc_->addBody(std::move(*body));
  } catch (const std::invalid_argument& e) {
    error(*p.desc, e.what());
  }
}

std::optional<Body> Builder::makeBody(const PlannedBody& p) {
  const BodyDesc& b = *p.desc;
  Body body;
  body.frame = p.frame;
  body.name = tree().frame(p.frame).name();
  body.kind = kindOf(b.tag);
  body.properties = b.properties;
  bool ok = addGeometryFrames(p, body);
  ok = setMaterial(b, body) && ok;
  if (ok && body.kind == BodyKind::kRigid) ok = setMassProperties(b, body);
  if (ok && b.tag == "FixedBody" &&
      std::none_of(body.geometryFrames.begin(), body.geometryFrames.end(), [&](FrameId f) {
        const auto* object = dwc_->workcell().findObject(f);
        return object != nullptr && !object->collision.empty();
      })) {
    error(b, "frame \"" + body.name + "\" has no collision geometry; a FixedBody needs some");
    ok = false;
  }
  if (!ok) return std::nullopt;
  return body;
}

bool Builder::addGeometryFrames(const PlannedBody& p, Body& body) {
  body.geometryFrames = rwsim::dynamics::rigidlyAttachedFrames(tree(), p.frame, bodyFrames_);
  for (const LocatedText& associate : p.desc->associates) {
    FrameId id = dwc_->workcell().findFrame(p.prefix + associate.text);
    if (!id.valid()) id = dwc_->workcell().findFrame(associate.text);
    if (!id.valid()) {
      sink_.error(associate.location,
                  "<Associate object=\"" + associate.text + "\">: unknown frame");
      return false;
    }
    if (std::find(bodyFrames_.begin(), bodyFrames_.end(), id) != bodyFrames_.end()) {
      sink_.error(associate.location, "<Associate object=\"" + associate.text +
                                          "\">: the frame is the frame of a body");
      return false;
    }
    for (const FrameId f : rwsim::dynamics::rigidlyAttachedFrames(tree(), id, bodyFrames_)) {
      if (std::find(body.geometryFrames.begin(), body.geometryFrames.end(), f) ==
          body.geometryFrames.end()) {
        body.geometryFrames.push_back(f);
      }
    }
  }
  return true;
}

bool Builder::setMaterial(const BodyDesc& b, Body& body) {
  const auto& materials = dwc_->materials();
  if (b.material) {
    if (!materials.hasMaterial(b.material->text)) {
      sink_.error(b.material->location, "<MaterialID>: unknown material \"" + b.material->text +
                                            "\" (not declared in <MaterialData>)");
      return false;
    }
    body.material = b.material->text;
  } else if (materials.defaultMaterial().empty()) {
    error(b, "no <MaterialID> and no default material (<MaterialData><Default>)");
    return false;
  } else {
    body.material = materials.defaultMaterial();
  }
  if (b.objectType) {
    if (!materials.hasObjectType(b.objectType->text)) {
      sink_.error(b.objectType->location, "<ObjectID>: unknown object type \"" +
                                              b.objectType->text +
                                              "\" (not declared in <ObjectTypeData>)");
      return false;
    }
    body.objectType = b.objectType->text;
  } else {
    body.objectType = materials.defaultObjectType();
  }
  return true;
}

bool Builder::setMassProperties(const BodyDesc& b, Body& body) {
  if (!b.mass || !(*b.mass > 0.0)) return false;  // reported by the parser
  body.mass.mass = *b.mass;
  if (!b.estimateInertia) {
    if (!b.cog || !b.inertia) return false;  // reported by the parser
    body.mass.cog = *b.cog;
    body.mass.inertia = *b.inertia;
    return true;
  }
  const rw::kinematics::State state = dwc_->workcell().defaultState();
  std::vector<rw::geometry::PlacedGeometry> geometry;
  for (const FrameId f : body.geometryFrames) {
    const auto* object = dwc_->workcell().findObject(f);
    if (object == nullptr) continue;
    const auto X_body_frame = rw::kinematics::relativeTransform(tree(), state, body.frame, f);
    for (const auto& g : object->collision) {
      geometry.push_back({g.geometry, X_body_frame * g.X_frame_geometry});
    }
  }
  if (geometry.empty() && isLink(b.tag)) {
    error(b, "<EstimateInertia/> needs geometry, but \"" + body.name +
                 "\" has no collision geometry (give <COG> and <Inertia>)");
    return false;
  }
  const auto estimate = rw::geometry::estimateMassProperties(*b.mass, geometry, b.cog);
  if (!estimate.fromGeometry) {
    sink_.warning(b.location,
                  b.element +
                      ": no geometry with a volume to estimate the inertia from; a solid "
                      "sphere of radius 0.0001 m is used, as RobWork does");
  }
  body.mass.cog = estimate.cog;
  body.mass.inertia = estimate.inertia;
  return true;
}

void Builder::addDevice(const PlannedDevice& d) {
  const DeviceDesc& desc = *d.desc;
  const std::size_t errorsBefore = sink_.errorCount();
  rwsim::dynamics::RigidDevice device;
  device.device = d.device;
  device.forceLimits = d.forceLimits;
  device.linkBodies.assign(d.device->joints().size(), BodyId::none());
  if (d.base->desc->tag == "RefBase") {
    device.baseBody = dwc_->findBody(d.base->desc->frame);
    if (!device.baseBody.valid()) {
      device.baseBody = dwc_->findBody(d.base->prefix + d.base->desc->frame);
    }
    if (!device.baseBody.valid())
      error(*d.base->desc, "unknown body \"" + d.base->desc->frame + "\"");
  } else {
    addBody(*d.base);
    device.baseBody = dwc_->findBody(tree().frame(d.base->frame).name());
  }
  const auto& joints = d.device->joints();
  for (const PlannedBody& link : d.links) {
    addBody(link);
    const auto j = static_cast<std::size_t>(std::find(joints.begin(), joints.end(), link.frame) -
                                            joints.begin());
    device.linkBodies[j] = dwc_->findBody(tree().frame(link.frame).name());
  }
  if (sink_.errorCount() != errorsBefore || !device.baseBody.valid()) {
    failedDevices_.push_back(desc.name);
    return;
  }
  try {
    dwc_->addDevice(std::move(device));
  } catch (const std::invalid_argument& e) {
    sink_.error(desc.location, desc.element + ": " + e.what());
    failedDevices_.push_back(desc.name);
  }
}

void Builder::addController(const ControllerDesc& c) {
  if (std::find(failedDevices_.begin(), failedDevices_.end(), c.device) != failedDevices_.end()) {
    return;  // the device's own error says enough
  }
  const DeviceId index = dwc_->findDevice(c.device);
  if (!index.valid()) {
    const bool inWorkCell = dwc_->workcell().findDevice(c.device) != nullptr;
    sink_.error(c.location, c.element + ": " +
                                (inWorkCell ? "device \"" + c.device + "\" has no <RigidDevice>"
                                            : "unknown device \"" + c.device + "\""));
    return;
  }
  if (!c.gains) return;  // reported by the parser
  const Device& device = *dwc_->device(index).device;
  const auto dof = static_cast<std::size_t>(device.dof());
  // One P and D pair stands for every DOF (this project's extension; RobWork wants a pair per DOF).
  std::vector<double> gains = *c.gains;
  if (gains.size() == 2 && dof > 1) {
    for (std::size_t i = 1; i < dof; ++i) gains.insert(gains.end(), {gains[0], gains[1]});
  }
  if (gains.size() != 2 * dof) {
    sink_.error(c.gainsLocation, "<PDParams>: expected " + std::to_string(2 * dof) +
                                     " numbers (a P and a D gain for each of the " +
                                     std::to_string(dof) + " DOF of device \"" + c.device +
                                     "\", or one pair for all), got " +
                                     std::to_string(c.gains->size()));
    return;
  }
  rwsim::dynamics::PDController controller;
  controller.name = c.name;
  controller.device = index;
  controller.type = c.type;
  controller.timeStep = c.timeStep;
  controller.p.resize(static_cast<Eigen::Index>(dof));
  controller.d.resize(static_cast<Eigen::Index>(dof));
  for (std::size_t i = 0; i < dof; ++i) {
    controller.p[static_cast<Eigen::Index>(i)] = gains[2 * i];
    controller.d[static_cast<Eigen::Index>(i)] = gains[2 * i + 1];
  }
  try {
    dwc_->addController(std::move(controller));
  } catch (const std::invalid_argument& e) {
    sink_.error(c.location, c.element + ": " + e.what());
  }
}

const char* kindName(BodyKind kind) {
  switch (kind) {
    case BodyKind::kRigid:
      return "rigid";
    case BodyKind::kKinematic:
      return "kinematic";
    case BodyKind::kFixed:
      return "fixed";
  }
  return "unknown";
}

void Builder::addConstraint(const ConstraintDesc& c) {
  if (!c.type || c.parent == c.child) return;  // reported by the parser
  bool ok = true;
  const auto find = [&](const std::string& name, const char* role) {
    const BodyId id = dwc_->findBody(name);
    if (!id.valid()) {
      sink_.error(c.location, c.element + ": unknown " + role + " body \"" + name +
                                  "\" (expected the frame name of a RigidBody, FixedBody, "
                                  "KinematicBody or device body)");
      ok = false;
    }
    return id;
  };
  rwsim::dynamics::Constraint constraint;
  constraint.parent = find(c.parent, "parent");
  constraint.child = find(c.child, "child");
  if (!ok) return;
  const BodyKind parentKind = dwc_->body(constraint.parent).kind;
  const BodyKind childKind = dwc_->body(constraint.child).kind;
  if (parentKind != BodyKind::kRigid && childKind != BodyKind::kRigid) {
    sink_.error(c.location, c.element + ": parent \"" + c.parent + "\" is " + kindName(parentKind) +
                                " and child \"" + c.child + "\" is " + kindName(childKind) +
                                "; expected at least one rigid body (one that can move)");
    return;
  }
  constraint.name = c.name;
  constraint.type = *c.type;
  constraint.X_parent_constraint = c.X_parent_constraint;
  constraint.limits = c.limits;
  constraint.spring = c.spring;
  try {
    dwc_->addConstraint(std::move(constraint));
  } catch (const std::invalid_argument& e) {
    sink_.error(c.location, c.element + ": " + e.what());
  }
}

}  // namespace

std::unique_ptr<DynamicWorkCell> buildDynamicWorkCell(
    const DynamicWorkCellDesc& desc, std::unique_ptr<rw::models::WorkCell> workcell,
    DiagnosticSink& sink) {
  return Builder(desc, std::move(workcell), sink).run();
}

}  // namespace rwsim::loaders::detail
