#include "visgrab/database/database_index.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "rw/common/diagnostic.hpp"
#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/xml_attributes.hpp"
#include "rw/common/xml_reader.hpp"
#include "rw/math/rpy.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/detail/index_schema.hpp"

namespace visgrab::database {

using rw::math::kDeg2Rad;
using rw::math::kRad2Deg;

namespace {

constexpr std::string_view kRoot = "VisGraBDatabase";

// Poses at a fixed resolution (1 nm, 1e-9 degree), so that reading and writing an index again
// gives the same text (the shortest form of an RPY angle changes in its last digits when it
// goes through a rotation matrix and back).
std::string fixed(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.9f", value);
  std::string text(buffer);
  if (text == "-0.000000000") text = "0.000000000";
  return text;
}

// Reads the three numbers of <Pos>/<RPY>; reports non-finite values (the schema's xs:double
// accepts NaN and INF).
bool vector3(const rw::common::XmlElement& e, rw::common::DiagnosticSink& sink,
             Eigen::Vector3d& out) {
  const auto values = rw::common::XmlValueReader(sink).textVector3(e);
  if (!values) return false;
  out = Eigen::Vector3d((*values)[0], (*values)[1], (*values)[2]);
  return true;
}

class IndexParser {
 public:
  explicit IndexParser(rw::common::DiagnosticSink& sink) : sink_(sink) {}

  std::optional<DatabaseIndex> parse(const std::vector<rw::common::XmlElement>& top,
                                     const rw::common::SourceLocation& whole) {
    if (top.empty()) {
      sink_.error(whole, "no <VisGraBDatabase> element: not a VisGraB database index");
      return std::nullopt;
    }
    if (top.size() > 1) {
      sink_.error(top[1].location, "a second <VisGraBDatabase> element; an index has one");
      return std::nullopt;
    }
    const rw::common::XmlElement& root = top[0];
    DatabaseIndex index;
    const std::string version = root.attributeOr("formatVersion", "1");
    version_ = 0;
    for (int v = kOldestIndexFormatVersion; v <= kIndexFormatVersion; ++v) {
      if (version == std::to_string(v)) version_ = v;
    }
    if (version_ == 0) {
      sink_.error(root.location, "index format version " + version +
                                     " is not supported (this program reads versions " +
                                     std::to_string(kOldestIndexFormatVersion) + " to " +
                                     std::to_string(kIndexFormatVersion) + ")");
      return std::nullopt;
    }
    index.formatVersion = version_;
    index.seed = std::stoull(root.attributeOr("seed", "0"));
    index.generator = root.attributeOr("generator", "");
    index.camera = root.attributeOr("camera", "");
    camera_ = index.camera;
    const auto catalog = readCatalog(root);
    if (!catalog) return std::nullopt;
    index.catalog = *catalog;
    catalog_ = &index.catalog;
    std::map<std::string, int> firstLine;
    for (const rw::common::XmlElement& scene : root.children) {
      auto record = parseScene(scene);
      if (!record) continue;
      const auto [it, inserted] = firstLine.emplace(record->id, scene.location.line);
      if (!inserted) {
        sink_.error(scene.location, "duplicate scene id \"" + record->id + "\" (first at line " +
                                        std::to_string(it->second) + ")");
        continue;
      }
      index.scenes.push_back(std::move(*record));
    }
    if (sink_.hasErrors()) return std::nullopt;
    return index;
  }

