#include "visgrab/objects/object_spec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <utility>

#include "rw/common/diagnostic.hpp"
#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/common/xml_tree.hpp"
#include "visgrab/objects/detail/objects_schema.hpp"

namespace visgrab::objects {

namespace {

using rw::common::DiagnosticSink;
using rw::common::XmlAttribute;
using rw::common::XmlElement;

struct PatternName {
  PatternKind kind;
  std::string_view name;
};
constexpr std::array<PatternName, 4> kPatternNames{{
    {PatternKind::kPrintedBox, "printed-box"},
    {PatternKind::kLabelBand, "label-band"},
    {PatternKind::kMetalCan, "metal-can"},
    {PatternKind::kPlainPlastic, "plain-plastic"},
}};
static_assert(kPatternNames.size() == kPatternKindCount);

struct MaterialName {
  SurfaceMaterial material;
  std::string_view name;
};
constexpr std::array<MaterialName, 4> kMaterialNames{{
    {SurfaceMaterial::kPlastic, "plastic"},
    {SurfaceMaterial::kMetal, "metal"},
    {SurfaceMaterial::kGlass, "glass"},
    {SurfaceMaterial::kCardboard, "cardboard"},
}};
static_assert(kMaterialNames.size() == kSurfaceMaterialCount);

constexpr std::array<std::string_view, 2> kTablePatternNames{"plain", "cluttered"};

using rw::common::AttributeRule;
using rw::common::ValueKind;

// Typed attributes (the schema says xs:double, xs:positiveInteger, ...), for a precise message on
// a schema datatype error.
constexpr std::array<AttributeRule, 25> kValueRules{{
    {"x"},
    {"y"},
    {"z"},
    {"r"},
    {"mass"},
    {"radius"},
    {"height"},
    {"span"},
    {"reach"},
    {"thickness"},
    {"specular"},
    {"cornerRadius"},
    {"labelBottom"},
    {"labelTop"},
    {"lidBottom"},
    {"density"},
    {"scale"},
    {"concavity"},
    {"maxPieces", ValueKind::kInteger, 0, {}, 1},
    {"rpy", ValueKind::kNumbers, 3, "roll pitch yaw (degrees, about z, y, x)"},
    {"id", ValueKind::kInteger, 0, {}, 1},
    {"seed", ValueKind::kInteger, 0, {}, 0},
    {"rgb", ValueKind::kNumbers, 3, "red green blue"},
    {"body", ValueKind::kNumbers, 3, "red green blue"},
    {"lid", ValueKind::kNumbers, 3, "red green blue"},
}};

std::string inQuotes(std::string_view s) { return "\"" + std::string(s) + "\""; }

std::string explainValueError(const XmlElement& element) {
  return rw::common::explainAttributeValues(element, kValueRules);
}

// The semantic pass: reads the validated tree into the spec, reporting meaning errors.
class SpecReader {
 public:
  SpecReader(DiagnosticSink& sink, std::filesystem::path file)
      : read_(sink), file_(std::move(file)) {}

  ObjectDatabaseSpec read(const XmlElement& root) {
    ObjectDatabaseSpec spec;
    std::map<int, int> ids;
    std::map<std::string, int> names;
    std::map<std::string, int> tables;
    std::vector<const XmlElement*> pairs;
    for (const XmlElement& e : root.children) {
      if (e.name == "Table") {
        TableSpec t;
        if (!readTable(e, t)) continue;
        if (!tables.emplace(t.name, e.location.line).second) {
          error(e, "duplicate table name " + inQuotes(t.name) + " (first at line " +
                       std::to_string(tables[t.name]) + ")");
          continue;
        }
        spec.tables.push_back(std::move(t));
      } else if (e.name == "Object") {
        ObjectSpec o;
        if (!readObject(e, o)) continue;
        if (!ids.emplace(o.id, e.location.line).second) {
          error(e, "duplicate id " + std::to_string(o.id) + " (first at line " +
                       std::to_string(ids[o.id]) + ")");
          continue;
        }
        if (!names.emplace(o.name, e.location.line).second) {
          error(e, "duplicate name " + inQuotes(o.name) + " (first at line " +
                       std::to_string(names[o.name]) + ")");
          continue;
        }
        spec.objects.push_back(std::move(o));
      } else if (e.name == "Pair") {
        pairs.push_back(&e);
      }
    }
    std::vector<std::string> allNames;  // also of objects with errors (already reported)
    for (const XmlElement& e : root.children) {
      if (e.name == "Object") allNames.push_back(e.attributeOr("name", ""));
    }
    readPairs(pairs, allNames, spec);
    return spec;
  }

