#include "visgrab/taskio/rwtask_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include "rw/common/numbers.hpp"
#include "rw/common/strings.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/math/rpy.hpp"
#include "visgrab/taskio/detail/common.hpp"

namespace visgrab::taskio {

using rw::common::XmlElement;
using rw::math::Q;
using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;

namespace {

/// The value types of RobWork's DOM PropertyMap (reference §3.3).
constexpr std::array<std::string_view, 21> kKnownTypes = {
    "String",      "StringList", "Integer", "IntList",    "Double",     "Float",
    "DoubleList",  "Boolean",    "Q",       "Vector3D",   "Vector2D",   "Transform3D",
    "Rotation3D",  "RPY",        "EAA",     "Quaternion", "Rotation2D", "VelocityScrew6D",
    "PropertyMap", "QPath",      "T3DPath"};

/// Scale factor of a `unit` attribute (to metres / radians / seconds); 0 if unknown.
double unitFactor(std::string_view unit) {
  static const std::map<std::string_view, double> kUnits = {
      {"m", 1.0},       {"cm", 1e-2},
      {"mm", 1e-3},     {"inch", 0.0254},
      {"rad", 1.0},     {"deg", std::numbers::pi / 180.0},
      {"m/s", 1.0},     {"cm/s", 1e-2},
      {"mm/s", 1e-3},   {"m/s^2", 1.0},
      {"cm/s^2", 1e-2}, {"mm/s^2", 1e-3},
      {"rad/s", 1.0},   {"deg/s", std::numbers::pi / 180.0},
      {"rad/s^2", 1.0}, {"deg/s^2", std::numbers::pi / 180.0}};
  const auto it = kUnits.find(unit);
  return it == kUnits.end() ? 0.0 : it->second;
}

/// A PropertyMap entry as read, before interpretation.
struct RawProperty {
  std::string name;
  std::string description;
  const XmlElement* value = nullptr;    // the typed element inside <Value>
  const XmlElement* element = nullptr;  // the <Property>
};

/// Largest magnitude of an Integer property.
constexpr long long kLargestInteger = 1'000'000'000;

class TaskParser {
 public:
  explicit TaskParser(rw::common::DiagnosticSink& sink) : sink_(sink) {}

  GraspTask parseRoot(const XmlElement& root) {
    GraspTask task;
    for (const auto& c : root.children) {
      const auto name = detail::localName(c.name);
      if (name == "Entities") {
        for (const auto& entity : c.children) {
          if (detail::localName(entity.name) == "CartesianTask") {
            task.subTasks.push_back(parseSubTask(entity));
          } else {
            sink_.warning(entity.location, entity.describe() +
                                               ": entity ignored (only CartesianTask sub-tasks "
                                               "are grasp tasks)");
          }
        }
      } else if (name == "PropertyMap") {
        for (auto& p : readPropertyMap(c)) {
          if (p.name == "Gripper") {
            task.gripperId = readString(p);
          } else if (p.name == "TCP") {
            task.tcpId = readString(p);
          } else if (p.name == "GraspController") {
            task.graspControllerId = readString(p);
          } else {
            task.otherProperties.push_back(keep(p));
          }
        }
      } else if (name == "Targets") {
        if (!c.children.empty()) {
          sink_.warning(c.location,
                        "<Targets> of the root task ignored (grasp targets belong "
                        "to the sub-tasks)");
        }
      } else if (name != "Id" && name != "Index") {
        sink_.warning(c.location, c.describe() + ": element ignored");
      }
    }
    return task;
  }

