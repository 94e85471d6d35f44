#include "rwsim/loaders/detail/dwc_parser.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <utility>

#include "rw/common/numbers.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/math/rpy.hpp"

namespace rwsim::loaders::detail {

namespace {

using rw::common::DiagnosticSink;
using rw::common::parseNumberList;
using rw::common::trimXmlSpace;
using rw::common::XmlElement;
using rw::math::Vector3D;
using rwsim::dynamics::FrictionData;

/// Relative tolerance of the symmetry check of a 9-value inertia.
constexpr double kSymmetryTolerance = 1e-9;

/// Controller types RobWork's PDDeviceController accepts.
constexpr std::array<std::string_view, 5> kControllerTypes = {"Position", "CntPosition", "Velocity",
                                                              "Force", "Current"};

/// Elements read but not simulated by this project.
constexpr std::array<std::string_view, 10> kNotSimulated = {"TactileArraySensor",
                                                            "BodyContactSensor",
                                                            "FTSensor",
                                                            "TactileMultiAxisSensor",
                                                            "SuctionCup",
                                                            "KinematicDevice",
                                                            "PoseDeviceController",
                                                            "SerialDeviceController",
                                                            "SpringJointController",
                                                            "Spring"};

/// Elements whose text is a list of numbers (for explainDynamicWorkCellValueError).
constexpr std::array<std::string_view, 13> kNumberElements = {
    "Gravity",    "Mass", "COG", "Inertia",    "PDParams",   "TimeStep", "CollisionMargin",
    "ForceLimit", "Pos",  "RPY", "Rotation3D", "Compliance", "Damping"};

/// Tolerance of the orthonormality check of a <Rotation3D>.
constexpr double kRotationTolerance = 1e-6;

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string trimmed(const XmlElement& e) { return std::string(trimXmlSpace(e.text)); }

std::string formatNumber(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

/// True for the body elements whose mass properties matter.
bool isRigidKind(const std::string& tag) {
  return tag == "RigidBody" || tag == "RigidBase" || tag == "RigidJoint" || tag == "Link";
}

/// true/1/on or false/0/off in any case; nullopt otherwise.
std::optional<bool> parseBool(std::string_view text) {
  const std::string value = lower(trimXmlSpace(text));
  if (value == "true" || value == "1" || value == "on") return true;
  if (value == "false" || value == "0" || value == "off") return false;
  return std::nullopt;
}

/// Reads one dynamic workcell's elements into a description.
class Parser {
 public:
  explicit Parser(DiagnosticSink& sink) : sink_(sink), read_(sink, describeElement) {}

  std::optional<DynamicWorkCellDesc> run(const XmlElement& root,
                                         const std::vector<XmlElement>& topLevel) {
    desc_.workcellFile = root.attributeOr("workcell", "");
    desc_.rootLocation = root.location;
    for (const XmlElement& e : topLevel) topLevelElement(e);
    finish();
    if (sink_.hasErrors()) return std::nullopt;
    return std::move(desc_);
  }

 private:
  void error(const XmlElement& e, const std::string& message) { read_.error(e, message); }
  void warning(const XmlElement& e, const std::string& message) { read_.warning(e, message); }

  void topLevelElement(const XmlElement& e);
  void physicsEngine(const XmlElement& e);
  void materialData(const XmlElement& e);
  void frictionMap(const XmlElement& e);
  std::optional<FrictionData> frictionData(const XmlElement& pair);
  void objectTypeData(const XmlElement& e);
  void contactMap(const XmlElement& e);
  BodyDesc body(const XmlElement& e, const char* frameAttribute);
  void bodyChild(const XmlElement& child, BodyDesc& body, std::set<std::string>& seen);
  void checkBody(const XmlElement& e, const BodyDesc& body);
  void rigidDevice(const XmlElement& e);
  void deviceBase(const XmlElement& child, DeviceDesc& device);
  void controller(const XmlElement& e);
  void constraint(const XmlElement& e);
  std::optional<rw::math::Transform3D> transform(const XmlElement& e);
  void constraintLimits(const XmlElement& e, ConstraintDesc& c);
  void constraintSpring(const XmlElement& e, ConstraintDesc& c);
  void finish();

  std::optional<double> number(const XmlElement& e) { return read_.textNumber(e); }
  std::optional<std::vector<double>> numbers(const XmlElement& e) { return read_.textNumbers(e); }
  std::optional<Vector3D> vector3(const XmlElement& e);
  std::optional<Eigen::Matrix3d> inertia(const XmlElement& e);
  std::optional<std::string> nonEmptyText(const XmlElement& e);
  std::optional<rw::kinematics::PropertyValue> property(const XmlElement& e, std::string& text);

  DiagnosticSink& sink_;
  rw::common::XmlValueReader read_;
  DynamicWorkCellDesc desc_;
};

void Parser::topLevelElement(const XmlElement& e) {
  const std::string& n = e.name;
  if (n == "Gravity") {
    if (auto g = vector3(e)) desc_.gravity = *g;
  } else if (n == "PhysicsEngine") {
    physicsEngine(e);
  } else if (n == "MaterialData") {
    materialData(e);
  } else if (n == "FrictionMap") {
    frictionMap(e);
  } else if (n == "ObjectTypeData") {
    objectTypeData(e);
  } else if (n == "ContactMap") {
    contactMap(e);
  } else if (n == "DefaultRestitutionModel" || n == "ContactModel") {
    warning(e, "ignored (RobWork ignores it too)");
  } else if (n == "RigidBody" || n == "FixedBody" || n == "KinematicBody") {
    desc_.bodies.push_back(body(e, "frame"));
  } else if (n == "RigidDevice") {
    rigidDevice(e);
  } else if (n == "PDDeviceController") {
    controller(e);
  } else if (n == "Constraint") {
    constraint(e);
  } else if (std::find(kNotSimulated.begin(), kNotSimulated.end(), n) != kNotSimulated.end()) {
    warning(e, "not simulated by this project; ignored");
  } else {
    error(e, "unexpected element here");  // the schema normally rejects it first
  }
}

void Parser::physicsEngine(const XmlElement& e) {
  for (const XmlElement& c : e.children) {
    if (c.name == "CollisionMargin") {
      (void)number(c);  // read but unused, as in RobWork
    } else if (c.name == "AutoDisable") {
      const std::string value = lower(trimmed(c));
      if (value != "true" && value != "false") error(c, "expected true or false");
    } else if (c.name == "Property") {
      std::string text;
      if (property(c, text)) desc_.engineProperties[c.attributeOr("name", "")] = text;
    }
  }
}

void Parser::materialData(const XmlElement& e) {
  for (const XmlElement& c : e.children) {
    if (c.name == "Default") {
      auto name = nonEmptyText(c);
      if (!name) continue;
      if (desc_.defaultMaterial && desc_.defaultMaterial->text != *name) {
        warning(c, "replaces the default material \"" + desc_.defaultMaterial->text + "\"");
      }
      desc_.defaultMaterial = LocatedText{*name, c.location};
      desc_.materials.setDefaultMaterial(*name);
    } else if (c.name == "Material") {
      const std::string id = c.attributeOr("id", "");
      if (!desc_.materials.addMaterial(id)) {
        warning(c, "material \"" + id +
                       "\" is declared twice; the second declaration is "
                       "ignored, as RobWork does");
      }
    }
  }
}

void Parser::frictionMap(const XmlElement& e) {
  for (const XmlElement& pair : e.children) {
    const std::string first = pair.attributeOr("first", "");
    const std::string second = pair.attributeOr("second", "");
    auto data = frictionData(pair);
    if (!data) continue;
    for (const std::string& m : {first, second}) {
      if (!desc_.materials.hasMaterial(m)) {
        warning(pair, "unknown material \"" + m +
                          "\" (not declared before in <MaterialData>); the pair is ignored, as "
                          "RobWork does");
        data.reset();
        break;
      }
    }
    if (!data) continue;
    if (desc_.materials.friction(first, second) != nullptr) {
      warning(pair,
              "a second friction entry for this pair; it is ignored (RobWork keeps the "
              "first)");
      continue;
    }
    desc_.materials.setFriction(first, second, std::move(*data));
  }
}

std::optional<FrictionData> Parser::frictionData(const XmlElement& pair) {
  std::optional<FrictionData> result;
  for (const XmlElement& c : pair.children) {
    if (c.name != "FrictionData") {
      warning(c, "ignored in a <FrictionMap> (expected <FrictionData>)");
      continue;
    }
    if (result) {
      warning(c, "only the first <FrictionData> of a pair is used");
      continue;
    }
    FrictionData data;
    const std::string type = c.attributeOr("type", "");
    data.type = lower(type) == "coulomb" ? "Coulomb" : type;
    for (const XmlElement& parameter : c.children) {
      auto values = numbers(parameter);
      if (!values) return std::nullopt;
      data.parameters.emplace_back(parameter.name, std::move(*values));
    }
    if (!trimXmlSpace(c.text).empty()) {
      error(c, "text is not allowed here; write the values in named children such as <Mu>");
      return std::nullopt;
    }
    if (data.parameters.empty() || data.parameters.front().second.empty()) {
      warning(c, "no friction coefficient (the first value of the first child); mu " +
                     formatNumber(rwsim::dynamics::MaterialMap::kDefaultMu) + " is used");
    }
    result = std::move(data);
  }
  if (!result) warning(pair, "no <FrictionData>; the pair is ignored");
  return result;
}

void Parser::objectTypeData(const XmlElement& e) {
  for (const XmlElement& c : e.children) {
    if (c.name == "Default") {
      auto name = nonEmptyText(c);
      if (!name) continue;
      desc_.defaultObjectType = LocatedText{*name, c.location};
      desc_.materials.setDefaultObjectType(*name);
    } else if (c.name == "ObjectType") {
      const std::string id = c.attributeOr("id", "");
      if (!desc_.materials.addObjectType(id)) {
        warning(c, "object type \"" + id +
                       "\" is declared twice; the second declaration is "
                       "ignored");
      }
    }
  }
}

void Parser::contactMap(const XmlElement& e) {
  for (const XmlElement& pair : e.children) {
    const std::string first = pair.attributeOr("first", "");
    const std::string second = pair.attributeOr("second", "");
    if (!desc_.materials.hasObjectType(first) || !desc_.materials.hasObjectType(second)) {
      warning(pair,
              "unknown object type (not declared before in <ObjectTypeData>); the pair is "
              "ignored, as RobWork does");
      continue;
    }
    bool used = false;
    for (const XmlElement& c : pair.children) {
      if (c.name != "ContactData" || c.attributeOr("type", "") != "Newton" || used) {
        warning(c, "ignored (expected one <ContactData type=\"Newton\"> with <cr>)");
        continue;
      }
      const auto cr = std::find_if(c.children.begin(), c.children.end(),
                                   [](const XmlElement& x) { return x.name == "cr"; });
      if (cr == c.children.end()) {
        error(c, "missing <cr> (the restitution coefficient)");
        continue;
      }
      if (auto value = number(*cr)) {
        if (*value < 0.0) {
          error(*cr, "the restitution coefficient must be >= 0, got " + formatNumber(*value));
        } else {
          desc_.materials.setRestitution(first, second, *value);
          used = true;
        }
      }
    }
  }
}

BodyDesc Parser::body(const XmlElement& e, const char* frameAttribute) {
  BodyDesc b;
  b.tag = e.name;
  b.element = describeElement(e);
  b.location = e.location;
  b.frame = e.attributeOr(frameAttribute, "");
  std::set<std::string> seen;
  for (const XmlElement& child : e.children) bodyChild(child, b, seen);
  checkBody(e, b);
  return b;
}

void Parser::bodyChild(const XmlElement& c, BodyDesc& b, std::set<std::string>& seen) {
  const std::string& n = c.name;
  if (n != "Associate" && n != "Property" && !seen.insert(n).second) {
    warning(c, "given twice in " + b.element + "; the first is used, as RobWork does");
    return;
  }
  if (n == "Mass") {
    b.mass = number(c);
    b.massLocation = c.location;
  } else if (n == "COG") {
    b.cog = vector3(c);
  } else if (n == "Inertia") {
    b.inertia = inertia(c);
  } else if (n == "EstimateInertia") {
    b.estimateInertia = true;
  } else if (n == "Integrator" || n == "MaterialID" || n == "ObjectID") {
    auto text = nonEmptyText(c);
    if (!text) return;
    auto& target = n == "Integrator" ? b.integrator : n == "MaterialID" ? b.material : b.objectType;
    target = LocatedText{*text, c.location};
  } else if (n == "Associate") {
    b.associates.push_back(LocatedText{c.attributeOr("object", ""), c.location});
  } else if (n == "Property") {
    std::string text;
    if (auto value = property(c, text)) {
      b.properties[c.attributeOr("name", "")] =
          rw::kinematics::Property{std::move(*value), c.attributeOr("desc", "")};
    }
  }
}

void Parser::checkBody(const XmlElement& e, const BodyDesc& b) {
  if (!isRigidKind(b.tag)) {
    const bool massGiven = b.mass || b.cog || b.inertia || b.estimateInertia;
    if (massGiven) warning(e, "mass properties are ignored for a " + b.tag);
    if (b.integrator) warning(e, "<Integrator> is ignored for a " + b.tag);
    if (b.tag == "KinematicBody" && !b.material) {
      warning(e,
              "RobWork requires a <MaterialID> in a KinematicBody; the default material is "
              "used");
    }
    return;
  }
  if (!b.mass) {
    if (std::none_of(e.children.begin(), e.children.end(),
                     [](const XmlElement& c) { return c.name == "Mass"; })) {
      error(e, "missing <Mass> (kg, > 0)");
    }
  } else if (!(*b.mass > 0.0)) {
    sink_.error(b.massLocation, "<Mass>: the mass must be > 0 kg, got " + formatNumber(*b.mass));
  }
  if (b.estimateInertia && b.inertia) {
    warning(e, "<Inertia> is ignored because <EstimateInertia/> is given (as RobWork does)");
  } else if (!b.estimateInertia && !b.inertia) {
    if (std::none_of(e.children.begin(), e.children.end(),
                     [](const XmlElement& c) { return c.name == "Inertia"; })) {
      error(e, "expected <EstimateInertia/> or <COG> with <Inertia>");
    }
  } else if (!b.estimateInertia && !b.cog &&
             std::none_of(e.children.begin(), e.children.end(),
                          [](const XmlElement& c) { return c.name == "COG"; })) {
    error(e, "<Inertia> needs a <COG> (the point it is taken about)");
  }
  if (b.tag == "RigidBody" && !b.integrator) {
    warning(e,
            "missing <Integrator>, which RobWork requires; this project's simulator does not "
            "use it");
  } else if (b.tag != "RigidBody" && b.tag != "RigidBase" && b.integrator) {
    warning(e, "<Integrator> is ignored for a " + b.tag);
  }
}

void Parser::rigidDevice(const XmlElement& e) {
  DeviceDesc d;
  d.name = e.attributeOr("device", "");
  d.element = describeElement(e);
  d.location = e.location;
  for (const XmlElement& c : e.children) {
    if (c.name == "ForceLimit") {
      const std::string joint = c.attributeOr("joint", "");
      const auto same = [&](const ForceLimitDesc& f) { return f.joint == joint; };
      auto value = number(c);
      if (!value) continue;
      if (std::any_of(d.forceLimits.begin(), d.forceLimits.end(), same)) {
        error(c, "a second <ForceLimit> for joint \"" + joint + "\"");
      } else if (*value < 0.0) {
        error(c, "the force limit must be >= 0, got " + formatNumber(*value));
      } else {
        d.forceLimits.push_back(ForceLimitDesc{joint, *value, c.location});
      }
    } else if (c.name == "RigidJoint" || c.name == "Link") {
      d.links.push_back(body(c, c.name == "Link" ? "object" : "joint"));
    } else {
      deviceBase(c, d);
    }
  }
  if (!d.base) {
    error(e, "missing base: expected <KinematicBase>, <FixedBase>, <RigidBase> or <RefBase>");
  }
  desc_.devices.push_back(std::move(d));
}

void Parser::deviceBase(const XmlElement& c, DeviceDesc& d) {
  if (d.base) {
    error(c, "a second base; a RigidDevice has one (the first is at line " +
                 std::to_string(d.base->location.line) + ")");
    return;
  }
  if (c.name == "RefBase") {
    BodyDesc ref;
    ref.tag = c.name;
    ref.element = describeElement(c);
    ref.location = c.location;
    ref.frame = c.attributeOr("body", "");
    d.base = std::move(ref);
  } else {
    d.base = body(c, "frame");
  }
}

void Parser::controller(const XmlElement& e) {
  ControllerDesc c;
  c.name = e.attributeOr("name", "");
  c.device = e.attributeOr("device", "");
  c.type = e.attributeOr("type", "Position");
  c.element = describeElement(e);
  c.location = e.location;
  if (std::find(kControllerTypes.begin(), kControllerTypes.end(), c.type) ==
      kControllerTypes.end()) {
    error(e, "unknown type \"" + c.type +
                 "\" (expected Position, CntPosition, Velocity, Force or Current)");
  }
  for (const XmlElement& child : e.children) {
    if (child.name == "Sync") {
      const auto sync = parseBool(child.text);
      if (!sync) {
        error(child, "expected true or false, got \"" + trimmed(child) + "\"");
      } else if (*sync) {
        error(child, "synchronous PD control (Sync true) is not supported, as in RobWork");
      }
    } else if (child.name == "PDParams") {
      c.gains = numbers(child);
      c.gainsLocation = child.location;
    } else if (child.name == "TimeStep") {
      auto dt = number(child);
      if (dt && !(*dt > 0.0)) error(child, "the time step must be > 0 s, got " + formatNumber(*dt));
      if (dt) c.timeStep = *dt;
    }
  }
  const bool hasParams = std::any_of(e.children.begin(), e.children.end(),
                                     [](const XmlElement& x) { return x.name == "PDParams"; });
  if (!hasParams) error(e, "missing <PDParams> (a P and a D gain per DOF)");
  desc_.controllers.push_back(std::move(c));
}

void Parser::constraint(const XmlElement& e) {
  using rwsim::dynamics::constraintTypeFromName;
  ConstraintDesc c;
  c.name = e.attributeOr("name", "");
  c.parent = e.attributeOr("parent", "");
  c.child = e.attributeOr("child", "");
  c.element = describeElement(e);
  c.location = e.location;
  const std::string type = e.attributeOr("type", "");
  c.type = constraintTypeFromName(type);
  if (!c.type) {
    error(e, "unknown type \"" + type + "\" (expected " + rwsim::dynamics::constraintTypeNames() +
                 "; any case)");
  }
  for (const ConstraintDesc& other : desc_.constraints) {
    if (other.name == c.name) {
      error(e, "a second constraint named \"" + c.name + "\" (the first is at line " +
                   std::to_string(other.location.line) + ")");
      break;
    }
  }
  if (c.parent == c.child) {
    error(e,
          "parent and child are the same body \"" + c.parent + "\"; expected two different bodies");
  }
  std::set<std::string> seen;
  for (const XmlElement& child : e.children) {
    if (!seen.insert(child.name).second) {
      error(child, "given twice in " + c.element);
      continue;
    }
    if (child.name == "Transform3D") {
      if (auto X = transform(child)) c.X_parent_constraint = *X;
    } else if (child.name == "Limits") {
      constraintLimits(child, c);
    } else if (child.name == "Spring") {
      constraintSpring(child, c);
    }
  }
  if (c.type == rwsim::dynamics::ConstraintType::kFree && seen.count("Spring") == 0) {
    warning(e, "a Free constraint leaves all six DOF free: without a <Spring> it has no effect");
  }
  desc_.constraints.push_back(std::move(c));
}

std::optional<rw::math::Transform3D> Parser::transform(const XmlElement& e) {
  rw::math::Transform3D X = rw::math::Transform3D::Identity();
  bool ok = true;
  const XmlElement* rotation = nullptr;
  for (const XmlElement& c : e.children) {
    if (c.name == "Pos") {
      const auto p = vector3(c);
      if (p) X.translation() = *p;
      ok = ok && p.has_value();
    } else if (c.name == "RPY" || c.name == "Rotation3D") {
      if (rotation != nullptr) {
        error(c, "a second rotation in <Transform3D> (the first is <" + rotation->name +
                     "> at line " + std::to_string(rotation->location.line) +
                     "); expected one <RPY> or <Rotation3D>");
        ok = false;
        continue;
      }
      rotation = &c;
      if (c.name == "RPY") {
        const auto rpy = vector3(c);
        if (rpy) X.linear() = rw::math::rpyToRotation(*rpy);  // radians in a .dwc.xml
        ok = ok && rpy.has_value();
        continue;
      }
      const auto values = read_.textNumbers(c, 9, "a row-major 3x3 rotation matrix");
      if (!values) {
        ok = false;
        continue;
      }
      Eigen::Matrix3d R;
      for (int k = 0; k < 9; ++k) R(k / 3, k % 3) = (*values)[static_cast<std::size_t>(k)];
      if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), kRotationTolerance) ||
          !(R.determinant() > 0.0)) {
        error(c, "not a rotation matrix (expected orthonormal rows and determinant +1)");
        ok = false;
        continue;
      }
      X.linear() = R;
    }
  }
  if (!ok) return std::nullopt;
  return X;
}