 private:
  void error(const XmlElement& e, const std::string& message) { read_.error(e, message); }

  // A required number attribute (the schema guarantees presence and format).
  double number(const XmlElement& e, std::string_view name) {
    return read_.optionalNumber(e, name).value_or(0.0);
  }

  std::optional<double> optionalNumber(const XmlElement& e, std::string_view name) {
    return read_.optionalNumber(e, name);
  }

  bool positive(const XmlElement& e, std::string_view name, double value) {
    if (value > 0.0) return true;
    error(e, "attribute " + std::string(name) + " must be positive, got " + format(value));
    return false;
  }

  static std::string format(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", v);
    return buffer;
  }

  bool rgb(const XmlElement& e, std::string_view name, Eigen::Vector3f& out) {
    if (!e.has(name)) return true;
    const auto values = read_.optionalNumberList(e, name, 3, "red green blue");
    if (!values) return false;
    for (int i = 0; i < 3; ++i) {
      const double value = (*values)[static_cast<std::size_t>(i)];
      if (!(value >= 0.0 && value <= 1.0)) {
        error(e, "attribute " + std::string(name) + ": colour components must be in [0, 1], got " +
                     inQuotes(*e.attribute(name)));
        return false;
      }
      out[i] = static_cast<float>(value);
    }
    return true;
  }

  bool seed(const XmlElement& e, std::uint32_t& out) {
    const auto s = read_.integer(e, "seed", 0, std::numeric_limits<std::uint32_t>::max());
    if (!s) return false;
    out = static_cast<std::uint32_t>(*s);
    return true;
  }

  bool readTable(const XmlElement& e, TableSpec& t) {
    t.name = e.attributeOr("name", "");
    t.x = number(e, "x");
    t.y = number(e, "y");
    if (!positive(e, "x", t.x) || !positive(e, "y", t.y)) return false;
    const auto pattern = read_.choice(e, "pattern", kTablePatternNames, "table pattern");
    if (!pattern) return false;
    t.pattern = *pattern == 0 ? TablePattern::kPlain : TablePattern::kCluttered;
    return rgb(e, "rgb", t.colour) && seed(e, t.seed);
  }

  bool readObject(const XmlElement& e, ObjectSpec& o) {
    o.line = e.location.line;
    o.id = static_cast<int>(read_.integer(e, "id", 1, std::numeric_limits<int>::max()).value_or(0));
    o.name = e.attributeOr("name", "");
    o.product = e.attributeOr("product", "");
    o.specFile = file_.lexically_normal().string();
    if (o.name.empty() || !std::all_of(o.name.begin(), o.name.end(), [](char c) {
          return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
        })) {
      error(e,
            "attribute name must be lower-case letters, digits and '_', got " + inQuotes(o.name));
      return false;
    }
    const XmlElement* appearance = nullptr;
    for (const XmlElement& c : e.children) {
      if (c.name == "Box" && !readBox(c, o)) return false;
      if (c.name == "Cylinder" && !readCylinder(c, o)) return false;
      if (c.name == "Lathe" && !readLathe(c, o)) return false;
      if (c.name == "Mesh" && !readMesh(c, o)) return false;
      if (c.name == "Appearance") appearance = &c;
    }
    if (!readMassOrDensity(e, o)) return false;
    for (const XmlElement& c : e.children) {
      if (c.name == "Handle" && !readHandle(c, o)) return false;
      if (c.name == "CollisionPiece") {
        if (o.kind != ShapeKind::kMesh) {
          error(c, "<CollisionPiece> needs a <Mesh> shape");
          return false;
        }
        const auto piece = meshFile(c, "collision piece");
        if (!piece) return false;
        o.meshShape->collisionPieces.push_back(*piece);
      }
    }
    if (appearance == nullptr) {
      if (o.kind != ShapeKind::kMesh) {
        error(e, "missing <Appearance> (only a <Mesh> object may leave it out)");
        return false;
      }
      o.hasAppearance = false;
      return true;
    }
    return readAppearance(*appearance, o);
  }

