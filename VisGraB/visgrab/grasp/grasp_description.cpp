#include "visgrab/grasp/grasp_description.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <sstream>
#include <utility>

#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "visgrab/grasp/detail/grasp_description_schema.hpp"

namespace visgrab::grasp {

namespace {

using rw::common::DiagnosticSink;
using rw::common::XmlAttribute;
using rw::common::XmlElement;

using rw::common::AttributeRule;
using rw::common::ValueKind;

// Typed attributes, for a precise message on a schema datatype error.
constexpr std::array<AttributeRule, 24> kValueRules{{
    {"value"},
    {"atLeast"},
    {"below"},
    {"gain"},
    {"floor"},
    {"backoff"},
    {"maxPositionError"},
    {"maxDirectionError"},
    {"maxApproachError"},
    {"directionWeight"},
    {"approachWeight"},
    {"qOpen", ValueKind::kNumbers},
    {"qClosed", ValueKind::kNumbers},
    {"tauMax", ValueKind::kNumbers},
    {"base", ValueKind::kNumbers},
    {"q", ValueKind::kNumbers},
    {"approachAxis", ValueKind::kNumbers, 3, "x y z"},
    {"point", ValueKind::kNumbers, 3, "x y z"},
    {"normal", ValueKind::kNumbers, 3, "x y z"},
    {"position", ValueKind::kNumbers, 3, "x y z"},
    {"approach", ValueKind::kNumbers, 3, "x y z"},
    {"closing", ValueKind::kNumbers, 3, "x y z"},
    {"stroke"},
    {"tipDepth"},
}};

std::string explainValueError(const XmlElement& element) {
  return rw::common::explainAttributeValues(element, kValueRules);
}

// The semantic pass over the validated tree (the schema guarantees the attributes' formats).
class DescriptionReader {
 public:
  explicit DescriptionReader(DiagnosticSink& sink) : read_(sink) {}

  GraspDescription readRoot(const XmlElement& root, const std::string& file) const;

 private:
  std::vector<double> numbers(const XmlElement& e, std::string_view name) const {
    return read_.optionalNumberList(e, name).value_or(std::vector<double>{});
  }

  double number(const XmlElement& e, std::string_view name) const {
    return read_.optionalNumber(e, name).value_or(0.0);
  }

  std::optional<double> optionalNumber(const XmlElement& e, std::string_view name) const {
    return read_.optionalNumber(e, name);
  }

  rw::math::Vector3D vector3(const XmlElement& e, std::string_view name) const {
    const auto v = read_.optionalNumberList(e, name, 3, "x y z");
    if (!v) return rw::math::Vector3D::Zero();
    return {(*v)[0], (*v)[1], (*v)[2]};
  }

  static std::vector<std::string> names(const XmlElement& e, std::string_view name) {
    std::vector<std::string> out;
    std::istringstream in(e.attributeOr(name, ""));
    std::string word;
    while (in >> word) out.push_back(word);
    return out;
  }

  std::vector<CloseOffsetSpec> readClosing(const XmlElement& closing) const {
    std::vector<CloseOffsetSpec> out;
    for (const XmlElement& o : closing.children) {
      out.push_back({o.attributeOr("joint", ""), number(o, "value"), o.location});
    }
    return out;
  }

  TauRuleSpec readTauRule(const XmlElement& e) const {
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

  IkGraspSpec readIkGrasp(const XmlElement& e) const {
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

  ContactIkSpec readContactIk(const XmlElement& e) const {
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

  JawFrameSpec readJawFrame(const XmlElement& e) const {
    JawFrameSpec jaw;
    jaw.preshape = e.attributeOr("preshape", "");
    jaw.frame = e.attributeOr("frame", "");
    jaw.position = vector3(e, "position");
    if (e.has("approach")) jaw.approach = vector3(e, "approach");
    if (e.has("closing")) jaw.closing = vector3(e, "closing");
    jaw.stroke = number(e, "stroke");
    jaw.tipDepth = number(e, "tipDepth");
    jaw.where = e.location;
    return jaw;
  }

  rw::common::XmlValueReader read_;
};

GraspDescription DescriptionReader::readRoot(const XmlElement& root,
                                             const std::string& file) const {
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
    } else if (c.name == "JawFrame") {
      d.jawFrame = readJawFrame(c);
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
  GraspDescription description =
      DescriptionReader(sink).readRoot(elements->front(), source->displayPath);
  if (sink.hasErrors()) return std::nullopt;
  return description;
}

}  // namespace visgrab::grasp
