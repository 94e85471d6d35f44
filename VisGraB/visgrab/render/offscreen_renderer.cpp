#include "visgrab/render/offscreen_renderer.hpp"

#include <utility>

namespace visgrab::render {

OffscreenRenderer::OffscreenRenderer()
    : context_(std::make_unique<OffscreenContext>()), renderer_(std::make_unique<GlRenderer>()) {}

OffscreenRenderer::~OffscreenRenderer() {
  try {
    context_->makeCurrent();
    renderer_.reset();
  } catch (...) {
    // Current on another thread: the GL objects go with the context; the renderer's
    // bookkeeping is leaked rather than deleting through a foreign context.
    static_cast<void>(renderer_.release());
  }
  context_.reset();
}

MeshHandle OffscreenRenderer::add(std::shared_ptr<const visual::VisualMesh> mesh) {
  context_->makeCurrent();
  return renderer_->add(std::move(mesh));
}

RenderResult OffscreenRenderer::render(const Scene& scene, const PinholeCamera& camera,
                                       const RenderOptions& options) {
  context_->makeCurrent();
  return renderer_->render(scene, camera, options);
}

}  // namespace visgrab::render
