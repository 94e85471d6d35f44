#include "visgrab/generator/camera_profile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "rw/common/diagnostic.hpp"
#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "visgrab/generator/detail/camera_profile_schema.hpp"

namespace visgrab::generator {

namespace {

namespace fs = std::filesystem;
using rw::common::AttributeRule;
using rw::common::DiagnosticSink;
using rw::common::ValueKind;
using rw::common::XmlElement;

constexpr std::array<AttributeRule, 21> kValueRules{{
    {"width", ValueKind::kInteger, 0, {}, 1},
    {"height", ValueKind::kInteger, 0, {}, 1},
    {"focal"},
    {"baseline"},
    {"eye", ValueKind::kNumbers, 3, "x y z"},
    {"target", ValueKind::kNumbers, 3, "x y z"},
    {"misalignmentRpy", ValueKind::kNumbers, 3, "roll pitch yaw"},
    {"misalignmentOffset", ValueKind::kNumbers, 3, "x y z"},
    {"principalOffset", ValueKind::kNumbers, 2, "x y"},
    {"focalRatio"},
    {"distortion", ValueKind::kNumbers, 5, "k1 k2 p1 p2 k3"},
    {"exposure"},
    {"gain"},
    {"blur"},
    {"vignetting"},
    {"readNoise"},
    {"shotNoise"},
    {"supersampling"},
    {"shininess"},
    {"direction", ValueKind::kNumbers, 3, "x y z"},
    {"colour", ValueKind::kNumbers, 3, "red green blue"},
}};

/// Largest misalignment angle a profile may give (the rectification stays well conditioned).
constexpr double kMaxMisalignmentDegrees = 5.0;

std::string format(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", v);
  return buffer;
}

std::string explainValueError(const XmlElement& element) {
  return rw::common::explainAttributeValues(element, kValueRules);
}

// The semantic pass over the validated tree.
class ProfileReader {
 public:
  explicit ProfileReader(DiagnosticSink& sink) : read_(sink) {}

  CameraProfile read(const XmlElement& root) {
    CameraProfile p;
    p.name = root.attributeOr("name", "");
    bool seen[2] = {false, false};
    for (const XmlElement& e : root.children) {
      if (e.name == "Rig") readRig(e, p);
      if (e.name == "Sensor") readSensor(e, p);
      if (e.name == "Camera") {
        const int side = e.attributeOr("side", "") == "right" ? 1 : 0;
        if (seen[side])
          read_.error(e, "the " + std::string(side ? "right" : "left") + " camera is given twice");
        seen[side] = true;
        readCamera(e, p.cameras[static_cast<std::size_t>(side)]);
      }
      if (e.name == "Material") readMaterial(e, p);
      if (e.name == "Light") readLight(e, p);
    }
    return p;
  }

 private:
  // Reads an optional number attribute into `out` when present and inside (lo, hi) (bounds
  // open or closed as `closedLo`/`closedHi` say).
  void number(const XmlElement& e, std::string_view name, double& out, double lo, double hi,
              bool closedLo, const std::string& expected) {
    const auto v = read_.optionalNumber(e, name);
    if (!v) return;
    const bool ok = (closedLo ? *v >= lo : *v > lo) && *v <= hi;
    if (!ok) {
      read_.error(
          e, "attribute " + std::string(name) + " must be " + expected + ", got " + format(*v));
      return;
    }
    out = *v;
  }

  template <std::size_t N>
  void numbers(const XmlElement& e, std::string_view name, std::array<double, N>& out,
               std::string_view meaning) {
    const auto v = read_.optionalNumberList(e, name, N, meaning);
    if (!v) return;
    std::copy(v->begin(), v->end(), out.begin());
  }

