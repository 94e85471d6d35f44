#include "visgrab/generator/acronym_database.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/database_writer.hpp"
#include "visgrab/generator/scene_model.hpp"
#include "visgrab/objects/mesh_object.hpp"
#include "visgrab/objects/object_writer.hpp"

namespace visgrab::generator {

namespace fs = std::filesystem;
using rw::math::Transform3D;

namespace {

constexpr const char* kGeneratorName = "visgrab db from-acronym";

void check(const AcronymObjectSource& s) {
  const auto positive = [&s](double v, const char* what) {
    if (!std::isfinite(v) || v <= 0.0) {
      throw std::invalid_argument(s.file + ": object/" + what + " is " + std::to_string(v) +
                                  ", expected a finite number > 0");
    }
  };
  positive(s.scale, "scale");
  positive(s.mass, "mass");
  if (!std::isfinite(s.friction) || s.friction < 0.0) {
    throw std::invalid_argument(s.file + ": object/friction is " + std::to_string(s.friction) +
                                ", expected a finite number >= 0");
  }
  if (!s.com.allFinite()) throw std::invalid_argument(s.file + ": object/com is not finite");
  const Eigen::Matrix3d& I = s.inertia;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (I + I.transpose()));
  if (!I.allFinite() || (I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * I.norm() ||
      eigen.eigenvalues().minCoeff() <= 0.0) {
    throw std::invalid_argument(s.file +
                                ": object/inertia is not a symmetric positive definite 3x3 matrix");
  }
}

// The material of object `name` (friction against the fingers from its source).
std::string materialOf(const std::string& name) { return "Object_" + name; }

// The database's material map: the project's, plus one material per object whose friction
// against the fingers is its source's (against everything else as "Object").
std::string materialsXml(const fs::path& projectMaterials,
                         const std::vector<AcronymObjectSource>& sources,
                         const std::vector<std::string>& names) {
  std::string text;
  const std::string why = rw::common::readTextFile(projectMaterials, text);
  if (!why.empty()) {
    throw std::runtime_error("cannot read the material map " + projectMaterials.string() + ": " +
                             why);
  }
  std::string materials;
  std::string pairs;
  const auto pair = [](const std::string& a, const std::string& b, double mu) {
    char number[32];
    std::snprintf(number, sizeof number, "%.10g", mu);
    return "    <Pair first=\"" + a + "\" second=\"" + b +
           "\"><FrictionData type=\"Coulomb\"><Mu>" + number + "</Mu></FrictionData></Pair>\n";
  };
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const std::string m = materialOf(names[i]);
    materials += "    <Material id=\"" + m + "\"><Description>" +
                 rw::common::escapeXml(sources[i].file) + "</Description></Material>\n";
    pairs += pair("Finger", m, sources[i].friction);
    pairs += pair(m, "Object", 0.4);
    pairs += pair(m, "Table", 0.4);
  }
  for (const auto& [tag, extra] :
       {std::pair{"</MaterialData>", materials}, std::pair{"</FrictionMap>", pairs}}) {
    const std::size_t at = text.find(tag);
    if (at == std::string::npos) {
      throw std::runtime_error(projectMaterials.string() + ": no " + tag +
                               " to add the objects' materials to");
    }
    const std::size_t lineStart = text.rfind('\n', at) + 1;
    text.insert(lineStart, extra);
  }
  return text;
}

// The source's mesh, scaled, its vertices joined by position, in the object frame: one
// non-convex collision piece.
objects::CollisionPiece meshPiece(const AcronymObjectSource& s, const objects::ObjectModel& model) {
  const auto loaded = rw::geometry::loadMesh(s.mesh);
  auto mesh = std::make_shared<rw::geometry::TriMesh>();
  std::map<std::array<double, 3>, std::uint32_t> joined;
  std::vector<std::uint32_t> index(loaded->vertices.size());
  for (std::size_t i = 0; i < loaded->vertices.size(); ++i) {
    const rw::math::Vector3D& v = loaded->vertices[i];
    const auto [it, inserted] = joined.emplace(std::array<double, 3>{v.x(), v.y(), v.z()},
                                               static_cast<std::uint32_t>(mesh->vertices.size()));
    if (inserted) mesh->vertices.push_back(model.X_O_mesh * (s.scale * v));
    index[i] = it->second;
  }
  for (const auto& t : loaded->triangles) {
    const std::array<std::uint32_t, 3> joinedTriangle{index[t[0]], index[t[1]], index[t[2]]};
    if (joinedTriangle[0] == joinedTriangle[1] || joinedTriangle[1] == joinedTriangle[2] ||
        joinedTriangle[0] == joinedTriangle[2]) {
      continue;
    }
    mesh->triangles.push_back(joinedTriangle);
  }
  std::shared_ptr<const rw::geometry::TriMesh> triangles = std::move(mesh);
  return {rw::geometry::Geometry::mesh(triangles, model.name + "_hull0.stl"),
          Transform3D::Identity(), triangles};
}

objects::ObjectModel objectOf(const AcronymObjectSource& s, int id, const std::string& name,
                              const AcronymDatabaseOptions& options) {
  objects::ObjectSpec spec;
  spec.id = id;
  spec.name = name;
  spec.product = s.file;
  spec.kind = objects::ShapeKind::kMesh;
  spec.mass = s.mass;
  spec.hasAppearance = false;
  spec.specFile = s.file;
  objects::MeshShapeSpec shape;
  shape.mesh.file = s.mesh;
  shape.mesh.written = s.mesh.string();
  shape.scale = s.scale;
  const bool pieces = options.collision == AcronymCollision::kPieces;
  shape.maxPieces = pieces ? options.maxPieces : 1;  // the hull alone: replaced below
  shape.concavity = options.concavity;
  spec.meshShape = shape;
  objects::ObjectModel model = objects::generateMeshObject(spec);
  if (!pieces) {
    model.collision = {meshPiece(s, model)};
    model.notes = {"collision geometry: the mesh itself (" +
                   std::to_string(model.collision.front().triangles->triangles.size()) +
                   " triangles)"};
  }
  // The source's mass properties, not those of a uniform solid of the mesh.
  const Eigen::Matrix3d R = model.X_O_mesh.linear();
  model.mass.mass = s.mass;
  model.mass.cog = model.X_O_mesh * s.com;
  model.mass.inertia = R * (0.5 * (s.inertia + s.inertia.transpose())) * R.transpose();
  model.mass.fromGeometry = false;
  return model;
}

std::string header(const std::string& id, const AcronymObjectSource& s, const char* what) {
  return "<!-- VisGraB database scene " + id + ": " + what + " of the object of " +
         rw::common::escapeXml(s.file) + " (generated by " + kGeneratorName +
         "; do not edit). -->\n";
}

}  // namespace