 private:
  // The objects named by the <Object> elements and the pairs of the two-object scenes: the
  // benchmark's catalog when they agree with it, else a catalog of the database's own objects.
  std::optional<ObjectCatalog> readCatalog(const rw::common::XmlElement& root) {
    std::map<int, std::pair<std::string, int>> names;  // id -> name, first line
    std::vector<std::pair<int, int>> pairs;
    bool ok = true;
    for (const rw::common::XmlElement& scene : root.children) {
      std::vector<int> ids;
      for (const rw::common::XmlElement& child : scene.children) {
        if (child.name != "Object") continue;
        const auto id = rw::common::XmlValueReader(sink_).integer(child, "id", 1,
                                                                  std::numeric_limits<int>::max());
        if (!id) return std::nullopt;
        const std::string name = child.attributeOr("name", "");
        const auto [it, inserted] =
            names.emplace(static_cast<int>(*id), std::pair{name, child.location.line});
        if (!inserted && it->second.first != name) {
          sink_.error(child.location, child.describe() + ": object " + std::to_string(*id) +
                                          " is called \"" + it->second.first + "\" at line " +
                                          std::to_string(it->second.second) + ", not \"" + name +
                                          "\"");
          ok = false;
        }
        ids.push_back(static_cast<int>(*id));
      }
      if (ids.size() == 2 &&
          std::find(pairs.begin(), pairs.end(), std::pair{ids[0], ids[1]}) == pairs.end()) {
        pairs.emplace_back(ids[0], ids[1]);
      }
    }
    if (!ok) return std::nullopt;
    // The benchmark's database when every scene id is one of the benchmark's (the objects are
    // then checked against it).
    const bool benchmark = std::all_of(
        root.children.begin(), root.children.end(), [](const rw::common::XmlElement& scene) {
          return parseSceneId(scene.attributeOr("id", "")).has_value();
        });
    if (benchmark) return ObjectCatalog::benchmark();
    std::vector<ObjectCatalog::Object> objects;
    for (const auto& [id, name] : names) objects.push_back({id, name.first});
    try {
      return ObjectCatalog::make(std::move(objects), std::move(pairs));
    } catch (const std::invalid_argument& e) {
      sink_.error(root.location,
                  root.describe() + ": the scenes' objects do not form a database: " + e.what());
      return std::nullopt;
    }
  }

  std::optional<SceneRecord> parseScene(const rw::common::XmlElement& e) {
    SceneRecord record;
    record.id = e.attributeOr("id", "");
    const auto parsed = parseSceneId(record.id, *catalog_);
    if (!parsed) {
      sink_.error(e.location, e.describe() + ": \"" + record.id +
                                  "\" is not a scene id (expected <plain|textured>/<single|"
                                  "double>/<object or pair>/<01..08>, e.g. "
                                  "textured/single/cocacola/03)");
      return std::nullopt;
    }
    record.conditions = *parsed;
    const std::string texture(toString(parsed->texture));
    const std::string kind(toString(parsed->kind));
    const std::string arrangement(toString(parsed->arrangement()));
    const std::string pose = std::to_string(parsed->pose);
    for (const auto& [name, expected] :
         {std::pair{"texture", texture}, std::pair{"kind", kind},
          std::pair{"arrangement", arrangement}, std::pair{"pose", pose}}) {
      const std::string got = e.attributeOr(name, "");
      if (got != expected) {
        sink_.error(e.location, e.describe() + ": " + name + "=\"" + got +
                                    "\" contradicts the id, which means " + name + "=\"" +
                                    expected + "\"");
        return std::nullopt;
      }
    }
    bool ok = true;
    for (const rw::common::XmlElement& child : e.children) {
      if (child.name == "Files") {
        ok = parseFiles(child, record.files) && ok;
      } else if (child.name == "Object") {
        if (auto objectPose = parseObject(child)) {
          record.objects.push_back(*objectPose);
        } else {
          ok = false;
        }
      } else if (child.name == "Source") {
        SceneSource source;
        source.file = child.attributeOr("file", "");
        if (source.file.empty() || source.file.find_first_of("/\\") != std::string::npos) {
          sink_.error(child.location, child.describe() + ": file=\"" + source.file +
                                          "\": expected a file name without folders");
          ok = false;
        } else if (parsePose(child, source.X_W_source)) {
          record.source = std::move(source);
        } else {
          ok = false;
        }
      }
    }
    if (!ok) return std::nullopt;
    std::vector<int> ids;
    for (const ObjectPose& o : record.objects) ids.push_back(o.object);
    if (ids != record.conditions.objects) {
      std::string expected;
      for (int id : record.conditions.objects) {
        expected += (expected.empty() ? "" : ", ") + std::to_string(id);
      }
      sink_.error(e.location, e.describe() + ": the <Object> ids must be " + expected +
                                  " (in this order) for this scene");
      return std::nullopt;
    }
    return record;
  }