void Parser::constraintLimits(const XmlElement& e, ConstraintDesc& c) {
  using rwsim::dynamics::ConstraintLimit;
  using rwsim::dynamics::ConstraintType;
  bool ok = true;
  std::vector<ConstraintLimit> limits;
  for (const XmlElement& l : e.children) {
    if (l.name != "Limit") continue;  // the schema rejects anything else
    ConstraintLimit limit;
    for (const char* key : {"low", "high"}) {
      if (!l.has(key)) continue;
      const auto value = read_.optionalNumber(l, key);
      if (!value) {
        ok = false;
        continue;
      }
      (std::string_view(key) == "low" ? limit.low : limit.high) = *value;
    }
    if (limit.low > limit.high) {
      error(l, "low " + formatNumber(limit.low) + " > high " + formatNumber(limit.high) +
                   "; expected low <= high");
      ok = false;
    }
    const bool angular = c.type && limits.size() >= rwsim::dynamics::constraintDof(*c.type).linear;
    constexpr double kPi = std::numbers::pi;
    if (angular && ((std::isfinite(limit.low) && limit.low < -kPi) ||
                    (std::isfinite(limit.high) && limit.high > kPi))) {
      error(l, "an angular limit must lie in [-pi, pi] rad (ODE's stop range)");
      ok = false;
    }
    limits.push_back(limit);
  }
  if (!ok || !c.type) return;
  const std::string typeName(rwsim::dynamics::constraintTypeName(*c.type));
  if (*c.type == ConstraintType::kFree) {
    warning(e, "ignored: a Free constraint has no stops (RobWork ignores them too)");
    return;
  }
  if (*c.type == ConstraintType::kSpherical) {
    error(e, "a Spherical constraint takes no limits (RobWork's ODE engine rejects them too)");
    return;
  }
  const std::size_t dof = rwsim::dynamics::constraintDof(*c.type).total();
  if (limits.size() != dof) {
    error(e, "expected " + std::to_string(dof) + " <Limit> (one per free DOF of a " + typeName +
                 " constraint: " + std::string(rwsim::dynamics::constraintDofText(*c.type)) +
                 "), got " + std::to_string(limits.size()));
    return;
  }
  c.limits = std::move(limits);
}

