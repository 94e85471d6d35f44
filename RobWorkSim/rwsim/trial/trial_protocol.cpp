#include "rwsim/trial/trial_protocol.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "rw/common/diagnostic.hpp"
#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "rwsim/control/ramp_trajectory.hpp"

namespace rwsim::trial {

namespace {

using rw::common::DiagnosticSink;
using rw::common::XmlElement;
using rw::math::Vector3D;

constexpr std::array<std::string_view, 3> kFrames{"world", "tcp", "jaw"};
constexpr std::array<std::string_view, 2> kClosingRules{"rest", "force"};
constexpr std::array<std::string_view, 2> kMotions{"translation", "rotation"};
constexpr std::array<std::string_view, 2> kSuccessRules{"hand-contact", "two-fingers"};

// Typed attributes, for a precise message on a schema datatype error.
const std::array<rw::common::AttributeRule, 16> kValueRules{{
    {"enabled", rw::common::ValueKind::kBoolean},
    {"force"},
    {"angularSpeed"},
    {"height"},
    {"speed"},
    {"acceleration"},
    {"settle"},
    {"amplitude"},
    {"frequency"},
    {"distance"},
    {"cycles"},
    {"axis", rw::common::ValueKind::kNumbers, 3, "x y z"},
    {"direction", rw::common::ValueKind::kNumbers, 3, "x y z"},
    {"frame", rw::common::ValueKind::kChoice, 0, {}, 0, 0, kFrames},
    {"rule", rw::common::ValueKind::kChoice, 0, {}, 0, 0, kClosingRules},
    {"motion", rw::common::ValueKind::kChoice, 0, {}, 0, 0, kMotions},
}};

std::string explainValueError(const XmlElement& element) {
  if (element.name == "Success") {
    static const std::array<rw::common::AttributeRule, 1> kSuccess{
        {{"rule", rw::common::ValueKind::kChoice, 0, {}, 0, 0, kSuccessRules}}};
    return rw::common::explainAttributeValues(element, kSuccess);
  }
  return rw::common::explainAttributeValues(element, kValueRules);
}

// Shortest text that reads back as `value`.
std::string number(double value) {
  std::array<char, 32> text{};
  const auto result = std::to_chars(text.data(), text.data() + text.size(), value);
  return std::string(text.data(), result.ptr);
}

std::string vector(const Vector3D& v) {
  return number(v.x()) + " " + number(v.y()) + " " + number(v.z());
}

std::string frameName(AxisFrame f) { return std::string(kFrames[static_cast<std::size_t>(f)]); }

// Reads one attribute that must be > 0 (or >= 0 with `zeroAllowed`); keeps `value` when absent
// and optional.
void readPositive(const rw::common::XmlValueReader& read, const XmlElement& e,
                  std::string_view name, bool required, bool zeroAllowed, double& value) {
  const auto v = required ? read.number(e, name) : read.optionalNumber(e, name);
  if (!v) return;
  if (zeroAllowed ? !(*v >= 0.0) : !(*v > 0.0)) {
    read.error(e, "attribute " + std::string(name) + ": expected a number " +
                      (zeroAllowed ? ">= 0" : "> 0") + ", got " + number(*v));
    return;
  }
  value = *v;
}

std::optional<Vector3D> readAxis(const rw::common::XmlValueReader& read, const XmlElement& e,
                                 std::string_view name) {
  const auto v = read.vector3(e, name, "x y z");
  if (!v) return std::nullopt;
  const Vector3D axis((*v)[0], (*v)[1], (*v)[2]);
  if (!(axis.norm() > 1e-9)) {
    read.error(
        e, "attribute " + std::string(name) + ": expected a non-zero vector, got " + vector(axis));
    return std::nullopt;
  }
  return axis.normalized();
}

ProtocolPhase readPhase(const rw::common::XmlValueReader& read, const XmlElement& e) {
  ProtocolPhase p;
  if (e.name == "Lift") {
    p.kind = PhaseKind::kLift;
    readPositive(read, e, "height", true, false, p.distance);
  } else if (e.name == "Pull") {
    p.kind = PhaseKind::kPull;
    if (const auto f = read.choice(e, "frame", kFrames)) p.frame = static_cast<AxisFrame>(*f);
    if (const auto axis = readAxis(read, e, "direction")) p.axis = *axis;
    readPositive(read, e, "distance", true, false, p.distance);
  } else {
    p.kind = PhaseKind::kShake;
    p.settle = 0.0;
    if (const auto m = read.choice(e, "motion", kMotions)) p.rotation = *m == 1;
    if (const auto f = read.choice(e, "frame", kFrames)) p.frame = static_cast<AxisFrame>(*f);
    if (const auto axis = readAxis(read, e, "axis")) p.axis = *axis;
    readPositive(read, e, "amplitude", true, false, p.amplitude);
    readPositive(read, e, "frequency", true, false, p.frequency);
    readPositive(read, e, "cycles", true, false, p.cycles);
    if (p.cycles * 2.0 != std::round(p.cycles * 2.0)) {
      read.error(e, "attribute cycles: expected a whole or half number of periods, got " +
                        number(p.cycles));
    }
  }
  if (p.kind != PhaseKind::kShake) {
    readPositive(read, e, "speed", false, false, p.speed);
    readPositive(read, e, "acceleration", false, false, p.acceleration);
  }
  readPositive(read, e, "settle", false, true, p.settle);
  return p;
}

// The semantic pass over the validated tree.
TrialProtocol readProtocol(const XmlElement& root, DiagnosticSink& sink) {
  const rw::common::XmlValueReader read(sink);
  TrialProtocol protocol;
  if (const auto* name = read.required(root, "name")) {
    protocol.name = *name;
    if (protocol.name.empty()) read.error(root, "attribute name: expected a name, got \"\"");
  }
  for (const XmlElement& part : root.children) {
    if (part.name == "Gravity") {
      const auto* text = read.required(part, "enabled");
      if (text) protocol.gravity = rw::common::parseBoolean(*text).value_or(true);
    } else if (part.name == "Closing") {
      const auto rule = read.choice(part, "rule", kClosingRules);
      if (rule && *rule == 1) {
        protocol.closing = ClosingRule::kForceThreshold;
        readPositive(read, part, "force", true, false, protocol.gripForce);
      } else if (rule && part.has("force")) {
        read.error(part, "attribute force: only rule=\"force\" takes a force");
      }
      readPositive(read, part, "speed", false, false, protocol.closingSpeed);
      readPositive(read, part, "angularSpeed", false, false, protocol.closingAngularSpeed);
    } else if (part.name == "Phases") {
      protocol.phases.clear();
      for (const XmlElement& phase : part.children)
        protocol.phases.push_back(readPhase(read, phase));
    } else if (part.name == "Success") {
      if (const auto rule = read.choice(part, "rule", kSuccessRules)) {
        protocol.success = static_cast<SuccessRule>(*rule);
      }
    }
  }
  return protocol;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("trial protocol: " + what);
}

}  // namespace

bool TrialProtocol::isLift() const {
  TrialProtocol named = *this;
  named.name = "lift";
  return named == TrialProtocol::lift();
}

bool TrialProtocol::usesJawFrame() const {
  return std::any_of(phases.begin(), phases.end(),
                     [](const ProtocolPhase& p) { return p.frame == AxisFrame::kJaw; });
}

void TrialProtocol::requireJawFrame(bool handHasJawFrame, const std::string& hand) const {
  if (handHasJawFrame || !usesJawFrame()) return;
  throw std::invalid_argument(
      "the protocol \"" + name + "\" gives an axis in the jaw frame, but " + hand +
      " declares no jaw frame (<JawFrame> in its grasp description, docs/grasp-utilities.md): "
      "give a hand description that declares one (as every hand in scenes/hands does) or a "
      "protocol whose axes are in frame \"tcp\" or \"world\"");
}

void checkProtocol(const TrialProtocol& protocol) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto nonNegative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  require(!protocol.phases.empty(), "no phase after closing");
  require(protocol.closing == ClosingRule::kRest || positive(protocol.gripForce),
          "the closing force threshold must be a finite number > 0 N, not " +
              number(protocol.gripForce));
  require(nonNegative(protocol.closingSpeed),
          "the closing speed must be >= 0 m/s (0: no cap), not " + number(protocol.closingSpeed));
  require(nonNegative(protocol.closingAngularSpeed),
          "the closing angular speed must be >= 0 rad/s (0: no cap), not " +
              number(protocol.closingAngularSpeed));
  for (std::size_t i = 0; i < protocol.phases.size(); ++i) {
    const ProtocolPhase& p = protocol.phases[i];
    const std::string at = "phase " + std::to_string(i + 1) + ": ";
    require(p.axis.allFinite() && p.axis.norm() > 1e-9, at + "the axis must be a non-zero vector");
    require(nonNegative(p.settle), at + "settle must be >= 0 s, not " + number(p.settle));
    if (p.kind == PhaseKind::kShake) {
      require(positive(p.amplitude), at + "amplitude must be > 0, not " + number(p.amplitude));
      require(positive(p.frequency), at + "frequency must be > 0 Hz, not " + number(p.frequency));
      require(positive(p.cycles) && p.cycles * 2.0 == std::round(p.cycles * 2.0),
              at + "cycles must be a positive whole or half number, not " + number(p.cycles));
    } else {
      require(positive(p.distance), at + "the distance must be > 0 m, not " + number(p.distance));
      require(positive(p.speed), at + "speed must be > 0 m/s, not " + number(p.speed));
      require(positive(p.acceleration),
              at + "acceleration must be > 0 m/s^2, not " + number(p.acceleration));
    }
  }
}

