#include "visgrab/runner/noise_model.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>

#include "rw/common/diagnostic.hpp"
#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/statistics.hpp"

namespace visgrab::runner {

namespace {

using results::formatDouble;
using rw::common::DiagnosticSink;
using rw::common::XmlElement;
using rw::math::Vector3D;

// Typed attributes, for a precise message on a schema datatype error.
constexpr std::array<rw::common::AttributeRule, 3> kNoiseValueRules{{
    {"translation"},
    {"rotation"},
    {"sigma"},
}};

std::string explainNoiseValueError(const XmlElement& element) {
  return rw::common::explainAttributeValues(element, kNoiseValueRules);
}

// What a sigma measures, for its bound and the message about it.
enum class SigmaKind { kLength, kAngle, kRelative };

// One sigma of the model: where the file gives it and which field it sets.
struct SigmaRule {
  std::string_view element;
  std::string_view attribute;
  std::string_view what;
  double NoiseModel::*field;
  SigmaKind kind;
};

constexpr std::array<SigmaRule, 6> kSigmaRules{{
    {"Hand", "translation", "hand translation", &NoiseModel::handTranslation, SigmaKind::kLength},
    {"Hand", "rotation", "hand rotation", &NoiseModel::handRotation, SigmaKind::kAngle},
    {"Object", "translation", "object translation", &NoiseModel::objectTranslation,
     SigmaKind::kLength},
    {"Object", "rotation", "object rotation", &NoiseModel::objectRotation, SigmaKind::kAngle},
    {"Friction", "sigma", "friction", &NoiseModel::friction, SigmaKind::kRelative},
    {"Mass", "sigma", "mass", &NoiseModel::mass, SigmaKind::kRelative},
}};

// Why `value` is not a sigma of `kind` ("expected ..., got ..."), or an empty string.
std::string sigmaProblem(SigmaKind kind, double value) {
  const double bound = kind == SigmaKind::kLength  ? kMaxTranslationSigma
                       : kind == SigmaKind::kAngle ? kMaxRotationSigma
                                                   : kMaxRelativeSigma;
  if (value >= 0.0 && value <= bound) return {};
  std::string expected;
  std::string hint;
  switch (kind) {
    case SigmaKind::kLength:
      expected = "a sigma from 0 to " + formatDouble(bound) + " m";
      hint = " (lengths are in metres: 2 mm is 0.002)";
      break;
    case SigmaKind::kAngle:
      expected = "a sigma from 0 to " + formatDouble(bound) + " rad (pi/4)";
      hint = " (angles are in radians: 1 degree is " + formatDouble(rw::math::kDeg2Rad) + ")";
      break;
    case SigmaKind::kRelative:
      expected = "a relative sigma from 0 to " + formatDouble(bound);
      hint = " (a fraction of the value it scales: 10 % is 0.1)";
      break;
  }
  return "expected " + expected + ", got " + formatDouble(value) + (value > bound ? hint : "");
}

// The semantic pass over the validated tree: the defaults, replaced by the values given.
NoiseModel readModel(const XmlElement& root, DiagnosticSink& sink) {
  const rw::common::XmlValueReader read(sink);
  NoiseModel model;
  for (const XmlElement& part : root.children) {
    for (const SigmaRule& rule : kSigmaRules) {
      if (part.name != rule.element) continue;
      const auto value = read.number(part, rule.attribute);
      if (!value) continue;
      const std::string problem = sigmaProblem(rule.kind, *value);
      if (!problem.empty()) {
        read.error(part, "attribute " + std::string(rule.attribute) + ": " + problem);
        continue;
      }
      model.*rule.field = *value == 0.0 ? 0.0 : *value;  // no "-0" in describe()
    }
  }
  return model;
}

// sigma * z, or exactly 0 for a part that is off.
double noiseOffset(double sigma, double z) { return sigma == 0.0 ? 0.0 : sigma * z; }

// The factor max(floor, 1 + sigma * z), or exactly 1 for a part that is off.
double noiseFactor(double sigma, double z) {
  return sigma == 0.0 ? 1.0 : std::max(kNoiseScaleFloor, 1.0 + sigma * z);
}

// The rotation of rotation vector `w` (angle |w| about w / |w|); the identity for w = 0.
rw::math::Rotation3D rotationFromVector(const Vector3D& w) {
  const double angle = w.norm();
  if (angle == 0.0) return rw::math::Rotation3D::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

}  // namespace

NoiseModel defaultNoiseModel() { return NoiseModel{}; }

NoiseModel parseNoiseModel(std::string_view xml, const std::filesystem::path& file) {
  DiagnosticSink sink;
  auto source = std::make_shared<rw::common::SourceFile>(
      rw::common::SourceFile{file.lexically_normal().string(), {}});
  rw::common::XmlReader reader(
      rw::common::XmlReaderOptions{std::string(noiseModelSchema()), explainNoiseValueError});
  const auto elements = reader.parse(xml, source, sink);
  NoiseModel model;
  if (elements && !sink.hasErrors()) {
    // The schema lets any number of roots pass, so that these messages can say where.
    if (elements->empty()) {
      sink.error(rw::common::SourceLocation{source, 1, 1},
                 "expected a <NoiseModel> element, found none");
    } else if (elements->size() > 1) {
      sink.error((*elements)[1].location,
                 "a second <NoiseModel> element; a file holds one (the first is at line " +
                     std::to_string(elements->front().location.line) + ")");
    } else {
      model = readModel(elements->front(), sink);
    }
  }
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  return model;
}

NoiseModel loadNoiseModel(const std::filesystem::path& file) {
  return parseNoiseModel(rw::common::readTextFileOrThrow(file), file);
}

std::string describe(const NoiseModel& model) {
  return "hand " + formatDouble(model.handTranslation) + " m " + formatDouble(model.handRotation) +
         " rad; object " + formatDouble(model.objectTranslation) + " m " +
         formatDouble(model.objectRotation) + " rad; friction " + formatDouble(model.friction) +
         "; mass " + formatDouble(model.mass);
}

void checkNoiseModel(const NoiseModel& model) {
  for (const SigmaRule& rule : kSigmaRules) {
    const std::string problem = sigmaProblem(rule.kind, model.*rule.field);
    if (!problem.empty()) {
      throw std::invalid_argument("noise model: " + std::string(rule.what) + ": " + problem);
    }
  }
}

Perturbation samplePerturbation(const NoiseModel& model, std::uint64_t seed) {
  checkNoiseModel(model);
  results::SeededRandom random(seed);
  std::array<double, 11> z{};
  for (double& value : z) value = random.normal();
  Perturbation p;
  const Vector3D t(noiseOffset(model.handTranslation, z[0]),
                   noiseOffset(model.handTranslation, z[1]),
                   noiseOffset(model.handTranslation, z[2]));
  const Vector3D w(noiseOffset(model.handRotation, z[3]), noiseOffset(model.handRotation, z[4]),
                   noiseOffset(model.handRotation, z[5]));
  p.X_tcp_perturbed = rw::math::makeTransform(rotationFromVector(w), t);
  p.objectDx = noiseOffset(model.objectTranslation, z[6]);
  p.objectDy = noiseOffset(model.objectTranslation, z[7]);
  p.objectYaw = noiseOffset(model.objectRotation, z[8]);
  p.frictionScale = noiseFactor(model.friction, z[9]);
  p.massScale = noiseFactor(model.mass, z[10]);
  return p;
}

}  // namespace visgrab::runner