  bool readBox(const XmlElement& e, ObjectSpec& o) {
    o.kind = ShapeKind::kBox;
    o.boxSize = {number(e, "x"), number(e, "y"), number(e, "z")};
    if (!positive(e, "x", o.boxSize.x()) || !positive(e, "y", o.boxSize.y()) ||
        !positive(e, "z", o.boxSize.z())) {
      return false;
    }
    o.cornerRadius = optionalNumber(e, "cornerRadius").value_or(0.0);
    const double limit = std::min(kMaxCornerRadius, o.boxSize.minCoeff() / 4.0);
    if (!(o.cornerRadius >= 0.0 && o.cornerRadius <= limit)) {
      error(e, "attribute cornerRadius must be in [0, " + format(limit) + "] (at most " +
                   format(kMaxCornerRadius) + " and a quarter of the smallest edge), got " +
                   format(o.cornerRadius));
      return false;
    }
    return true;
  }

  bool readCylinder(const XmlElement& e, ObjectSpec& o) {
    o.kind = ShapeKind::kCylinder;
    const double r = number(e, "radius");
    const double h = number(e, "height");
    if (!positive(e, "radius", r) || !positive(e, "height", h)) return false;
    o.profile = {{0.0, r}, {h, r}};
    return true;
  }

  bool readLathe(const XmlElement& e, ObjectSpec& o) {
    o.kind = ShapeKind::kLathe;
    for (const XmlElement& p : e.children) {
      const ProfilePoint point{number(p, "z"), number(p, "r")};
      if (o.profile.empty() && point.z != 0.0) {
        error(p, "the first profile point must be at z = 0 (the bottom face), got z = " +
                     format(point.z));
        return false;
      }
      if (!o.profile.empty() && !(point.z > o.profile.back().z)) {
        error(p, "profile not monotonic: z = " + format(point.z) +
                     " does not increase (previous point z = " + format(o.profile.back().z) + ")");
        return false;
      }
      if (!positive(p, "r", point.r)) return false;
      o.profile.push_back(point);
    }
    if (o.profile.size() < 2) {
      error(e, "a lathe needs at least two <Point> elements (bottom and top), got " +
                   std::to_string(o.profile.size()));
      return false;
    }
    return true;
  }

  bool readHandle(const XmlElement& e, ObjectSpec& o) {
    if (o.kind == ShapeKind::kBox || o.kind == ShapeKind::kMesh) {
      error(e, "a handle needs a Cylinder or Lathe body, not a Box or Mesh");
      return false;
    }
    HandleSpec h{number(e, "z"), number(e, "span"), number(e, "reach"), number(e, "thickness")};
    if (!positive(e, "span", h.span) || !positive(e, "reach", h.reach) ||
        !positive(e, "thickness", h.thickness)) {
      return false;
    }
    if (!(h.reach > h.thickness) || !(h.span > h.thickness)) {
      error(e, "reach and span must exceed thickness (the handle needs an opening), got reach " +
                   format(h.reach) + ", span " + format(h.span) + ", thickness " +
                   format(h.thickness));
      return false;
    }
    const double low = h.z - h.span / 2 - h.thickness / 2;
    const double high = h.z + h.span / 2 + h.thickness / 2;
    if (low < 0.0 || high > o.height()) {
      error(e, "the handle spans z " + format(low) + " to " + format(high) +
                   ", outside the body (z 0 to " + format(o.height()) + ")");
      return false;
    }
    if (o.minRadiusBetween(low, high) <= h.thickness) {
      error(e, "the body is too thin where the handle attaches (radius must exceed thickness)");
      return false;
    }
    o.handle = h;
    return true;
  }