 private:
  GraspSubTask parseSubTask(const XmlElement& element) {
    GraspSubTask sub;
    sub.sourceLine = element.location.line;
    for (const auto& c : element.children) {
      const auto name = detail::localName(c.name);
      if (name == "Targets") {
        for (const auto& t : c.children) {
          if (detail::localName(t.name) == "CartesianTarget") {
            sub.targets.push_back(parseTarget(t));
          } else {
            sink_.warning(t.location, t.describe() +
                                          ": target ignored (expected "
                                          "<CartesianTarget>)");
          }
        }
      } else if (name == "Id") {
        sub.taskId = std::string(rw::common::trimXmlSpace(c.text));
      } else if (name == "PropertyMap") {
        for (auto& p : readPropertyMap(c)) {
          if (p.name == "refframe") {
            sub.refframe = readString(p);
            if (sub.refframe.empty()) sub.refframe = "WORLD";
          } else if (p.name == "ObjectID") {
            sub.objectId = readString(p);
          } else if (p.name == "Offset") {
            sub.offset = readTransformProperty(p);
          } else if (p.name == "Approach") {
            sub.approach = readTransformProperty(p);
          } else if (p.name == "Retract") {
            sub.retract = readTransformProperty(p);
          } else if (p.name == "OpenQ") {
            sub.openQ = readQ(p);
          } else if (p.name == "CloseQ") {
            sub.closeQ = readQ(p);
          } else if (p.name == "TauMax") {
            sub.tauMax = readQ(p);
          } else {
            sub.otherProperties.push_back(keep(p));
          }
        }
      } else if (name == "Entities") {
        if (!c.children.empty()) sink_.warning(c.location, "nested sub-task entities ignored");
      } else if (name != "Index") {
        sink_.warning(c.location, c.describe() + ": element ignored");
      }
    }
    return sub;
  }

  GraspTarget parseTarget(const XmlElement& element) {
    GraspTarget target;
    target.sourceLine = element.location.line;
    if (!element.has("id")) {
      sink_.error(element.location, "<CartesianTarget> has no id attribute (RobWork requires one)");
    }
    bool posed = false;
    for (const auto& c : element.children) {
      const auto name = detail::localName(c.name);
      if (name == "Transform3D") {
        target.pose = readTransform(c);
        posed = true;
      } else if (name == "PropertyMap") {
        if (!c.children.empty()) target.result = readResult(c);
      } else if (name != "Id" && name != "Index") {
        sink_.warning(c.location, c.describe() + ": element ignored");
      }
    }
    if (!posed) sink_.error(element.location, element.describe() + ": missing <Transform3D>");
    return target;
  }

  GraspResult readResult(const XmlElement& map) {
    GraspResult r;
    for (auto& p : readPropertyMap(map)) {
      const std::string& n = p.name;
      if (n == "TestStatus") {
        r.testStatus = readInteger(p);
      } else if (n == "LiftResult") {
        r.liftResult = readDouble(p);
      } else if (n == "LiftStatus") {
        readInteger(p);  // derived from TestStatus when written
      } else if (n == "GripperConfiguration") {
        r.gripperConfigurationGrasp = readQ(p);
      } else if (n == "GripperConfigurationPost") {
        r.gripperConfigurationLift = readQ(p);
      } else if (n == "QualityBeforeLifting") {
        r.qualityBeforeLifting = readQ(p);
      } else if (n == "QualityAfterLifting") {
        r.qualityAfterLifting = readQ(p);
      } else if (n == "ObjectTtcptTarget") {
        r.objectTtcpTarget = readTransformProperty(p);
      } else if (n == "ObjectTtcpApproach") {
        r.objectTtcpApproach = readTransformProperty(p);
      } else if (n == "ObjectTtcpGrasp") {
        r.objectTtcpGrasp = readTransformProperty(p);
      } else if (n == "ObjectTtcpLift") {
        r.objectTtcpLift = readTransformProperty(p);
      } else if (n == "ContactsGrasp") {
        r.contactsGrasp = readContacts(p);
      } else if (n == "ContactsLift") {
        r.contactsLift = readContacts(p);
      } else if (n == "InterferenceTs") {
        r.interferenceTs = readTransformPath(p);
      } else if (n == "InterferenceDistances") {
        r.interferenceDistances = readDoubles(p, "DoubleList");
      } else if (n == "InterferenceAngles") {
        r.interferenceAngles = readDoubles(p, "DoubleList");
      } else if (n == "Interferences") {
        r.interferences = readDoubles(p, "DoubleList");
      } else if (n == "Interference") {
        r.interference = readDouble(p);
      } else {
        r.otherProperties.push_back(keep(p));
      }
    }
    return r;
  }

