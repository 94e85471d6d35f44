#include "rw/loaders/detail/wc_geometry.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/geometry/mesh_loader.hpp"

namespace rw::loaders::detail {

namespace fs = std::filesystem;
using rw::geometry::Geometry;
using rw::geometry::GeometryType;
using rw::geometry::MeshUse;

namespace {

constexpr const char* kTriedExtensions =
    ".stl, .stla, .stlb, .pcd, .tri, .dae, .ac, .ac3d, .3ds, .obj, .ivg, .ply";

// Makes geometry objects, sharing one per mesh file.
class GeometryMaker {
 public:
  explicit GeometryMaker(common::DiagnosticSink& sink) : sink_(sink) {}

  std::shared_ptr<const Geometry> primitive(const GeometryDesc& g) {
    const auto& p = g.parameters;
    try {
      switch (g.type) {
        case GeometryType::kBox:
          return Geometry::box(p.at(0), p.at(1), p.at(2));
        case GeometryType::kSphere:
          return Geometry::sphere(p.at(0));
        case GeometryType::kCylinder:
          return Geometry::cylinder(p.at(0), p.at(1));
        case GeometryType::kCone:
          return Geometry::cone(p.at(0), p.at(1));
        case GeometryType::kTube:
          return Geometry::tube(p.at(0), p.at(1), p.at(2));
        case GeometryType::kFrustum:
          return Geometry::frustum(p.at(0), p.at(1), p.at(2));
        case GeometryType::kPlane:
          return Geometry::plane();
        case GeometryType::kMesh:
          break;
      }
    } catch (const std::exception& e) {
      sink_.error(g.origin.location, g.origin.element + ": " + e.what());
    }
    return nullptr;
  }

  std::shared_ptr<const Geometry> mesh(const GeometryDesc& g, MeshUse use) {
    const fs::path base = g.baseDir.empty() ? fs::path(".") : fs::path(g.baseDir);
    const auto resolved = rw::geometry::resolveMeshFile(base, g.meshName, use);
    if (!resolved) {
      std::error_code ec;
      const fs::path folder =
          fs::absolute(base / fs::path(g.meshName), ec).lexically_normal().parent_path();
      sink_.error(g.origin.location,
                  g.origin.element + ": mesh \"" + g.meshName + "\" not found: looked in " +
                      folder.string() + " for \"" + fs::path(g.meshName).filename().string() +
                      "\" as written and with the extensions " + kTriedExtensions +
                      " (each as written, lower and upper case)");
      return nullptr;
    }
    std::error_code ec;
    const std::string key = fs::absolute(*resolved, ec).lexically_normal().string();
    if (const auto hit = meshes_.find(key); hit != meshes_.end()) return hit->second;
    if (const auto failed = failures_.find(key); failed != failures_.end()) {
      sink_.error(g.origin.location, g.origin.element + ": " + failed->second);
      return nullptr;
    }
    try {
      auto geometry = Geometry::mesh(rw::geometry::loadMesh(*resolved), key);
      meshes_.emplace(key, geometry);
      return geometry;
    } catch (const std::exception& e) {
      // MeshLoadError says "FILE: error: WHY"; keep the file, drop the nested "error:".
      std::string why = e.what();
      const std::string prefix = resolved->string() + ": error: ";
      if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
      const std::string message = "mesh file \"" + key + "\": " + why;
      failures_.emplace(key, message);
      sink_.error(g.origin.location, g.origin.element + ": " + message);
      return nullptr;
    }
  }

 private:
  common::DiagnosticSink& sink_;
  std::map<std::string, std::shared_ptr<const Geometry>> meshes_;
  std::map<std::string, std::string> failures_;
};

rw::models::GeometryInstance instanceOf(const ModelDesc& model,
                                        std::shared_ptr<const Geometry> geometry) {
  rw::models::GeometryInstance instance;
  instance.name = model.name;
  instance.X_frame_geometry = model.transform;
  instance.geometry = std::move(geometry);
  if (model.color) instance.color = *model.color;
  return instance;
}

void addModel(rw::models::WorkCell& wc, const ModelDesc& model, GeometryMaker& maker) {
  const rw::kinematics::FrameId frame = wc.findFrame(model.frame);
  if (!frame.valid()) return;
  for (const GeometryDesc& g : model.geometries) {
    std::shared_ptr<const Geometry> forCollision;
    std::shared_ptr<const Geometry> forDrawing;
    if (g.type == GeometryType::kMesh) {
      if (model.collision) forCollision = maker.mesh(g, MeshUse::kCollision);
      if (model.visual && (!model.collision || forCollision)) {
        forDrawing = maker.mesh(g, MeshUse::kVisual);
      }
    } else {
      forCollision = forDrawing = maker.primitive(g);
    }
    if (model.collision && forCollision) {
      wc.objectOf(frame).collision.push_back(instanceOf(model, forCollision));
    }
    if (model.visual && forDrawing) {
      wc.objectOf(frame).visual.push_back(instanceOf(model, forDrawing));
    }
  }
}

}  // namespace

void addGeometry(rw::models::WorkCell& wc, const std::vector<ModelDesc>& models,
                 common::DiagnosticSink& sink) {
  GeometryMaker maker(sink);
  for (const ModelDesc& model : models) addModel(wc, model, maker);
}

}  // namespace rw::loaders::detail