  bool material(const XmlElement& e, std::string_view attribute, SurfaceMaterial& out) {
    const std::string* v = e.attribute(attribute);
    if (v == nullptr) return true;
    const auto m = surfaceMaterialFromName(*v);
    if (!m) {
      error(e, "unknown " + std::string(attribute) + " " + inQuotes(*v) +
                   "; expected plastic, metal, glass or cardboard");
      return false;
    }
    out = *m;
    return true;
  }

  bool readAppearance(const XmlElement& e, ObjectSpec& o) {
    AppearanceSpec& a = o.appearance;
    const std::string pattern = e.attributeOr("pattern", "");
    const auto kind = patternKindFromName(pattern);
    if (!kind) {
      error(e, "unknown pattern " + inQuotes(pattern) +
                   "; expected printed-box, label-band, metal-can or plain-plastic");
      return false;
    }
    a.pattern = *kind;
    const bool isBox = o.kind == ShapeKind::kBox;
    const bool isMesh = o.kind == ShapeKind::kMesh;  // any pattern, wrapped around z
    if ((!isMesh && a.pattern == PatternKind::kPrintedBox && !isBox) ||
        (!isMesh && (a.pattern == PatternKind::kLabelBand || a.pattern == PatternKind::kMetalCan) &&
         isBox)) {
      error(e, "pattern " + inQuotes(pattern) + " does not fit a " +
                   (isBox ? "Box (use printed-box or plain-plastic)"
                          : "lathe (use label-band, metal-can or plain-plastic)"));
      return false;
    }
    a.bodyMaterial = a.pattern == PatternKind::kMetalCan     ? SurfaceMaterial::kMetal
                     : a.pattern == PatternKind::kPrintedBox ? SurfaceMaterial::kCardboard
                                                             : SurfaceMaterial::kPlastic;
    if (!seed(e, a.seed) || !rgb(e, "body", a.body) || !rgb(e, "lid", a.lid) ||
        !material(e, "bodyMaterial", a.bodyMaterial) ||
        !material(e, "lidMaterial", a.lidMaterial)) {
      return false;
    }
    const double specular = optionalNumber(e, "specular").value_or(0.1);
    if (!(specular >= 0.0 && specular <= 1.0)) {
      error(e, "attribute specular must be in [0, 1], got " + format(specular));
      return false;
    }
    a.specular = static_cast<float>(specular);
    for (const XmlElement& c : e.children) {
      Eigen::Vector3f colour;
      if (!rgb(c, "rgb", colour)) return false;
      a.palette.push_back(colour);
    }
    if (a.pattern != PatternKind::kPlainPlastic && a.palette.size() < 2) {
      error(e, "pattern " + inQuotes(pattern) + " needs at least two <Colour> children, got " +
                   std::to_string(a.palette.size()));
      return false;
    }
    const auto bottom = optionalNumber(e, "labelBottom");
    const auto top = optionalNumber(e, "labelTop");
    const auto lid = optionalNumber(e, "lidBottom");
    if ((bottom || top || lid) && (isBox || isMesh)) {
      error(e, "labelBottom, labelTop and lidBottom apply to lathes only");
      return false;
    }
    if (bottom.has_value() != top.has_value()) {
      error(e, "labelBottom and labelTop must be given together");
      return false;
    }
    const double h = o.height();
    if (bottom && !(*bottom >= 0.0 && *bottom < *top && *top <= h)) {
      error(e, "expected 0 <= labelBottom < labelTop <= " + format(h) + " (the height), got " +
                   format(*bottom) + " and " + format(*top));
      return false;
    }
    if (bottom) a.label = std::array<double, 2>{*bottom, *top};
    if (lid && !(*lid > 0.0 && *lid < h)) {
      error(e, "expected 0 < lidBottom < " + format(h) + " (the height), got " + format(*lid));
      return false;
    }
    a.lidBottom = lid;
    return true;
  }