void Parser::constraintSpring(const XmlElement& e, ConstraintDesc& c) {
  const std::size_t n = c.type ? rwsim::dynamics::constraintDof(*c.type).total() : 0;
  const auto size = static_cast<Eigen::Index>(n);
  rwsim::dynamics::ConstraintSpring spring{Eigen::MatrixXd::Zero(size, size),
                                           Eigen::MatrixXd::Zero(size, size)};
  bool ok = c.type.has_value();
  for (const XmlElement& m : e.children) {
    if (m.name != "Compliance" && m.name != "Damping") continue;  // the schema rejects others
    const auto values = numbers(m);
    if (!values || !c.type) {
      ok = false;
      continue;
    }
    if (values->size() != n * n) {
      error(m, "expected " + std::to_string(n * n) + " numbers (a " + std::to_string(n) + " x " +
                   std::to_string(n) + " matrix for the free DOF of a " +
                   std::string(rwsim::dynamics::constraintTypeName(*c.type)) +
                   " constraint), got " + std::to_string(values->size()));
      ok = false;
      continue;
    }
    Eigen::MatrixXd& target = m.name == "Compliance" ? spring.compliance : spring.damping;
    for (std::size_t k = 0; k < values->size(); ++k) {
      // Column by column, as RobWork's readMatrixD fills it.
      target(static_cast<Eigen::Index>(k % n), static_cast<Eigen::Index>(k / n)) = (*values)[k];
    }
  }
  if (!ok) return;  // the matrix's own error says enough
  c.spring = std::move(spring);
  error(e,
        "springs on constraints are not supported yet (this project does not simulate "
        "RobWorkSim's compliance/damping forces); remove the <Spring>");
}