  void readRig(const XmlElement& e, CameraProfile& p) {
    const double inf = std::numeric_limits<double>::infinity();
    double width = p.rig.width;
    double height = p.rig.height;
    number(e, "width", width, 16, 8192, true, "from 16 to 8192");
    number(e, "height", height, 16, 8192, true, "from 16 to 8192");
    p.rig.width = static_cast<int>(width);
    p.rig.height = static_cast<int>(height);
    number(e, "focal", p.rig.focal, 0, inf, false, "positive");
    number(e, "baseline", p.rig.baseline, 0, inf, false, "positive");
    std::array<double, 3> v{};
    if (e.has("eye")) {
      numbers(e, "eye", v, "x y z");
      p.rig.eye = rw::math::Vector3D(v[0], v[1], v[2]);
    }
    if (e.has("target")) {
      numbers(e, "target", v, "x y z");
      p.rig.target = rw::math::Vector3D(v[0], v[1], v[2]);
    }
    numbers(e, "misalignmentRpy", p.misalignmentRpy, "roll pitch yaw");
    for (const double a : p.misalignmentRpy) {
      if (std::abs(a) > kMaxMisalignmentDegrees) {
        read_.error(e, "attribute misalignmentRpy: each angle must be within +-" +
                           format(kMaxMisalignmentDegrees) + " degrees, got " + format(a));
        break;
      }
    }
    numbers(e, "misalignmentOffset", p.misalignmentOffset, "x y z");
    for (const double d : p.misalignmentOffset) {
      if (std::abs(d) > 0.25 * p.rig.baseline) {
        read_.error(e,
                    "attribute misalignmentOffset: each component must be within a quarter "
                    "of the baseline (" +
                        format(0.25 * p.rig.baseline) + " m), got " + format(d));
        break;
      }
    }
  }

  void readCamera(const XmlElement& e, CameraSensorSpec& c) {
    numbers(e, "principalOffset", c.principalOffset, "x y");
    number(e, "focalRatio", c.focalRatio, 0.5, 2.0, true, "from 0.5 to 2");
    numbers(e, "distortion", c.distortion, "k1 k2 p1 p2 k3");
    for (std::size_t i = 0; i < c.distortion.size(); ++i) {
      if (std::abs(c.distortion[i]) > 1.0) {
        read_.error(e, "attribute distortion: coefficients must be within +-1, got " +
                           format(c.distortion[i]) + " (value " + std::to_string(i + 1) + ")");
        break;
      }
    }
    number(e, "exposure", c.exposure, 0.0, 10.0, false, "in (0, 10]");
    number(e, "gain", c.gain, 0.0, 10.0, false, "in (0, 10]");
  }

  void readSensor(const XmlElement& e, CameraProfile& p) {
    number(e, "blur", p.rig.blurSigma, 0.0, 10.0, true, "from 0 to 10 pixels");
    number(e, "vignetting", p.vignetting, 0.0, 0.95, true, "from 0 to 0.95");
    number(e, "readNoise", p.rig.noiseSigma, 0.0, 50.0, true, "from 0 to 50 grey levels");
    number(e, "shotNoise", p.shotNoise, 0.0, 10.0, true, "from 0 to 10");
    number(e, "supersampling", p.supersampling, 1.0, 4.0, true, "from 1 to 4");
    const std::string bayer = e.attributeOr("bayer", "none");
    p.bayer = bayer == "RGGB" ? BayerPattern::kRggb : BayerPattern::kNone;
  }

  void readMaterial(const XmlElement& e, CameraProfile& p) {
    MaterialFinish m;
    const auto material = objects::surfaceMaterialFromName(e.attributeOr("name", ""));
    if (!material) return;  // the schema lists the names
    m.material = *material;
    for (const auto& other : p.materials) {
      if (other.material == m.material) {
        read_.error(e, "material \"" + e.attributeOr("name", "") + "\" is given twice");
        return;
      }
    }
    double specular = 0.0;
    double shininess = 1.0;
    number(e, "specular", specular, 0.0, 4.0, true, "from 0 to 4");
    number(e, "shininess", shininess, 1.0, 10000.0, true, "from 1 to 10000");
    m.specular = static_cast<float>(specular);
    m.shininess = static_cast<float>(shininess);
    p.materials.push_back(m);
  }