  bool parseFiles(const rw::common::XmlElement& e, SceneFiles& files) {
    for (const SceneFileField& field : sceneFileFields()) {
      std::string& target = files.*field.member;
      if (!field.required && !e.has(field.attribute)) continue;  // none: empty
      if (field.required && !e.has(field.attribute)) {
        if (fileMayBeAbsent(field, camera_)) continue;  // a database without images
        sink_.error(e.location, "<Files>: " + std::string(field.attribute) +
                                    " is missing (only a database with camera=\"" +
                                    std::string(kNoCamera) + "\" has no images)");
        return false;
      }
      if (!field.required && version_ < 2) {
        sink_.error(e.location, "<Files>: " + std::string(field.attribute) +
                                    " needs index format version 2 (this index says version " +
                                    std::to_string(version_) + ")");
        return false;
      }
      target = e.attributeOr(field.attribute, "");
      const std::string why = checkRelativePath(target);
      if (!why.empty()) {
        sink_.error(e.location,
                    "<Files>: " + std::string(field.attribute) + "=\"" + target + "\": " + why);
        return false;
      }
    }
    return true;
  }

  std::optional<ObjectPose> parseObject(const rw::common::XmlElement& e) {
    ObjectPose pose;
    const auto id =
        rw::common::XmlValueReader(sink_).integer(e, "id", 1, std::numeric_limits<int>::max());
    if (!id) return std::nullopt;
    pose.object = static_cast<int>(*id);
    const std::string name = e.attributeOr("name", "");
    if (catalog_->isBenchmark() && name != objectName(pose.object)) {
      sink_.error(e.location, e.describe() + ": object " + std::to_string(pose.object) +
                                  " is called \"" + std::string(objectName(pose.object)) +
                                  "\", not \"" + name + "\"");
      return std::nullopt;
    }
    if (!parsePose(e, pose.X_WO)) return std::nullopt;
    return pose;
  }

  // The <Pos> and <RPY> children of `e` as a pose; false after reporting a bad number.
  bool parsePose(const rw::common::XmlElement& e, rw::math::Transform3D& X) {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
    bool ok = true;
    for (const rw::common::XmlElement& child : e.children) {
      if (child.name == "Pos") ok = vector3(child, sink_, position) && ok;
      if (child.name == "RPY") ok = vector3(child, sink_, rpy) && ok;
    }
    if (ok) X = rw::math::rpyTransform(rpy * kDeg2Rad, position);
    return ok;
  }

  rw::common::DiagnosticSink& sink_;
  int version_ = kIndexFormatVersion;
  std::string camera_;
  const ObjectCatalog* catalog_ = nullptr;
};

}  // namespace

std::string checkRelativePath(std::string_view path) {
  if (path.empty()) return "the path is empty";
  if (path.front() == '/') return "the path must be relative to the database folder";
  for (char c : path) {
    if (c == '\\') return "use '/' as the folder separator";
    if (static_cast<unsigned char>(c) < 0x20) return "the path contains a control character";
  }
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    if (path.substr(start, end - start) == "..") return "the path must not contain \"..\"";
    start = end + 1;
  }
  return {};
}