  std::vector<RawProperty> readPropertyMap(const XmlElement& map) {
    std::vector<RawProperty> out;
    for (const auto& c : map.children) {
      if (detail::localName(c.name) != "Property") {
        sink_.warning(c.location, c.describe() +
                                      ": ignored in <PropertyMap> (expected "
                                      "<Property>)");
        continue;
      }
      RawProperty p;
      p.element = &c;
      const XmlElement* name = detail::child(c, "Name");
      const XmlElement* value = detail::child(c, "Value");
      if (name == nullptr) {
        sink_.error(c.location, "<Property> without <Name>");
        continue;
      }
      p.name = std::string(rw::common::trimXmlSpace(name->text));
      if (const XmlElement* d = detail::child(c, "Description")) p.description = d->text;
      if (value == nullptr || value->children.size() != 1) {
        sink_.error(value ? value->location : c.location,
                    "property '" + p.name +
                        "': <Value> must hold exactly one typed element "
                        "such as <String> or <Q>");
        continue;
      }
      p.value = &value->children.front();
      const auto type = detail::localName(p.value->name);
      if (std::find(kKnownTypes.begin(), kKnownTypes.end(), type) == kKnownTypes.end()) {
        sink_.warning(p.value->location, "property '" + p.name + "': value type <" +
                                             std::string(type) +
                                             "> is unknown to RobWork; kept as written");
      }
      out.push_back(std::move(p));
    }
    return out;
  }

  bool expectType(const RawProperty& p, std::string_view type) {
    if (detail::localName(p.value->name) == type) return true;
    sink_.error(p.value->location, "property '" + p.name + "': expected a <" + std::string(type) +
                                       "> value, got <" + p.value->name + ">");
    return false;
  }

  static Property keep(const RawProperty& p) { return Property{p.name, p.description, *p.value}; }

  std::string readString(const RawProperty& p) {
    if (!expectType(p, "String")) return {};
    return std::string(rw::common::trimXmlSpace(p.value->text));
  }

  int readInteger(const RawProperty& p) {
    if (!expectType(p, "Integer")) return 0;
    const auto n = rw::common::parseInteger(p.value->text, -kLargestInteger, kLargestInteger);
    if (!n.error.empty()) {
      sink_.error(p.value->location, "property '" + p.name + "': " + n.error);
      return 0;
    }
    return static_cast<int>(n.value);
  }

  double readDouble(const RawProperty& p) {
    const auto type = detail::localName(p.value->name);
    if (type != "Float" && !expectType(p, "Double")) return 0.0;
    const auto n = rw::common::parseFiniteNumber(p.value->text);
    if (!n.error.empty()) {
      sink_.error(p.value->location, "property '" + p.name + "': " + n.error);
      return 0.0;
    }
    return n.value;
  }

  /// Numbers of `element`, scaled by its unit attribute; `count` 0 = any number.
  bool numbers(const XmlElement& element, std::size_t count, std::vector<double>& values,
               std::string_view what) {
    auto read = rw::common::XmlValueReader(sink_).textNumbers(element, count, what);
    if (!read) return false;
    values = std::move(*read);
    if (const std::string* unit = element.attribute("unit")) {
      const double factor = unitFactor(rw::common::trimXmlSpace(*unit));
      if (factor == 0.0) {
        sink_.error(element.location,
                    element.describe() + ": unknown unit \"" + *unit +
                        "\" (expected mm, cm, m, inch, deg, rad, or a velocity/acceleration unit)");
        return false;
      }
      for (double& v : values) v *= factor;
    }
    return true;
  }

  Q readQ(const RawProperty& p) {
    if (!expectType(p, "Q")) return {};
    std::vector<double> v;
    if (!numbers(*p.value, 0, v, "")) return {};
    return Eigen::Map<const Q>(v.data(), static_cast<Eigen::Index>(v.size()));
  }