  void readPairs(const std::vector<const XmlElement*>& elements,
                 const std::vector<std::string>& allNames, ObjectDatabaseSpec& spec) {
    std::map<std::pair<std::string, std::string>, int> seen;
    for (const XmlElement* e : elements) {
      PairSpec pair{e->attributeOr("a", ""), e->attributeOr("b", ""), e->location.line};
      bool ok = true;
      for (const std::string* name : {&pair.a, &pair.b}) {
        if (spec.findObject(*name) != nullptr) continue;
        ok = false;
        if (std::find(allNames.begin(), allNames.end(), *name) == allNames.end()) {
          error(*e, "no object named " + inQuotes(*name) + " in this file");
        }
      }
      if (!ok) continue;
      if (pair.a == pair.b) {
        error(*e, "a pair needs two different objects, got " + inQuotes(pair.a) + " twice");
        continue;
      }
      const auto key = std::minmax(pair.a, pair.b);
      const auto [it, inserted] = seen.emplace(key, e->location.line);
      if (!inserted) {
        error(*e, "duplicate pair (first at line " + std::to_string(it->second) + ")");
        continue;
      }
      spec.pairs.push_back(std::move(pair));
    }
  }

  // A mesh file named by attribute "file", resolved against the spec's folder; reports a
  // missing file.
  std::optional<MeshFileSpec> meshFile(const XmlElement& e, std::string_view what) {
    MeshFileSpec m;
    m.written = e.attributeOr("file", "");
    m.line = e.location.line;
    const std::filesystem::path written(m.written);
    m.file = written.is_absolute() ? written : file_.parent_path() / written;
    m.file = m.file.lexically_normal();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(m.file, ec)) {
      error(e, std::string(what) + " file " + inQuotes(m.written) + " not found (looked for " +
                   m.file.string() + ")");
      return std::nullopt;
    }
    return m;
  }

  bool readMesh(const XmlElement& e, ObjectSpec& o) {
    o.kind = ShapeKind::kMesh;
    MeshShapeSpec shape;
    const auto mesh = meshFile(e, "mesh");
    if (!mesh) return false;
    shape.mesh = *mesh;
    shape.scale = optionalNumber(e, "scale").value_or(1.0);
    if (!positive(e, "scale", shape.scale)) return false;
    if (e.has("rpy")) {
      const auto rpy =
          read_.optionalNumberList(e, "rpy", 3, "roll pitch yaw (degrees, about z, y, x)");
      if (!rpy) return false;
      shape.rpyDegrees = Eigen::Vector3d((*rpy)[0], (*rpy)[1], (*rpy)[2]);
    }
    const auto fill = read_.optionalBoolean(e, "fillHoles");
    if (e.has("fillHoles") && !fill) return false;
    shape.fillHoles = fill.value_or(false);
    if (e.has("maxPieces")) {
      const auto pieces = read_.integer(e, "maxPieces", 1, 256);
      if (!pieces) return false;
      shape.maxPieces = static_cast<int>(*pieces);
    }
    shape.concavity = optionalNumber(e, "concavity").value_or(shape.concavity);
    if (!(shape.concavity > 0.0 && shape.concavity < 1.0)) {
      error(e, "attribute concavity must be in (0, 1), got " + format(shape.concavity));
      return false;
    }
    o.meshShape = std::move(shape);
    return true;
  }

  bool readMassOrDensity(const XmlElement& e, ObjectSpec& o) {
    const auto mass = optionalNumber(e, "mass");
    const auto density = optionalNumber(e, "density");
    if (mass.has_value() == density.has_value()) {
      error(e, mass ? "give either mass or density, not both"
                    : "missing attribute mass (kg) or density (kg/m^3)");
      return false;
    }
    if (density && o.kind != ShapeKind::kMesh) {
      error(e, "attribute density needs a <Mesh> shape; give the mass of a Box, Cylinder or Lathe");
      return false;
    }
    if (mass) {
      o.mass = *mass;
      return positive(e, "mass", o.mass);
    }
    o.density = *density;
    return positive(e, "density", *density);
  }

