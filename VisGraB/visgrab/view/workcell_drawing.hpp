#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "rw/kinematics/state.hpp"
#include "rw/models/workcell.hpp"
#include "visgrab/render/gl_renderer.hpp"
#include "visgrab/render/scene.hpp"

/// Drawing workcells, grasp trials and their outcomes with visgrab_render: the pictures of
/// `visgrab render`, of the report and of the viewer.
namespace visgrab::view {

/// What to draw of a workcell, and how.
struct DrawStyle {
  /// Draw the hand's frames (the device named at construction).
  bool hand = true;
  /// Draw every other frame (table, objects, fixtures).
  bool environment = true;
  /// When set, the hand's colour (e.g. the outcome of its grasp).
  std::optional<Eigen::Vector3f> handColour = std::nullopt;
};

/// A workcell's visual geometry (its Drawables) uploaded once to a GlRenderer, drawn at any
/// State. Mesh files are read with render::loadVisualMeshes (OBJ with materials and textures;
/// other formats take the Drawable's colour); primitives are tessellated and shaded with smooth
/// normals within a crease angle. Each frame with geometry gets its own instance id (1, 2, ...
/// in WorkCell::objects() order) in the renderer's instance-id image; arrows get kArrowInstance.
/// Holds references to the workcell and the renderer: both must outlive it, and the renderer's
/// context must be current whenever it is used.
class WorkcellDrawing {
 public:
  /// Instance id of arrows (contact forces, approach directions).
  static constexpr std::uint16_t kArrowInstance = 65535;

  /// Uploads the meshes. `handDevice` names the device DrawStyle::hand refers to (empty: none).
  /// A mesh file that cannot be read is drawn from its collision triangles; warnings() says so.
  /// @throws std::invalid_argument if `handDevice` is not a device of `workcell` or the workcell
  ///   has more than 65534 frames with geometry; std::runtime_error from the renderer.
  WorkcellDrawing(const rw::models::WorkCell& workcell, render::GlRenderer& renderer,
                  std::string_view handDevice = {});

  /// Appends the items of every frame `style` selects, at their poses in `state`.
  void addItems(const rw::kinematics::State& state, render::Scene& scene,
                const DrawStyle& style = {}) const;

  /// Appends an arrow from `tail` to `tip` (world, m) with a shaft of radius `radius` and a head
  /// three radii wide and at most a third of the length long. Nothing for a zero-length arrow.
  void addArrow(const Eigen::Vector3d& tail, const Eigen::Vector3d& tip, double radius,
                const Eigen::Vector3f& colour, render::Scene& scene) const;

  /// The instance id of `frame`'s geometry, 0 if it has none.
  std::uint16_t instanceId(rw::kinematics::FrameId frame) const;
  /// True if `id` is the instance id of a frame of the hand.
  bool isHandInstance(std::uint16_t id) const;
  /// The frames of the hand device that carry geometry.
  std::vector<rw::kinematics::FrameId> handFrames() const;

  /// World bounding box of the visual geometry of `frames` in `state` (empty box if none).
  Eigen::AlignedBox3d bounds(const rw::kinematics::State& state,
                             const std::vector<rw::kinematics::FrameId>& frames) const;

  /// Problems met while uploading (unreadable mesh files), one line each.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// The workcell drawn.
  const rw::models::WorkCell& workcell() const { return *workcell_; }

 private:
  struct Part {
    render::MeshHandle mesh;
    rw::math::Transform3D X_frame_part = rw::math::Transform3D::Identity();
    Eigen::AlignedBox3d box;
  };
  struct DrawnFrame {
    rw::kinematics::FrameId frame;
    std::uint16_t instanceId = 0;
    bool hand = false;
    std::vector<Part> parts;
  };

  const rw::models::WorkCell* workcell_;
  std::vector<DrawnFrame> frames_;
  render::MeshHandle shaft_;
  render::MeshHandle head_;
  std::vector<std::string> warnings_;
};

}  // namespace visgrab::view