  std::vector<double> readDoubles(const RawProperty& p, std::string_view type) {
    if (!expectType(p, type)) return {};
    std::vector<double> v;
    if (!numbers(*p.value, 0, v, "")) return {};
    return v;
  }

  std::vector<TaskContact> readContacts(const RawProperty& p) {
    std::vector<double> v = readDoubles(p, "DoubleList");
    if (v.size() % 9 != 0) {
      sink_.error(p.value->location, "property '" + p.name +
                                         "': expected 9 numbers per contact (p n f), got " +
                                         std::to_string(v.size()) + " numbers");
      return {};
    }
    std::vector<TaskContact> out(v.size() / 9);
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i].position = Vector3D(v[9 * i], v[9 * i + 1], v[9 * i + 2]);
      out[i].normal = Vector3D(v[9 * i + 3], v[9 * i + 4], v[9 * i + 5]);
      out[i].force = Vector3D(v[9 * i + 6], v[9 * i + 7], v[9 * i + 8]);
    }
    return out;
  }

  Transform3D readTransformProperty(const RawProperty& p) {
    if (!expectType(p, "Transform3D")) return Transform3D::Identity();
    return readTransform(*p.value);
  }

  std::vector<Transform3D> readTransformPath(const RawProperty& p) {
    std::vector<Transform3D> out;
    if (!expectType(p, "T3DPath")) return out;
    for (const auto& c : p.value->children) {
      if (detail::localName(c.name) == "Transform3D") {
        out.push_back(readTransform(c));
      } else {
        sink_.error(c.location, "property '" + p.name +
                                    "': expected <Transform3D> in <T3DPath>, "
                                    "got <" +
                                    c.name + ">");
      }
    }
    return out;
  }

  Rotation3D checkedRotation(const XmlElement& where, const Rotation3D& R) {
    if (R.determinant() <= 0) {
      sink_.error(where.location, where.describe() + ": not a rotation (determinant " +
                                      detail::formatNumber(R.determinant()) + " is not positive)");
      return Rotation3D::Identity();
    }
    if (detail::orthonormalityError(R) > 1e-6) {
      sink_.warning(where.location, where.describe() +
                                        ": rotation is not orthonormal; projected onto the "
                                        "nearest rotation (as RobWork does)");
      return detail::nearestRotation(R);
    }
    return R;
  }