std::string describe(const TrialProtocol& protocol) {
  std::string text = protocol.gravity ? "gravity on" : "gravity off";
  text += protocol.closing == ClosingRule::kRest
              ? "; close until rest"
              : "; close until rest or " + number(protocol.gripForce) + " N";
  // Nothing is added for an uncapped closing, so the hashes of earlier protocols stay.
  if (protocol.closingSpeed > 0.0) text += " at most " + number(protocol.closingSpeed) + " m/s";
  if (protocol.closingAngularSpeed > 0.0) {
    text += " at most " + number(protocol.closingAngularSpeed) + " rad/s";
  }
  for (const ProtocolPhase& p : protocol.phases) {
    switch (p.kind) {
      case PhaseKind::kLift:
        text += "; lift " + number(p.distance) + " m";
        break;
      case PhaseKind::kPull:
        text += "; pull " + number(p.distance) + " m along " + vector(p.axis) + " (" +
                frameName(p.frame) + ")";
        break;
      case PhaseKind::kShake:
        text += std::string("; shake ") + (p.rotation ? "about " : "along ") + vector(p.axis) +
                " (" + frameName(p.frame) + ") " + number(p.amplitude) +
                (p.rotation ? " rad " : " m ") + number(p.frequency) + " Hz " + number(p.cycles) +
                " cycles";
        break;
    }
    if (p.kind != PhaseKind::kShake) {
      text += " at " + number(p.speed) + " m/s " + number(p.acceleration) + " m/s^2";
    }
    text += ", settle " + number(p.settle) + " s";
  }
  text += protocol.success == SuccessRule::kHandContact ? "; held by hand contact"
                                                        : "; held by two fingers";
  return text;
}