const std::vector<SceneFileField>& sceneFileFields() {
  static const std::vector<SceneFileField> fields = {
      {"left", &SceneFiles::left, true},
      {"right", &SceneFiles::right, true},
      {"calibration", &SceneFiles::calibration, true},
      {"workcell", &SceneFiles::workcell, true},
      {"dynamicWorkcell", &SceneFiles::dynamicWorkcell, true},
      {"rawLeft", &SceneFiles::rawLeft, false},
      {"rawRight", &SceneFiles::rawRight, false},
      {"disparity", &SceneFiles::disparity, false},
      {"pointCloud", &SceneFiles::pointCloud, false},
      {"depth", &SceneFiles::depth, false},
      {"mask", &SceneFiles::mask, false},
      {"poses", &SceneFiles::poses, false}};
  return fields;
}

bool fileMayBeAbsent(const SceneFileField& field, std::string_view camera) {
  if (!field.required) return true;
  return camera == kNoCamera && field.member != &SceneFiles::workcell &&
         field.member != &SceneFiles::dynamicWorkcell;
}

SceneFiles defaultSceneFiles(std::string_view id) {
  const std::string dir = "scenes/" + std::string(id) + "/";
  SceneFiles files;
  files.left = dir + "left.png";
  files.right = dir + "right.png";
  files.calibration = dir + "calibration.yml";
  files.workcell = dir + "scene.wc.xml";
  files.dynamicWorkcell = dir + "scene.dwc.xml";
  files.rawLeft = dir + "raw_left.png";
  files.rawRight = dir + "raw_right.png";
  files.disparity = dir + "disparity.png";
  files.pointCloud = dir + "cloud.ply";
  files.depth = dir + "depth.png";
  files.mask = dir + "mask.png";
  files.poses = dir + "poses.yml";
  return files;
}

DatabaseIndex parseIndex(std::string_view text, const std::string& displayPath) {
  rw::common::DiagnosticSink sink;
  auto file =
      std::make_shared<const rw::common::SourceFile>(rw::common::SourceFile{displayPath, {}});
  const rw::common::SourceLocation whole{file, 0, 0};
  std::optional<DatabaseIndex> index;
  try {
    rw::common::XmlReader reader(
        rw::common::XmlReaderOptions{std::string(detail::indexSchema()), {}});
    const auto top = reader.parse(text, file, sink);
    if (top && !sink.hasErrors()) index = IndexParser(sink).parse(*top, whole);
  } catch (const std::exception& e) {
    sink.error(whole, std::string("internal error while reading the index: ") + e.what());
  }
  if (!index && !sink.hasErrors()) sink.error(whole, "the index could not be read");
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  return std::move(*index);
}

DatabaseIndex readIndex(const std::filesystem::path& file) {
  std::string text;
  const std::string why = rw::common::readTextFile(file, text);
  if (!why.empty()) {
    throw rw::common::LoadError({rw::common::Diagnostic{rw::common::Diagnostic::Severity::kError,
                                                        file.string(),
                                                        0,
                                                        0,
                                                        "cannot read the database index: " + why,
                                                        {}}});
  }
  return parseIndex(text, file.string());
}

std::string poseXml(const rw::math::Transform3D& X, const std::string& what,
                    const std::string& indent) {
  const Eigen::Vector3d p = X.translation();
  const Eigen::Vector3d rpy = rw::math::rotationToRpy(X.linear()) * kRad2Deg;
  if (!p.allFinite() || !rpy.allFinite()) throw std::invalid_argument(what + ": non-finite pose");
  return indent + "<Pos>" + fixed(p.x()) + " " + fixed(p.y()) + " " + fixed(p.z()) + "</Pos>\n" +
         indent + "<RPY>" + fixed(rpy.x()) + " " + fixed(rpy.y()) + " " + fixed(rpy.z()) +
         "</RPY>\n";
}

std::string sourceXml(const SceneRecord& s) {
  if (s.source->file.empty() || s.source->file.find_first_of("/\\") != std::string::npos) {
    throw std::invalid_argument("scene \"" + s.id + "\": source \"" + s.source->file +
                                "\" is not a file name without folders");
  }
  return "    <Source file=\"" + rw::common::escapeXml(s.source->file) + "\">\n" +
         poseXml(s.source->X_W_source, "scene \"" + s.id + "\" source", "      ") +
         "    </Source>\n";
}