  Rotation3D rowMajor(const std::vector<double>& v, std::size_t first) {
    Rotation3D R;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R(r, c) = v[first + static_cast<std::size_t>(4 * r + c)];
    }
    return R;
  }

  Rotation3D quaternionXyzw(const XmlElement& where, const std::vector<double>& v) {
    const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (norm < 1e-12) {
      sink_.error(where.location, where.describe() + ": zero quaternion");
      return Rotation3D::Identity();
    }
    return Eigen::Quaterniond(v[3] / norm, v[0] / norm, v[1] / norm, v[2] / norm)
        .toRotationMatrix();
  }

  /// All Transform3D forms of reference §3.3.
  Transform3D readTransform(const XmlElement& element) {
    std::vector<double> v;
    if (element.children.empty()) {
      if (!numbers(element, 12, v, "a 3x4 matrix, row-major")) return Transform3D::Identity();
      Rotation3D R;
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) R(r, c) = v[static_cast<std::size_t>(4 * r + c)];
      }
      return rw::math::makeTransform(checkedRotation(element, R), Vector3D(v[3], v[7], v[11]));
    }
    Transform3D X = Transform3D::Identity();
    bool rotated = false;
    for (const auto& c : element.children) {
      const auto name = detail::localName(c.name);
      if (name == "Pos") {
        if (numbers(c, 3, v, "x y z")) X.translation() = Vector3D(v[0], v[1], v[2]);
        continue;
      }
      if (name == "Matrix") {
        if (!numbers(c, 12, v, "a 3x4 matrix, row-major")) continue;
        Rotation3D R;
        for (int r = 0; r < 3; ++r) {
          for (int k = 0; k < 3; ++k) R(r, k) = v[static_cast<std::size_t>(4 * r + k)];
        }
        X = rw::math::makeTransform(checkedRotation(c, R), Vector3D(v[3], v[7], v[11]));
        rotated = true;
        continue;
      }
      Rotation3D R = Rotation3D::Identity();
      if (name == "Rotation3D") {
        auto read = rw::common::XmlValueReader(sink_).textNumbers(c);
        if (!read) continue;
        v = std::move(*read);
        if (v.size() == 9) {
          Rotation3D M;
          for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < 3; ++k) M(r, k) = v[static_cast<std::size_t>(3 * r + k)];
          }
          R = checkedRotation(c, M);
        } else if (v.size() == 4) {
          R = quaternionXyzw(c, v);
        } else {
          sink_.error(c.location, c.describe() +
                                      ": expected 9 numbers (row-major matrix) or 4 "
                                      "(quaternion x y z w), got " +
                                      std::to_string(v.size()));
          continue;
        }
      } else if (name == "RPY") {
        if (!numbers(c, 3, v, "roll pitch yaw, radians unless unit=\"deg\"")) continue;
        R = rw::math::rpyToRotation(v[0], v[1], v[2]);
      } else if (name == "EAA") {
        if (!numbers(c, 3, v, "rotation axis times angle")) continue;
        const Vector3D eaa(v[0], v[1], v[2]);
        const double angle = eaa.norm();
        if (angle > 0) R = Eigen::AngleAxisd(angle, eaa / angle).toRotationMatrix();
      } else if (name == "Quaternion") {
        if (!numbers(c, 4, v, "x y z w")) continue;
        R = quaternionXyzw(c, v);
      } else {
        sink_.warning(c.location, c.describe() +
                                      ": ignored in <Transform3D> (expected <Pos> and "
                                      "<Rotation3D>, <RPY>, <EAA> or <Quaternion>)");
        continue;
      }
      if (rotated) {
        sink_.warning(c.location, c.describe() +
                                      ": second rotation in <Transform3D>; it replaces "
                                      "the first");
      }
      X.linear() = R;
      rotated = true;
    }
    return X;
  }

  rw::common::DiagnosticSink& sink_;
};

// --- writer -------------------------------------------------------------------------------

/// A property to write: its name and the <Value> body (already indented XML).
struct OutProperty {
  std::string name;
  std::string description;
  std::string body;
};

std::string pad(int n) { return std::string(static_cast<std::size_t>(n), ' '); }

std::string transformXml(const Transform3D& X, int indent) {
  const Vector3D p = X.translation();
  std::array<double, 9> r{};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) r[static_cast<std::size_t>(3 * i + k)] = X.linear()(i, k);
  }
  return pad(indent) + "<Transform3D>\n" + pad(indent + 2) + "<Pos>" +
         detail::formatNumbers(p.data(), 3) + "</Pos>\n" + pad(indent + 2) + "<Rotation3D>" +
         detail::formatNumbers(r.data(), 9) + "</Rotation3D>\n" + pad(indent) + "</Transform3D>\n";
}

std::string simple(std::string_view type, const std::string& text, int indent) {
  return pad(indent) + "<" + std::string(type) + ">" + text + "</" + std::string(type) + ">\n";
}

std::string numbersText(const std::vector<double>& v) {
  return detail::formatNumbers(v.data(), v.size());
}

std::string qText(const Q& q) {
  return detail::formatNumbers(q.data(), static_cast<std::size_t>(q.size()));
}

std::vector<double> contactValues(const std::vector<TaskContact>& contacts) {
  std::vector<double> v;
  for (const auto& c : contacts) {
    for (const Vector3D* x : {&c.position, &c.normal, &c.force})
      v.insert(v.end(), x->data(), x->data() + 3);
  }
  return v;
}

bool isIdentity(const Transform3D& X) { return X.matrix().isIdentity(0.0); }