  rw::common::XmlValueReader read_;
  std::filesystem::path file_;
};

ObjectDatabaseSpec load(std::string_view text, const std::filesystem::path& file,
                        DiagnosticSink& sink) {
  auto source = std::make_shared<rw::common::SourceFile>(
      rw::common::SourceFile{file.lexically_normal().string(), {}});
  rw::common::XmlReader reader(
      rw::common::XmlReaderOptions{std::string(detail::objectsSchema()), explainValueError});
  const auto elements = reader.parse(text, source, sink);
  if (!elements || sink.hasErrors()) return {};
  if (elements->size() != 1 || elements->front().name != "ObjectDatabase") {
    sink.error(rw::common::SourceLocation{source, 1, 1}, "expected one <ObjectDatabase> element");
    return {};
  }
  return SpecReader(sink, file).read(elements->front());
}

ObjectDatabaseSpec loadOrThrow(std::string_view text, const std::filesystem::path& file,
                               DiagnosticSink& sink) {
  ObjectDatabaseSpec spec = load(text, file, sink);
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  return spec;
}

}  // namespace

std::string_view patternKindName(PatternKind kind) {
  for (const auto& p : kPatternNames) {
    if (p.kind == kind) return p.name;
  }
  return "?";
}

std::optional<PatternKind> patternKindFromName(std::string_view name) {
  for (const auto& p : kPatternNames) {
    if (p.name == name) return p.kind;
  }
  return std::nullopt;
}

std::string_view surfaceMaterialName(SurfaceMaterial material) {
  for (const auto& m : kMaterialNames) {
    if (m.material == material) return m.name;
  }
  return "?";
}

std::optional<SurfaceMaterial> surfaceMaterialFromName(std::string_view name) {
  for (const auto& m : kMaterialNames) {
    if (m.name == name) return m.material;
  }
  return std::nullopt;
}

double ObjectSpec::height() const {
  if (kind == ShapeKind::kBox) return boxSize.z();
  if (kind == ShapeKind::kMesh) return 0.0;
  return profile.empty() ? 0.0 : profile.back().z;
}

double ObjectSpec::maxRadius() const {
  double r = 0.0;
  for (const ProfilePoint& p : profile) r = std::max(r, p.r);
  return r;
}

double ObjectSpec::radiusAt(double z) const {
  if (profile.empty()) return 0.0;
  if (z <= profile.front().z) return profile.front().r;
  for (std::size_t i = 1; i < profile.size(); ++i) {
    if (z == profile[i].z) return profile[i].r;
    if (z < profile[i].z) {
      const double t = (z - profile[i - 1].z) / (profile[i].z - profile[i - 1].z);
      return profile[i - 1].r + t * (profile[i].r - profile[i - 1].r);
    }
  }
  return profile.back().r;
}

double ObjectSpec::minRadiusBetween(double z0, double z1) const {
  double r = std::min(radiusAt(z0), radiusAt(z1));
  for (const ProfilePoint& p : profile) {
    if (p.z > z0 && p.z < z1) r = std::min(r, p.r);
  }
  return r;
}

const ObjectSpec* ObjectDatabaseSpec::findObject(std::string_view name) const {
  for (const ObjectSpec& o : objects) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

const ObjectSpec* ObjectDatabaseSpec::findObject(int id) const {
  for (const ObjectSpec& o : objects) {
    if (o.id == id) return &o;
  }
  return nullptr;
}

const TableSpec* ObjectDatabaseSpec::findTable(std::string_view name) const {
  for (const TableSpec& t : tables) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

ObjectDatabaseSpec loadObjectSpecs(const std::filesystem::path& file) {
  DiagnosticSink sink;
  std::string text;
  const std::string problem = rw::common::readTextFile(file, text);
  if (!problem.empty()) {
    auto source = std::make_shared<rw::common::SourceFile>(
        rw::common::SourceFile{file.lexically_normal().string(), {}});
    sink.error(rw::common::SourceLocation{source, 0, 0}, "cannot read the file: " + problem);
    throw rw::common::LoadError(sink.take());
  }
  return loadOrThrow(text, file, sink);
}

ObjectDatabaseSpec loadObjectSpecsFromString(std::string_view xml,
                                             const std::filesystem::path& virtualFile) {
  DiagnosticSink sink;
  return loadOrThrow(xml, virtualFile, sink);
}

}  // namespace visgrab::objects