std::string acronymObjectName(const std::string& file) {
  std::string stem = fs::path(file).stem().string();
  // <Category>_<mesh id>_<scale>: drop the scale when the last part is a number.
  const std::size_t last = stem.rfind('_');
  if (last != std::string::npos && last + 1 < stem.size() &&
      stem.find_first_not_of("0123456789.eE-+", last + 1) == std::string::npos) {
    stem.resize(last);
  }
  std::string name;
  for (const char c : stem) {
    const auto u = static_cast<unsigned char>(c);
    name += std::isalnum(u) != 0 ? static_cast<char>(std::tolower(u)) : '_';
  }
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name.front())) != 0) {
    name = "object_" + name;
  }
  return name;
}

AcronymDatabaseReport generateAcronymDatabase(const std::vector<AcronymObjectSource>& sources,
                                              const fs::path& out,
                                              const AcronymDatabaseOptions& options) {
  if (sources.empty()) throw std::invalid_argument("no ACRONYM file given");
  std::vector<std::string> names;
  std::map<std::string, int> nameCount;
  std::map<std::string, std::size_t> fileIndex;
  std::vector<database::ObjectCatalog::Object> catalogObjects;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    check(sources[i]);
    if (!fileIndex.emplace(sources[i].file, i).second) {
      throw std::invalid_argument(sources[i].file + " is given twice (one scene per file)");
    }
    std::string name = acronymObjectName(sources[i].file);
    const int seen = ++nameCount[name];
    if (seen > 1) name += "_" + std::to_string(seen);
    names.push_back(name);
    catalogObjects.push_back({static_cast<int>(i) + 1, name});
  }
  const database::ObjectCatalog catalog = database::ObjectCatalog::make(catalogObjects, {});
  database::DatabaseWriter writer(out, 0, kGeneratorName, catalog,
                                  std::string(database::kNoCamera));
  const AssetLayout layout;
  copyHandFolder(options.handFolder, out / layout.hand);
  database::writeFileAtomically(out / layout.materials,
                                materialsXml(options.materials, sources, names));

  AcronymDatabaseReport report;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const AcronymObjectSource& s = sources[i];
    const database::SceneConditions conditions =
        database::SceneConditions::single(database::Texture::kPlain, static_cast<int>(i) + 1, 1);
    const std::string id = database::sceneIdOf(conditions, catalog);
    report.scenes.push_back(id);
    if (writer.isComplete(id)) {
      if (options.onScene) options.onScene(id);
      continue;
    }
    const objects::ObjectModel model = objectOf(s, static_cast<int>(i) + 1, names[i], options);
    for (const std::string& note : model.notes) report.notes.push_back(id + ": " + note);
    objects::writeObjectFiles(model, out / layout.objects);
    // The scaled mesh frame is the world frame: the object frame sits at X_O_mesh^-1.
    const Transform3D X_WO = model.X_O_mesh.inverse();
    database::SceneRecord record;
    record.id = id;
    record.conditions = conditions;
    const std::string dir = "scenes/" + id;
    record.files.workcell = dir + "/scene.wc.xml";
    record.files.dynamicWorkcell = dir + "/scene.dwc.xml";
    const std::string base = relativeFolder(out / dir, out) + "/";
    std::string wc = header(id, s, "workcell") + "<WorkCell name=\"VisGraBScene\">\n";
    wc +=
        objects::objectFrameXml(model, base + layout.objects + "/" + names[i] + "/", "WORLD", X_WO);
    wc += handMountXml(defaultHandParking(), base + layout.hand + "/sdh.wc.xml");
    wc += "</WorkCell>\n";
    std::string dwc = header(id, s, "dynamic workcell") +
                      "<DynamicWorkcell workcell=\"scene.wc.xml\">\n<Gravity>0 0 -9.81</Gravity>\n"
                      "<Include file=\"" +
                      base + layout.materials + "\"/>\n";
    dwc += objects::objectBodyXml(model, materialOf(names[i]));
    dwc += "<Include file=\"" + base + layout.hand + "/sdh_dynamics.dwc.xml\"/>\n";
    dwc += "</DynamicWorkcell>\n";
    database::writeFileAtomically(out / record.files.workcell, wc);
    database::writeFileAtomically(out / record.files.dynamicWorkcell, dwc);
    record.objects.push_back(database::ObjectPose{static_cast<int>(i) + 1, X_WO});
    record.source = database::SceneSource{s.file, Transform3D::Identity()};
    writer.addScene(std::move(record));
    if (options.onScene) options.onScene(id);
  }
  return report;
}

}  // namespace visgrab::generator
