#include "rw/loaders/detail/wc_elements.hpp"

#include <Eigen/SVD>

#include <array>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <span>
#include <sstream>
#include <utility>
#include <vector>

#include "rw/common/numbers.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/math/dh.hpp"
#include "rw/math/rpy.hpp"

namespace rw::loaders::detail {

using rw::geometry::GeometryType;
using rw::kinematics::FrameType;
using rw::math::kDeg2Rad;
using rw::math::Transform3D;

namespace {

// A rotation part further than this from orthonormal is reported (it is made orthonormal).
constexpr double kRotationTolerance = 1e-4;

std::string formatNumber(double value) {
  std::ostringstream os;
  os << std::setprecision(10) << value;
  return os.str();
}

// The nearest rotation to R (by SVD), with the largest entry-wise correction made.
std::pair<rw::math::Rotation3D, double> nearestRotation(const rw::math::Rotation3D& R) {
  const Eigen::JacobiSVD<rw::math::Rotation3D> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const rw::math::Rotation3D nearest = svd.matrixU() * svd.matrixV().transpose();
  return {nearest, (nearest - R).cwiseAbs().maxCoeff()};
}

std::optional<Transform3D> matrixTransform(const common::XmlElement& matrix,
                                           common::DiagnosticSink& sink) {
  const auto v = common::XmlValueReader(sink).textNumbers(matrix, 12);
  if (!v) return std::nullopt;
  rw::math::Rotation3D R;
  R << (*v)[0], (*v)[1], (*v)[2], (*v)[4], (*v)[5], (*v)[6], (*v)[8], (*v)[9], (*v)[10];
  if (!(R.determinant() > 0.0)) {
    sink.error(matrix.location, matrix.describe() +
                                    ": the 3x3 part is not a rotation (its determinant is " +
                                    formatNumber(R.determinant()) + ")");
    return std::nullopt;
  }
  const auto [nearest, correction] = nearestRotation(R);
  if (correction > kRotationTolerance) {
    sink.warning(matrix.location, matrix.describe() +
                                      ": the 3x3 part is not orthonormal (off by up to " +
                                      formatNumber(correction) + "); the nearest rotation is used");
  }
  return rw::math::makeTransform(nearest, rw::math::Vector3D((*v)[3], (*v)[7], (*v)[11]));
}

// Checks a primitive size: > 0 (or >= 0 when zero is allowed).
bool checkSize(const common::XmlElement& element, std::string_view name, double value,
               bool allowZero, common::DiagnosticSink& sink) {
  if (value > 0.0 || (allowZero && value == 0.0)) return true;
  sink.error(element.location, element.describe() + ": " + std::string(name) + " must be " +
                                   (allowZero ? ">= 0" : "> 0") + " (got " + formatNumber(value) +
                                   ")");
  return false;
}

struct PrimitiveRule {
  std::string_view element;
  GeometryType type;
  std::array<std::string_view, 3> attributes;
  int count;
  int zeroAllowedIndex;  // parameter that may be 0 (Tube radius), -1 for none
};

constexpr std::array<PrimitiveRule, 6> kPrimitives{{
    {"Box", GeometryType::kBox, {"x", "y", "z"}, 3, -1},
    {"Sphere", GeometryType::kSphere, {"radius", "", ""}, 1, -1},
    {"Cylinder", GeometryType::kCylinder, {"radius", "z", ""}, 2, -1},
    {"Tube", GeometryType::kTube, {"radius", "thickness", "z"}, 3, 0},
    {"Cone", GeometryType::kCone, {"radius", "z", ""}, 2, -1},
    {"Plane", GeometryType::kPlane, {"", "", ""}, 0, -1},
}};

// Typed attributes of each element, for explainWorkCellValueError.
struct ElementRules {
  std::string_view element;
  std::span<const common::AttributeRule> rules;
};

using common::ValueKind;
constexpr std::array<std::string_view, 2> kColModels{"Enabled", "Disabled"};
constexpr std::array<common::AttributeRule, 7> kDhRules{
    {{"alpha"}, {"a"}, {"d"}, {"theta"}, {"b"}, {"beta"}, {"offset"}}};
constexpr std::array<common::AttributeRule, 3> kXyzRules{{{"x"}, {"y"}, {"z"}}};
constexpr std::array<common::AttributeRule, 3> kTubeRules{{{"radius"}, {"thickness"}, {"z"}}};
constexpr std::array<common::AttributeRule, 2> kRadiusZRules{{{"radius"}, {"z"}}};
constexpr std::array<common::AttributeRule, 2> kMinMaxRules{{{"min"}, {"max"}}};
constexpr std::array<common::AttributeRule, 1> kMaxRules{{{"max"}}};
constexpr std::array<common::AttributeRule, 2> kDependRules{{{"gain"}, {"offset"}}};
// Attributes that any element may carry.
constexpr std::array<common::AttributeRule, 2> kAnyElementRules{{
    {"daf", ValueKind::kBoolean},
    {"colmodel", ValueKind::kChoice, 0, {}, 0, 0, kColModels},
}};

constexpr std::array<ElementRules, 10> kElementRules{{
    {"Box", kXyzRules},
    {"Sphere", std::span(kRadiusZRules).first(1)},
    {"Cylinder", kRadiusZRules},
    {"Tube", kTubeRules},
    {"Cone", kRadiusZRules},
    {"PosLimit", kMinMaxRules},
    {"VelLimit", kMaxRules},
    {"AccLimit", kMaxRules},
    {"Depend", kDependRules},
    {"DHJoint", kDhRules},
}};

}  // namespace

Origin originOf(const common::XmlElement& element) {
  return Origin{element.location, element.describe()};
}

bool TransformReader::take(const common::XmlElement& owner, const common::XmlElement& child,
                           common::DiagnosticSink& sink) {
  const common::XmlElement** slot = nullptr;
  if (child.name == "RPY") slot = &rpy_;
  if (child.name == "Pos") slot = &pos_;
  if (child.name == "Transform") slot = &matrix_;
  if (slot == nullptr) return false;
  if (*slot != nullptr) {
    sink.error(child.location, owner.describe() + ": more than one <" + child.name + ">");
  } else if (child.name == "Transform" ? (rpy_ != nullptr || pos_ != nullptr)
                                       : matrix_ != nullptr) {
    sink.error(child.location, owner.describe() +
                                   ": give either <Transform> or <RPY> and <Pos>, "
                                   "not both");
  } else {
    *slot = &child;
  }
  return true;
}

std::optional<Transform3D> TransformReader::finish(const common::XmlElement& owner,
                                                   common::DiagnosticSink& sink) const {
  if (matrix_ != nullptr) return matrixTransform(*matrix_, sink);
  if (rpy_ == nullptr && pos_ == nullptr) return Transform3D::Identity();
  if (rpy_ == nullptr || pos_ == nullptr) {
    const common::XmlElement& lone = rpy_ != nullptr ? *rpy_ : *pos_;
    const char* other = rpy_ != nullptr ? "<Pos>" : "<RPY>";
    sink.error(lone.location, owner.describe() + ": <" + lone.name + "> without " + other +
                                  " (RobWork reads RPY and Pos only as a pair)");
    return std::nullopt;
  }
  const common::XmlValueReader read(sink);
  const auto rpy = read.textNumbers(*rpy_, 3);
  const auto pos = read.textNumbers(*pos_, 3);
  if (!rpy || !pos) return std::nullopt;
  const rw::math::Vector3D angles((*rpy)[0] * kDeg2Rad, (*rpy)[1] * kDeg2Rad, (*rpy)[2] * kDeg2Rad);
  return rw::math::rpyTransform(angles, rw::math::Vector3D((*pos)[0], (*pos)[1], (*pos)[2]));
}

bool isGeometryElement(std::string_view name) {
  for (const PrimitiveRule& r : kPrimitives) {
    if (r.element == name) return true;
  }
  return name == "Custom" || name == "Polytope";
}

std::optional<GeometryDesc> readGeometry(const common::XmlElement& element,
                                         common::DiagnosticSink& sink) {
  GeometryDesc g;
  g.origin = originOf(element);
  if (element.name == "Polytope") {
    g.type = GeometryType::kMesh;
    g.meshName = element.attributeOr("file", "");
    g.baseDir = std::filesystem::path(element.location.file ? element.location.file->displayPath
                                                            : std::string())
                    .parent_path()
                    .string();
    return g;
  }
  if (element.name == "Custom") {
    // RobWork looks Custom primitives up by type; this project knows one, the Frustum.
    const std::string type = element.attributeOr("type", "");
    if (type != "Frustum") {
      sink.error(element.location, element.describe() + ": unknown Custom geometry type \"" + type +
                                       "\"; this project knows \"Frustum\"");
      return std::nullopt;
    }
    const std::string problem =
        common::parseNumberList(element.attributeOr("param", ""), g.parameters);
    if (!problem.empty() || g.parameters.size() != 3) {
      sink.error(element.location,
                 element.describe() +
                     ": param must be three numbers: bottom radius, top radius, height" +
                     (problem.empty() ? " (got " + std::to_string(g.parameters.size()) + ")"
                                      : " (" + problem + ")"));
      return std::nullopt;
    }
    g.type = GeometryType::kFrustum;
    return g;
  }
  for (const PrimitiveRule& rule : kPrimitives) {
    if (rule.element != element.name) continue;
    g.type = rule.type;
    bool ok = true;
    for (int i = 0; i < rule.count; ++i) {
      const auto name = rule.attributes[static_cast<std::size_t>(i)];
      const auto v = common::XmlValueReader(sink).number(element, name);
      ok = ok && v && checkSize(element, name, *v, i == rule.zeroAllowedIndex, sink);
      g.parameters.push_back(v.value_or(0.0));
    }
    if (!ok) return std::nullopt;
    return g;
  }
  sink.error(element.location, "unknown geometry element <" + element.name + ">");
  return std::nullopt;
}

std::optional<PropertyDesc> readProperty(const common::XmlElement& element,
                                         common::DiagnosticSink& sink) {
  PropertyDesc p;
  p.origin = originOf(element);
  p.name = element.attributeOr("name", "");
  p.property.description = element.attributeOr("desc", "");
  const std::string type = element.attributeOr("type", "string");
  if (type == "string") {
    p.property.value = element.text;
  } else if (type == "double") {
    const common::ParsedNumber n = common::parseFiniteNumber(element.text);
    if (!n.error.empty()) {
      sink.error(element.location, element.describe() + ": type double: " + n.error);
      return std::nullopt;
    }
    p.property.value = n.value;
  } else if (type == "Q") {
    std::vector<double> values;
    const std::string problem = common::parseNumberList(element.text, values);
    if (!problem.empty()) {
      sink.error(element.location, element.describe() + ": type Q: " + problem);
      return std::nullopt;
    }
    p.property.value =
        Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  } else {
    sink.warning(element.location, element.describe() + ": type \"" + type +
                                       "\" is not supported (string, double or Q); the property "
                                       "is dropped, as RobWork drops it");
    return std::nullopt;
  }
  return p;
}

std::optional<LimitDesc> readLimit(const common::XmlElement& element, const std::string& owner,
                                   common::DiagnosticSink& sink) {
  LimitDesc limit;
  limit.origin = originOf(element);
  const std::string prefix =
      owner.empty() ? element.describe() : owner + ": <" + element.name + ">";
  if (element.name == "PosLimit") {
    limit.kind = LimitKind::kPosition;
    const auto v = common::XmlValueReader(sink).numbers(element, {"min", "max"});
    if (!v) return std::nullopt;
    limit.min = (*v)[0];
    limit.max = (*v)[1];
    if (limit.min > limit.max) {
      sink.error(element.location,
                 prefix + " min " + formatNumber(limit.min) + " > max " + formatNumber(limit.max));
      return std::nullopt;
    }
    return limit;
  }
  limit.kind = element.name == "VelLimit" ? LimitKind::kVelocity : LimitKind::kAcceleration;
  const auto v = common::XmlValueReader(sink).number(element, "max");
  if (!v) return std::nullopt;
  limit.max = *v;
  if (limit.max < 0.0) {
    sink.error(element.location,
               prefix + " max must be >= 0 (got " + formatNumber(limit.max) + ")");
    return std::nullopt;
  }
  return limit;
}

std::optional<DependDesc> readDepend(const common::XmlElement& element,
                                     common::DiagnosticSink& sink) {
  DependDesc d;
  d.origin = originOf(element);
  d.on = element.attributeOr("on", "");
  const auto v = common::XmlValueReader(sink).numbers(element, {"gain", "offset"});
  if (!v) return std::nullopt;
  d.gain = (*v)[0];
  d.offset = (*v)[1];
  return d;
}

std::optional<QDesc> readQ(const common::XmlElement& element, common::DiagnosticSink& sink) {
  QDesc q;
  q.origin = originOf(element);
  q.name = element.attributeOr("name", "");
  auto values = common::XmlValueReader(sink).textNumbers(element);
  if (!values) return std::nullopt;
  q.values = std::move(*values);
  return q;
}

std::optional<FrameKind> readFrameType(const common::XmlElement& element, const std::string& value,
                                       common::DiagnosticSink& sink) {
  if (value == "Fixed") return FrameKind{FrameType::kFixed, false};
  if (value == "Movable") return FrameKind{FrameType::kMovable, false};
  if (value == "EndEffector") return FrameKind{FrameType::kFixed, true};
  if (value == "Revolute") return FrameKind{FrameType::kRevolute, false};
  if (value == "Prismatic") return FrameKind{FrameType::kPrismatic, false};
  if (value == "Spherical" || value == "Universal" || value == "PrismaticSpherical" ||
      value == "PrismaticUniversal") {
    sink.error(element.location, element.describe() + ": joint type \"" + value +
                                     "\" is not supported by this project (supported: Revolute, "
                                     "Prismatic)");
    return std::nullopt;
  }
  sink.error(element.location, element.describe() + ": unknown type \"" + value +
                                   "\"; expected one of Fixed, Movable, EndEffector, Revolute, "
                                   "Prismatic");
  return std::nullopt;
}

// RobWork keeps the DH parameters in a parser member that is never reset, so an omitted `type`
// (or the HGP "parallel" flag of a b/beta joint) carries over to the next DHJoint (reference
// Appendix A.16). That is a bug, not a format rule: here every DHJoint stands on its own, with
// craig as the default type.
std::optional<DhPlacement> readDhJoint(const common::XmlElement& element,
                                       common::DiagnosticSink& sink) {
  int forms = 0;
  std::string form;
  for (const char* name : {"d", "theta", "b", "beta"}) {
    if (element.has(name)) {
      ++forms;
      form = name;
    }
  }
  if (forms != 1) {
    sink.error(element.location, element.describe() +
                                     ": needs exactly one of the attributes d "
                                     "(revolute), theta (prismatic), b or beta "
                                     "(HGP parallel)");
    return std::nullopt;
  }
  const bool hgpForm = form == "b" || form == "beta";
  const std::string type = element.attributeOr("type", hgpForm ? "HGP" : "craig");
  if (type != "craig" && type != "schilling" && type != "HGP") {
    sink.error(element.location, element.describe() + ": unknown DH type \"" + type +
                                     "\"; expected craig, schilling or HGP");
    return std::nullopt;
  }
  if (hgpForm && type != "HGP") {
    sink.error(element.location, element.describe() + ": the " + form +
                                     " parameter belongs to the HGP parallel convention, but "
                                     "type is \"" +
                                     type + "\"");
    return std::nullopt;
  }
  const auto v = common::XmlValueReader(sink).numbers(element, {"alpha", "a", form, "offset"});
  if (!v) return std::nullopt;
  const double alpha = (*v)[0] * kDeg2Rad;
  const double a = (*v)[1];
  const double p = (*v)[2];
  const double offset = (*v)[3];
  DhPlacement dh;
  if (form == "d") {
    dh.type = FrameType::kRevolute;
    dh.transform = type == "craig" ? rw::math::craigDH(alpha, a, p, offset * kDeg2Rad)
                                   : rw::math::schillingDH(alpha, a, p, offset * kDeg2Rad);
  } else if (form == "theta") {
    dh.type = FrameType::kPrismatic;
    dh.transform = type == "craig" ? rw::math::craigDH(alpha, a, offset, p * kDeg2Rad)
                                   : rw::math::schillingDH(alpha, a, offset, p * kDeg2Rad);
  } else if (form == "b") {
    dh.type = FrameType::kRevolute;
    dh.transform = rw::math::hgpDH(alpha, a, offset * kDeg2Rad, p);
  } else {
    dh.type = FrameType::kPrismatic;
    dh.transform = rw::math::hgpDH(alpha, a, p * kDeg2Rad, offset);
  }
  return dh;
}

std::string explainWorkCellValueError(const common::XmlElement& element) {
  for (const ElementRules& rules : kElementRules) {
    if (rules.element != element.name) continue;
    std::string problem = common::explainAttributeValues(element, rules.rules);
    if (!problem.empty()) return problem;
  }
  if (element.name == "RPY" || element.name == "Pos" || element.name == "Transform" ||
      element.name == "Q") {
    std::vector<double> values;
    return common::parseNumberList(element.text, values);
  }
  return common::explainAttributeValues(element, kAnyElementRules);
}

}  // namespace rw::loaders::detail
