#pragma once

#include <memory>

#include "visgrab/render/gl_renderer.hpp"
#include "visgrab/render/offscreen_context.hpp"

namespace visgrab::render {

/// An OffscreenContext and a GlRenderer drawing in it: headless rendering on one thread.
/// Create, use and destroy it on the same thread; make one per thread to render in parallel.
class OffscreenRenderer {
 public:
  /// Creates the context (current on this thread) and the renderer.
  /// @throws std::runtime_error as OffscreenContext and GlRenderer do.
  OffscreenRenderer();
  /// Makes the context current and releases the GL objects, then the context.
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  /// Uploads a mesh (see GlRenderer::add).
  MeshHandle add(std::shared_ptr<const visual::VisualMesh> mesh);
  /// Renders colour, depth and instance ids (see GlRenderer::render).
  RenderResult render(const Scene& scene, const PinholeCamera& camera,
                      const RenderOptions& options = {});
  /// The context.
  OffscreenContext& context() { return *context_; }
  /// The renderer (its context must be current when it is used).
  GlRenderer& renderer() { return *renderer_; }

 private:
  std::unique_ptr<OffscreenContext> context_;
  std::unique_ptr<GlRenderer> renderer_;
};

}  // namespace visgrab::render