std::string indexToXml(const DatabaseIndex& index) {
  std::vector<const SceneRecord*> ordered;
  for (const SceneRecord& s : index.scenes) {
    const std::string expectedId = sceneIdOf(s.conditions, index.catalog);
    if (s.id != expectedId) {
      throw std::invalid_argument("scene record \"" + s.id + "\" has the conditions of \"" +
                                  expectedId + "\"");
    }
    for (const SceneFileField& field : sceneFileFields()) {
      const std::string& path = s.files.*field.member;
      if (fileMayBeAbsent(field, index.camera) && path.empty()) continue;
      const std::string why = checkRelativePath(path);
      if (!why.empty()) {
        throw std::invalid_argument("scene \"" + s.id + "\": file \"" + path + "\": " + why);
      }
    }
    if (s.objects.size() != s.conditions.objects.size()) {
      throw std::invalid_argument("scene \"" + s.id +
                                  "\": one ground-truth pose per object needed");
    }
    ordered.push_back(&s);
  }
  std::stable_sort(
      ordered.begin(), ordered.end(), [&index](const SceneRecord* a, const SceneRecord* b) {
        return sceneIndex(a->conditions, index.catalog) < sceneIndex(b->conditions, index.catalog);
      });
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<!-- VisGraB scene database index; format: docs/database-format.md -->\n";
  out += "<VisGraBDatabase formatVersion=\"" + std::to_string(kIndexFormatVersion) + "\" seed=\"" +
         std::to_string(index.seed) + "\"";
  if (!index.generator.empty())
    out += " generator=\"" + rw::common::escapeXml(index.generator) + "\"";
  if (!index.camera.empty()) out += " camera=\"" + rw::common::escapeXml(index.camera) + "\"";
  out += ">\n";
  for (const SceneRecord* s : ordered) {
    const SceneConditions& c = s->conditions;
    out += "  <Scene id=\"" + rw::common::escapeXml(s->id) + "\" texture=\"" +
           std::string(toString(c.texture)) + "\" kind=\"" + std::string(toString(c.kind)) +
           "\" arrangement=\"" + std::string(toString(c.arrangement())) + "\" pose=\"" +
           std::to_string(c.pose) + "\">\n";
    // One attribute per line after the first, in sceneFileFields() order.
    std::string files;
    for (const SceneFileField& field : sceneFileFields()) {
      const std::string& path = s->files.*field.member;
      if (path.empty()) continue;
      files += (files.empty() ? "    <Files " : "\n           ") + std::string(field.attribute) +
               "=\"" + rw::common::escapeXml(path) + "\"";
    }
    out += files + "/>\n";
    for (std::size_t i = 0; i < s->objects.size(); ++i) {
      const ObjectPose& o = s->objects[i];
      if (o.object != c.objects[i]) {
        throw std::invalid_argument("scene \"" + s->id + "\": ground-truth object " +
                                    std::to_string(o.object) + " is not object " +
                                    std::to_string(c.objects[i]) + " of the scene");
      }
      const std::string pose = poseXml(o.X_WO, "scene \"" + s->id + "\" object", "      ");
      out += "    <Object id=\"" + std::to_string(o.object) + "\" name=\"" +
             rw::common::escapeXml(std::string(index.catalog.name(o.object))) + "\">\n" + pose +
             "    </Object>\n";
    }
    if (s->source) out += sourceXml(*s);
    out += "  </Scene>\n";
  }
  out += "</VisGraBDatabase>\n";
  return out;
}

void writeIndex(const std::filesystem::path& file, const DatabaseIndex& index) {
  writeFileAtomically(file, indexToXml(index));
}

}  // namespace visgrab::database