double phasesDuration(const TrialProtocol& protocol) {
  double total = 0.0;
  for (const ProtocolPhase& p : protocol.phases) {
    total += p.kind == PhaseKind::kShake
                 ? p.cycles / p.frequency
                 : control::RampProfile(p.distance, p.speed, p.acceleration).duration();
    total += p.settle;
  }
  return total;
}

std::string protocolHash(const TrialProtocol& protocol) {
  return rw::common::hex64(rw::common::fnv1a(describe(protocol)));
}

TrialProtocol parseTrialProtocol(std::string_view xml, const std::filesystem::path& file) {
  DiagnosticSink sink;
  auto source = std::make_shared<rw::common::SourceFile>(
      rw::common::SourceFile{file.lexically_normal().string(), {}});
  rw::common::XmlReader reader(
      rw::common::XmlReaderOptions{std::string(trialProtocolSchema()), explainValueError});
  const auto elements = reader.parse(xml, source, sink);
  TrialProtocol protocol;
  if (elements && !sink.hasErrors()) {
    if (elements->empty()) {
      sink.error(rw::common::SourceLocation{source, 1, 1},
                 "expected a <TrialProtocol> element, found none");
    } else if (elements->size() > 1) {
      sink.error((*elements)[1].location,
                 "a second <TrialProtocol> element; a file holds one (the first is at line " +
                     std::to_string(elements->front().location.line) + ")");
    } else {
      protocol = readProtocol(elements->front(), sink);
    }
  }
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  return protocol;
}

TrialProtocol loadTrialProtocol(const std::filesystem::path& file) {
  return parseTrialProtocol(rw::common::readTextFileOrThrow(file), file);
}

}  // namespace rwsim::trial
