#include "visgrab/grasp/grasp_description.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <sstream>
#include <utility>

#include "rw/common/numbers.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "visgrab/grasp/detail/grasp_description_schema.hpp"

namespace visgrab::grasp {

namespace {

using rw::common::DiagnosticSink;
using rw::common::XmlAttribute;
using rw::common::XmlElement;

constexpr std::array<std::string_view, 11> kNumberAttributes{"value",
                                                             "atLeast",
                                                             "below",
                                                             "gain",
                                                             "floor",
                                                             "backoff",
                                                             "maxPositionError",
                                                             "maxDirectionError",
                                                             "maxApproachError",
                                                             "directionWeight",
                                                             "approachWeight"};
constexpr std::array<std::string_view, 8> kListAttributes{
    "qOpen", "qClosed", "tauMax", "base", "q", "approachAxis", "point", "normal"};
constexpr std::array<std::string_view, 3> kVector3Attributes{"approachAxis", "point", "normal"};

template <std::size_t N>
bool contains(const std::array<std::string_view, N>& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// A precise message for a schema datatype error (which attribute is not a number).
std::string explainValueError(const XmlElement& element) {
  for (const XmlAttribute& a : element.attributes) {
    if (contains(kNumberAttributes, a.name)) {
      const rw::common::ParsedNumber n = rw::common::parseFiniteNumber(a.value);
      if (!n.error.empty()) return "attribute " + a.name + ": " + n.error;
    }
    if (contains(kListAttributes, a.name)) {
      std::vector<double> values;
      const std::string error = rw::common::parseNumberList(a.value, values);
      if (!error.empty()) return "attribute " + a.name + ": " + error;
      if (contains(kVector3Attributes, a.name) && values.size() != 3) {
        return "attribute " + a.name + ": expected 3 numbers (x y z), got " +
               std::to_string(values.size());
      }
    }
  }
  return {};
}

std::vector<double> numbers(const XmlElement& e, std::string_view name) {
  std::vector<double> values;
  if (const std::string* v = e.attribute(name)) rw::common::parseNumberList(*v, values);
  return values;
}

double number(const XmlElement& e, std::string_view name) {
  const std::string* v = e.attribute(name);
  return v == nullptr ? 0.0 : rw::common::parseFiniteNumber(*v).value;
}

std::optional<double> optionalNumber(const XmlElement& e, std::string_view name) {
  const std::string* v = e.attribute(name);
  if (v == nullptr) return std::nullopt;
  return rw::common::parseFiniteNumber(*v).value;
}

rw::math::Vector3D vector3(const XmlElement& e, std::string_view name) {
  const std::vector<double> v = numbers(e, name);
  if (v.size() != 3) return rw::math::Vector3D::Zero();  // the schema rejects this
  return {v[0], v[1], v[2]};
}

std::vector<std::string> names(const XmlElement& e, std::string_view name) {
  std::vector<std::string> out;
  std::istringstream in(e.attributeOr(name, ""));
  std::string word;
  while (in >> word) out.push_back(word);
  return out;
}

std::vector<CloseOffsetSpec> readClosing(const XmlElement& closing) {
  std::vector<CloseOffsetSpec> out;
  for (const XmlElement& o : closing.children) {
    out.push_back({o.attributeOr("joint", ""), number(o, "value"), o.location});
  }
  return out;
}

TauRuleSpec readTauRule(const XmlElement& e) {
  TauRuleSpec rule{numbers(e, "base"), {}, e.location};
  for (const XmlElement& a : e.children) {
    TauAdjustSpec adjust;
    adjust.angleJoint = a.attributeOr("angleJoint", "");
    adjust.atLeastDeg = optionalNumber(a, "atLeast");
    adjust.belowDeg = optionalNumber(a, "below");
    adjust.joints = names(a, "joints");
    adjust.source = a.attributeOr("source", "");
    adjust.gain = number(a, "gain");
    const std::string function = a.attributeOr("function", "one");
    adjust.function = function == "cos"      ? TauFunction::kCos
                      : function == "secant" ? TauFunction::kSecant
                                             : TauFunction::kOne;
    adjust.floor = optionalNumber(a, "floor").value_or(0.0);
    adjust.where = a.location;
    rule.adjust.push_back(std::move(adjust));
  }
  return rule;
}

IkGraspSpec readIkGrasp(const XmlElement& e) {
  IkGraspSpec g;
  g.contacts = static_cast<int>(number(e, "contacts"));
  g.fingers = names(e, "fingers");
  g.joints = names(e, "joints");
  g.where = e.location;
  for (const XmlElement& c : e.children) {
    if (c.name == "Seed") g.seeds.push_back(numbers(c, "q"));
    if (c.name == "Closing") g.closing = readClosing(c);
  }
  return g;
}

ContactIkSpec readContactIk(const XmlElement& e) {
  ContactIkSpec ik;
  ik.backoff = number(e, "backoff");
  ik.maxPositionError = number(e, "maxPositionError");
  ik.maxDirectionErrorDeg = number(e, "maxDirectionError");
  ik.maxApproachErrorDeg = number(e, "maxApproachError");
  ik.directionWeight = number(e, "directionWeight");
  ik.approachWeight = number(e, "approachWeight");
  ik.approachAxis = vector3(e, "approachAxis");
  ik.where = e.location;
  for (const XmlElement& c : e.children) {
    if (c.name == "Fingertip") {
      ik.fingertips.push_back({c.attributeOr("name", ""), c.attributeOr("frame", ""),
                               vector3(c, "point"), vector3(c, "normal"), c.location});
    } else if (c.name == "Grasp") {
      ik.grasps.push_back(readIkGrasp(c));
    }
  }
  return ik;
}

GraspDescription readRoot(const XmlElement& root, const std::string& file) {
  GraspDescription d;
  d.file = file;
  d.workcell = root.attributeOr("workcell", "");
  d.dynamics = root.attributeOr("dynamics", "");
  d.device = root.attributeOr("device", "");
  d.controller = root.attributeOr("controller", "");
  d.tcp = root.attributeOr("tcp", "");
  d.where = root.location;
  for (const XmlElement& c : root.children) {
    if (c.name == "PreShape") {
      PreShapeSpec p;
      p.name = c.attributeOr("name", "");
      p.aliases = names(c, "aliases");
      p.qOpen = numbers(c, "qOpen");
      p.qClosed = numbers(c, "qClosed");
      if (c.has("tauMax")) p.tauMax = numbers(c, "tauMax");
      p.tcp = c.attributeOr("tcp", "");
      p.where = c.location;
      d.preshapes.push_back(std::move(p));
    } else if (c.name == "Closing") {
      d.closing = readClosing(c);
    } else if (c.name == "TauMax") {
      d.tauRule = readTauRule(c);
    } else if (c.name == "ContactIK") {
      d.contactIk = readContactIk(c);
    }
  }
  return d;
}

}  // namespace

std::optional<GraspDescription> parseGraspDescription(std::string_view text,
                                                      const std::filesystem::path& file,
                                                      DiagnosticSink& sink) {
  auto source = std::make_shared<rw::common::SourceFile>(
      rw::common::SourceFile{file.lexically_normal().string(), {}});
  rw::common::XmlReader reader(rw::common::XmlReaderOptions{
      std::string(detail::graspDescriptionSchema()), explainValueError});
  const auto elements = reader.parse(text, source, sink);
  if (!elements || sink.hasErrors()) return std::nullopt;
  if (elements->size() != 1 || elements->front().name != "GraspDescription") {
    sink.error(rw::common::SourceLocation{source, 1, 1}, "expected one <GraspDescription> element");
    return std::nullopt;
  }
  return readRoot(elements->front(), source->displayPath);
}

}  // namespace visgrab::grasp