void Parser::finish() {
  const auto& m = desc_.materials;
  if (desc_.defaultMaterial && !m.hasMaterial(desc_.defaultMaterial->text)) {
    sink_.error(desc_.defaultMaterial->location, "<Default>: the default material \"" +
                                                     desc_.defaultMaterial->text +
                                                     "\" is not declared in <MaterialData>");
  }
  if (desc_.defaultObjectType && !m.hasObjectType(desc_.defaultObjectType->text)) {
    sink_.error(desc_.defaultObjectType->location, "<Default>: the default object type \"" +
                                                       desc_.defaultObjectType->text +
                                                       "\" is not declared in <ObjectTypeData>");
  }
}

std::optional<Vector3D> Parser::vector3(const XmlElement& e) {
  const auto v = read_.textVector3(e);
  if (!v) return std::nullopt;
  return Vector3D((*v)[0], (*v)[1], (*v)[2]);
}

std::optional<Eigen::Matrix3d> Parser::inertia(const XmlElement& e) {
  auto values = numbers(e);
  if (!values) return std::nullopt;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  if (values->size() == 3) {
    I = Vector3D((*values)[0], (*values)[1], (*values)[2]).asDiagonal();
  } else if (values->size() == 9) {
    for (int k = 0; k < 9; ++k) I(k / 3, k % 3) = (*values)[static_cast<std::size_t>(k)];
  } else {
    error(e, "expected 3 numbers (the diagonal) or 9 (row-major), got " +
                 std::to_string(values->size()));
    return std::nullopt;
  }
  const double scale = I.cwiseAbs().maxCoeff();
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * scale) {
    error(e, "the inertia tensor is not symmetric");
    return std::nullopt;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(I, Eigen::EigenvaluesOnly);
  if (!(eigen.eigenvalues().minCoeff() > 0.0)) {
    error(e, "the inertia tensor is not positive definite (smallest eigenvalue " +
                 formatNumber(eigen.eigenvalues().minCoeff()) + " kg m^2)");
    return std::nullopt;
  }
  return I;
}