  void readLight(const XmlElement& e, CameraProfile& p) {
    ExtraLight light;
    numbers(e, "direction", light.direction, "x y z");
    numbers(e, "colour", light.colour, "red green blue");
    if (light.direction == std::array<double, 3>{0.0, 0.0, 0.0}) {
      read_.error(e, "attribute direction must not be zero");
      return;
    }
    for (const double c : light.colour) {
      if (!(c >= 0.0 && c <= 2.0)) {
        read_.error(e, "attribute colour: components must be in [0, 2], got " + format(c));
        return;
      }
    }
    if (p.lights.size() >= 4) {
      read_.error(e, "at most 4 extra lights");
      return;
    }
    p.lights.push_back(light);
  }

  rw::common::XmlValueReader read_;
};

CameraProfile load(std::string_view text, const fs::path& file, DiagnosticSink& sink) {
  auto source = std::make_shared<rw::common::SourceFile>(
      rw::common::SourceFile{file.lexically_normal().string(), {}});
  rw::common::XmlReader reader(
      rw::common::XmlReaderOptions{std::string(detail::cameraProfileSchema()), explainValueError});
  const auto elements = reader.parse(text, source, sink);
  if (!elements || sink.hasErrors()) return {};
  if (elements->size() != 1 || elements->front().name != "CameraProfile") {
    sink.error(rw::common::SourceLocation{source, 1, 1}, "expected one <CameraProfile> element");
    return {};
  }
  return ProfileReader(sink).read(elements->front());
}

CameraProfile loadOrThrow(std::string_view text, const fs::path& file, DiagnosticSink& sink) {
  CameraProfile profile = load(text, file, sink);
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  return profile;
}

}  // namespace

bool CameraProfile::alreadyRectified() const {
  const auto ideal = [](const CameraSensorSpec& c) {
    return c.principalOffset == std::array<double, 2>{0.0, 0.0} && c.focalRatio == 1.0 &&
           std::all_of(c.distortion.begin(), c.distortion.end(), [](double d) { return d == 0; });
  };
  const auto zero = [](const std::array<double, 3>& v) {
    return v == std::array<double, 3>{0.0, 0.0, 0.0};
  };
  return ideal(cameras[0]) && ideal(cameras[1]) && zero(misalignmentRpy) &&
         zero(misalignmentOffset);
}

CameraProfile loadCameraProfile(const fs::path& file) {
  DiagnosticSink sink;
  return loadOrThrow(rw::common::readTextFileOrThrow(file), file, sink);
}

CameraProfile loadCameraProfileFromString(std::string_view xml, const fs::path& virtualFile) {
  DiagnosticSink sink;
  return loadOrThrow(xml, virtualFile, sink);
}

std::vector<std::string> knownCameraProfiles(const fs::path& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == ".xml") names.push_back(it->path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

CameraProfile findCameraProfile(std::string_view nameOrFile, const fs::path& folder) {
  const std::string text(nameOrFile);
  const bool isFile = text.find('/') != std::string::npos ||
                      (text.size() > 4 && text.compare(text.size() - 4, 4, ".xml") == 0);
  if (isFile) return loadCameraProfile(text);
  const fs::path file = folder / (text + ".xml");
  std::error_code ec;
  if (text.empty() || !fs::is_regular_file(file, ec)) {
    std::string known;
    for (const auto& name : knownCameraProfiles(folder)) {
      known += (known.empty() ? "" : ", ") + name;
    }
    throw std::invalid_argument("unknown camera profile \"" + text + "\" (no " + file.string() +
                                "); known profiles: " + (known.empty() ? "none" : known) +
                                ", or give a profile file's path");
  }
  return loadCameraProfile(file);
}

}  // namespace visgrab::generator
