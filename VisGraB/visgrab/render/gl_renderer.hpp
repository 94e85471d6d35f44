#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "visgrab/render/camera.hpp"
#include "visgrab/render/render_result.hpp"
#include "visgrab/render/scene.hpp"
#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::render {

/// Options of GlRenderer::render.
struct RenderOptions {
  /// Samples per pixel of the colour image (1 = no anti-aliasing); clamped to GL_MAX_SAMPLES.
  int colourSamples = 4;
  /// Side of the square shadow map in texels (used when a light casts shadows).
  int shadowMapSize = 2048;
  /// False: render() draws and reads back the colour image only (RenderResult::depth and
  /// instanceIds stay empty), for callers that need no depth or ids (the database's stereo
  /// pairs). The colour image is the same either way.
  bool depthAndIds = true;
};

/// Draws scenes of uploaded meshes with OpenGL 3.3 core. Needs only a current context: an
/// OffscreenContext, or the context of a QOpenGLWidget in the viewer. Every member function,
/// including the destructor, must be called with the context that was current at construction
/// current on the calling thread (GL objects belong to that context).
///
/// Meshes are uploaded once with add() and drawn any number of times at any pose. Textures are
/// shared by pointer: meshes whose VisualMesh::texture is the same RgbImage use one GL texture.
/// Rendering is deterministic: the same scene and camera give byte-identical images on one
/// machine and build (every buffer is cleared before drawing).
class GlRenderer {
 public:
  /// Lights per scene.
  static constexpr std::size_t kMaxLights = 8;

  /// Compiles the shaders.
  /// @throws std::runtime_error if no context is current or a shader fails to build.
  GlRenderer();
  /// Deletes the GL objects (the context must be current).
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  /// Uploads a mesh; it can then be drawn by SceneItem with the returned handle.
  /// @throws std::invalid_argument if the mesh is null or inconsistent (normals or uvs not one
  ///   per position, a triangle index out of range, a texture without uvs or of the wrong size).
  MeshHandle add(std::shared_ptr<const visual::VisualMesh> mesh);

  /// Number of uploaded meshes.
  std::size_t meshCount() const;

  /// Renders colour (anti-aliased), depth and instance ids (the latter two unless
  /// options.depthAndIds is false) into framebuffers of its own and reads them back. Restores the
  /// framebuffer bindings it found.
  /// @throws std::invalid_argument for an invalid camera, an unknown mesh handle or too many
  ///   lights; std::runtime_error on an OpenGL error.
  RenderResult render(const Scene& scene, const PinholeCamera& camera,
                      const RenderOptions& options = {});

  /// Draws the shaded scene into the currently bound draw framebuffer (e.g. a QOpenGLWidget's)
  /// with viewport (0, 0, camera.width, camera.height), after clearing it to the background.
  /// The framebuffer needs a depth buffer.
  /// @throws like render().
  void draw(const Scene& scene, const PinholeCamera& camera, const RenderOptions& options = {});

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace visgrab::render