void writePropertyMap(std::string& out, std::vector<OutProperty> props, int indent) {
  if (props.empty()) {
    out += pad(indent) + "<PropertyMap/>\n";
    return;
  }
  std::stable_sort(props.begin(), props.end(),
                   [](const OutProperty& a, const OutProperty& b) { return a.name < b.name; });
  out += pad(indent) + "<PropertyMap>\n";
  for (const auto& p : props) {
    out += pad(indent + 2) + "<Property>\n";
    out += pad(indent + 4) + "<Name>" + rw::common::escapeXml(p.name) + "</Name>\n";
    if (!p.description.empty()) {
      out += pad(indent + 4) + "<Description>" + rw::common::escapeXml(p.description) +
             "</Description>\n";
    }
    out += pad(indent + 4) + "<Value>\n" + p.body + pad(indent + 4) + "</Value>\n";
    out += pad(indent + 2) + "</Property>\n";
  }
  out += pad(indent) + "</PropertyMap>\n";
}

void addKept(std::vector<OutProperty>& props, const std::vector<Property>& kept, int indent) {
  for (const auto& p : kept) {
    std::string body;
    detail::writeElement(body, p.value, indent);
    props.push_back({p.name, p.description, std::move(body)});
  }
}

std::vector<OutProperty> resultProperties(const GraspResult& r, int vi) {
  std::vector<OutProperty> props;
  const auto add = [&](const char* name, std::string body) {
    props.push_back({name, "", std::move(body)});
  };
  const bool held = r.testStatus == 1 || r.testStatus == 5;
  const bool lifted = held || r.testStatus == 4;
  add("TestStatus", simple("Integer", std::to_string(r.testStatus), vi));
  if (r.gripperConfigurationGrasp.size() > 0) {
    add("GripperConfiguration", simple("Q", qText(r.gripperConfigurationGrasp), vi));
  }
  if (r.gripperConfigurationLift.size() > 0) {
    add("GripperConfigurationPost", simple("Q", qText(r.gripperConfigurationLift), vi));
  }
  if (r.qualityBeforeLifting.size() > 0) {
    add("QualityBeforeLifting", simple("Q", qText(r.qualityBeforeLifting), vi));
  }
  if (r.qualityAfterLifting.size() > 0) {
    add("QualityAfterLifting", simple("Q", qText(r.qualityAfterLifting), vi));
  }
  const std::array<std::pair<const char*, const Transform3D*>, 4> transforms = {{
      {"ObjectTtcptTarget", &r.objectTtcpTarget},
      {"ObjectTtcpApproach", &r.objectTtcpApproach},
      {"ObjectTtcpGrasp", &r.objectTtcpGrasp},
      {"ObjectTtcpLift", &r.objectTtcpLift},
  }};
  for (const auto& [name, X] : transforms) {
    if (!isIdentity(*X)) add(name, transformXml(*X, vi));
  }
  if (lifted || r.liftResult != 0.0) {
    add("LiftResult", simple("Double", detail::formatNumber(r.liftResult), vi));
  }
  if (lifted) add("LiftStatus", simple("Integer", held ? "1" : "4", vi));
  if (!r.contactsGrasp.empty()) {
    add("ContactsGrasp", simple("DoubleList", numbersText(contactValues(r.contactsGrasp)), vi));
  }
  if (!r.contactsLift.empty()) {
    add("ContactsLift", simple("DoubleList", numbersText(contactValues(r.contactsLift)), vi));
  }
  std::string path;
  if (r.interferenceTs.empty()) {
    path = pad(vi) + "<T3DPath/>\n";
  } else {
    path = pad(vi) + "<T3DPath>\n";
    for (const auto& X : r.interferenceTs) path += transformXml(X, vi + 2);
    path += pad(vi) + "</T3DPath>\n";
  }
  add("InterferenceTs", path);
  add("InterferenceDistances", simple("DoubleList", numbersText(r.interferenceDistances), vi));
  add("InterferenceAngles", simple("DoubleList", numbersText(r.interferenceAngles), vi));
  add("Interferences", simple("DoubleList", numbersText(r.interferences), vi));
  add("Interference", simple("Double", detail::formatNumber(r.interference), vi));
  addKept(props, r.otherProperties, vi);
  return props;
}

}  // namespace

