#include "visgrab/view/workcell_drawing.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <memory>
#include <stdexcept>

#include "rw/kinematics/frame_tree.hpp"
#include "visgrab/render/mesh_loader.hpp"
#include "visgrab/view/drawable_mesh.hpp"

namespace visgrab::view {

namespace {

using rw::kinematics::FrameId;

/// Mesh formats whose materials (colours, textures) are worth keeping; others (STL, ...) carry
/// none and are drawn in the Drawable's colour.
bool hasMaterials(const std::string& file) {
  std::string ext = std::filesystem::path(file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".obj" || ext == ".dae" || ext == ".fbx" || ext == ".gltf" || ext == ".glb" ||
         ext == ".3ds" || ext == ".wrl";
}

Eigen::AlignedBox3d boxOf(const visual::VisualMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& p : mesh.positions) box.extend(p.cast<double>());
  return box;
}

}  // namespace

WorkcellDrawing::WorkcellDrawing(const rw::models::WorkCell& workcell, render::GlRenderer& renderer,
                                 std::string_view handDevice)
    : workcell_(&workcell) {
  const rw::models::Device* hand = nullptr;
  if (!handDevice.empty()) {
    hand = workcell.findDevice(handDevice);
    if (hand == nullptr) {
      throw std::invalid_argument("WorkcellDrawing: the workcell has no device named '" +
                                  std::string(handDevice) + "'");
    }
  }
  // One upload per mesh file (a scene's objects often share none, a hand's links may).
  std::map<std::string, std::vector<std::pair<render::MeshHandle, Eigen::AlignedBox3d>>> files;
  for (const rw::models::Object& object : workcell.objects()) {
    if (object.visual.empty()) continue;
    if (frames_.size() >= kArrowInstance - 1) {
      throw std::invalid_argument("WorkcellDrawing: more than 65534 frames with geometry");
    }
    DrawnFrame drawn;
    drawn.frame = object.frame;
    drawn.instanceId = static_cast<std::uint16_t>(frames_.size() + 1);
    drawn.hand = hand != nullptr && hand->contains(object.frame);
    for (const rw::models::GeometryInstance& g : object.visual) {
      const Eigen::Vector3f colour(g.color[0], g.color[1], g.color[2]);
      const rw::geometry::Geometry& geometry = *g.geometry;
      std::vector<std::pair<render::MeshHandle, Eigen::AlignedBox3d>> meshes;
      const std::string& file = geometry.sourceFile();
      if (geometry.type() == rw::geometry::GeometryType::kMesh && !file.empty() &&
          hasMaterials(file)) {
        auto cached = files.find(file);
        if (cached == files.end()) {
          std::vector<std::pair<render::MeshHandle, Eigen::AlignedBox3d>> loaded;
          try {
            for (auto& m : render::loadVisualMeshes(file)) {
              const Eigen::AlignedBox3d box = boxOf(m);
              loaded.emplace_back(renderer.add(std::make_shared<const visual::VisualMesh>(m)), box);
            }
          } catch (const std::exception& e) {
            warnings_.push_back(std::string(e.what()) + "; drawing its collision triangles");
            loaded.clear();
          }
          cached = files.emplace(file, std::move(loaded)).first;
        }
        meshes = cached->second;
      }
      if (meshes.empty()) {
        auto mesh =
            std::make_shared<const visual::VisualMesh>(shadedMesh(geometry.triangles(), colour));
        const Eigen::AlignedBox3d box = boxOf(*mesh);
        meshes.emplace_back(renderer.add(mesh), box);
      }
      for (const auto& [handle, box] : meshes) {
        drawn.parts.push_back(Part{handle, g.X_frame_geometry, box});
      }
    }
    frames_.push_back(std::move(drawn));
  }
  shaft_ = renderer.add(std::make_shared<const visual::VisualMesh>(unitShaft()));
  head_ = renderer.add(std::make_shared<const visual::VisualMesh>(unitHead()));
}

void WorkcellDrawing::addItems(const rw::kinematics::State& state, render::Scene& scene,
                               const DrawStyle& style) const {
  const rw::kinematics::FKTable fk(workcell_->frames(), state);
  for (const DrawnFrame& f : frames_) {
    if (f.hand ? !style.hand : !style.environment) continue;
    const rw::math::Transform3D& X_W_frame = fk.worldTransform(f.frame);
    for (const Part& part : f.parts) {
      render::SceneItem item;
      item.mesh = part.mesh;
      item.X_WM = X_W_frame * part.X_frame_part;
      item.instanceId = f.instanceId;
      if (f.hand && style.handColour) item.colour = style.handColour;
      scene.items.push_back(item);
    }
  }
}

void WorkcellDrawing::addArrow(const Eigen::Vector3d& tail, const Eigen::Vector3d& tip,
                               double radius, const Eigen::Vector3f& colour,
                               render::Scene& scene) const {
  const Eigen::Vector3d d = tip - tail;
  const double length = d.norm();
  if (!(length > 1e-9) || !(radius > 0.0)) return;
  const Eigen::Vector3d z = d / length;
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z);
  const double headLength = std::min(length / 3.0, 4.5 * radius);
  render::SceneItem shaft;
  shaft.mesh = shaft_;
  shaft.X_WM = rw::math::Transform3D::Identity();
  shaft.X_WM.linear() = q.toRotationMatrix();
  shaft.X_WM.translation() = tail;
  shaft.scale = Eigen::Vector3d(radius, radius, length - headLength);
  shaft.instanceId = kArrowInstance;
  shaft.colour = colour;
  render::SceneItem head = shaft;
  head.mesh = head_;
  head.X_WM.translation() = tip - headLength * z;
  head.scale = Eigen::Vector3d(3.0 * radius, 3.0 * radius, headLength);
  scene.items.push_back(shaft);
  scene.items.push_back(head);
}

std::uint16_t WorkcellDrawing::instanceId(FrameId frame) const {
  for (const DrawnFrame& f : frames_) {
    if (f.frame == frame) return f.instanceId;
  }
  return 0;
}

bool WorkcellDrawing::isHandInstance(std::uint16_t id) const {
  return id >= 1 && id <= frames_.size() && frames_[id - 1u].hand;
}

std::vector<FrameId> WorkcellDrawing::handFrames() const {
  std::vector<FrameId> out;
  for (const DrawnFrame& f : frames_) {
    if (f.hand) out.push_back(f.frame);
  }
  return out;
}

Eigen::AlignedBox3d WorkcellDrawing::bounds(const rw::kinematics::State& state,
                                            const std::vector<FrameId>& frames) const {
  Eigen::AlignedBox3d box;
  const rw::kinematics::FKTable fk(workcell_->frames(), state);
  for (const DrawnFrame& f : frames_) {
    if (std::find(frames.begin(), frames.end(), f.frame) == frames.end()) continue;
    for (const Part& part : f.parts) {
      if (part.box.isEmpty()) continue;
      const rw::math::Transform3D X = fk.worldTransform(f.frame) * part.X_frame_part;
      for (int c = 0; c < 8; ++c) {
        box.extend(X * part.box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
      }
    }
  }
  return box;
}

}  // namespace visgrab::view