std::optional<std::string> Parser::nonEmptyText(const XmlElement& e) {
  std::string text = trimmed(e);
  if (text.empty()) {
    error(e, "is empty; expected a name");
    return std::nullopt;
  }
  return text;
}

std::optional<rw::kinematics::PropertyValue> Parser::property(const XmlElement& e,
                                                              std::string& text) {
  std::string type = e.attributeOr("type", "string");
  text = trimmed(e);
  if (type == "double") {
    warning(e,
            "type \"double\" is rejected by RobWork (it knows string, int, float and Q); "
            "read as float");
    type = "float";
  }
  if (type == "string") return rw::kinematics::PropertyValue{text};
  if (type == "int") {
    const auto n = rw::common::parseInteger(text, std::numeric_limits<std::int32_t>::min(),
                                            std::numeric_limits<std::int32_t>::max());
    if (!n.error.empty()) {
      error(e, n.error);
      return std::nullopt;
    }
    return rw::kinematics::PropertyValue{static_cast<double>(n.value)};
  }
  if (type == "float") {
    auto value = number(e);
    if (!value) return std::nullopt;
    return rw::kinematics::PropertyValue{*value};
  }
  if (type == "Q") {
    auto values = numbers(e);
    if (!values) return std::nullopt;
    return rw::kinematics::PropertyValue{
        Eigen::Map<const Eigen::VectorXd>(values->data(), static_cast<Eigen::Index>(values->size()))
            .eval()};
  }
  error(e, "unknown type \"" + type + "\" (expected string, int, float or Q)");
  return std::nullopt;
}

}  // namespace

std::string describeElement(const XmlElement& element) {
  if (element.name == "Pair" && element.has("first") && element.has("second")) {
    return "<Pair first=\"" + element.attributeOr("first", "") + "\" second=\"" +
           element.attributeOr("second", "") + "\">";
  }
  for (const char* key :
       {"frame", "device", "joint", "object", "body", "name", "id", "file", "workcell"}) {
    if (const std::string* value = element.attribute(key)) {
      return "<" + element.name + " " + key + "=\"" + *value + "\">";
    }
  }
  return "<" + element.name + ">";
}

std::string explainDynamicWorkCellValueError(const XmlElement& element) {
  if (std::find(kNumberElements.begin(), kNumberElements.end(), element.name) ==
      kNumberElements.end()) {
    return {};
  }
  std::vector<double> values;
  return parseNumberList(element.text, values);
}

std::optional<DynamicWorkCellDesc> parseDynamicWorkCellDescription(
    const XmlElement& root, const std::vector<XmlElement>& topLevel, DiagnosticSink& sink) {
  return Parser(sink).run(root, topLevel);
}

}  // namespace rwsim::loaders::detail