namespace detail {
GraspTask rwTaskFromElement(const XmlElement& root, rw::common::DiagnosticSink& sink) {
  return TaskParser(sink).parseRoot(root);
}
}  // namespace detail

GraspTask parseRwTask(std::string_view text, const std::filesystem::path& file,
                      std::vector<rw::common::Diagnostic>* warnings) {
  const auto top = detail::parseXmlOrThrow(text, file);
  rw::common::DiagnosticSink sink;
  if (top.size() != 1 || detail::localName(top.front().name) != "CartesianTask") {
    sink.error({detail::sourceFile(file), top.empty() ? 0 : top.front().location.line,
                top.empty() ? 0 : top.front().location.column},
               "expected one root element <CartesianTask> (RobWork's grasp task format)");
    throw rw::common::LoadError(sink.take());
  }
  GraspTask task = detail::rwTaskFromElement(top.front(), sink);
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  if (warnings != nullptr) {
    for (auto& d : sink.take()) warnings->push_back(std::move(d));
  }
  return task;
}

GraspTask readRwTask(const std::filesystem::path& file,
                     std::vector<rw::common::Diagnostic>* warnings) {
  return parseRwTask(detail::readFileOrThrow(file, "the grasp task"), file, warnings);
}

std::string formatRwTask(const GraspTask& task) {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\" ?>\n";
  out += "<CartesianTask>\n  <Targets/>\n  <Entities>\n";
  int targetId = 0;
  for (const auto& sub : task.subTasks) {
    out += "    <CartesianTask>\n      <Targets>\n";
    int index = 0;
    for (const auto& t : sub.targets) {
      out += "        <CartesianTarget id=\"" + std::to_string(targetId++) + "\">\n";
      out += transformXml(t.pose, 10);
      out += "          <Id></Id>\n          <Index>" + std::to_string(index++) + "</Index>\n";
      writePropertyMap(out, t.result ? resultProperties(*t.result, 16) : std::vector<OutProperty>{},
                       10);
      out += "        </CartesianTarget>\n";
    }
    out += "      </Targets>\n      <Entities/>\n      <Id>" + rw::common::escapeXml(sub.taskId) +
           "</Id>\n      <Index>0</Index>\n";
    std::vector<OutProperty> props;
    const auto add = [&](const char* name, std::string body) {
      props.push_back({name, "", std::move(body)});
    };
    add("refframe", simple("String", rw::common::escapeXml(sub.refframe), 12));
    if (!sub.objectId.empty())
      add("ObjectID", simple("String", rw::common::escapeXml(sub.objectId), 12));
    add("Offset", transformXml(sub.offset, 12));
    add("Approach", transformXml(sub.approach, 12));
    add("Retract", transformXml(sub.retract, 12));
    add("OpenQ", simple("Q", qText(sub.openQ), 12));
    add("CloseQ", simple("Q", qText(sub.closeQ), 12));
    add("TauMax", simple("Q", qText(sub.tauMax), 12));
    addKept(props, sub.otherProperties, 12);
    writePropertyMap(out, std::move(props), 6);
    out += "    </CartesianTask>\n";
  }
  out += "  </Entities>\n  <Id></Id>\n  <Index>-1</Index>\n";
  std::vector<OutProperty> props = {
      {"GraspController", "", simple("String", rw::common::escapeXml(task.graspControllerId), 8)},
      {"Gripper", "", simple("String", rw::common::escapeXml(task.gripperId), 8)},
      {"TCP", "", simple("String", rw::common::escapeXml(task.tcpId), 8)}};
  addKept(props, task.otherProperties, 8);
  writePropertyMap(out, std::move(props), 2);
  out += "</CartesianTask>\n";
  return out;
}

void writeRwTask(const GraspTask& task, const std::filesystem::path& file) {
  detail::writeFileOrThrow(file, formatRwTask(task));
}

}  // namespace visgrab::taskio
