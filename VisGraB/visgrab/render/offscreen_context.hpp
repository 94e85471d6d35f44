#pragma once

#include <string>

namespace visgrab::render {

/// A headless OpenGL 3.3 core context made with EGL on Mesa's surfaceless platform
/// (EGL_MESA_platform_surfaceless): no display, no window, no pbuffer; draw into framebuffer
/// objects. Construction makes the context current on the calling thread. Use one context per
/// thread: a context is current on at most one thread at a time.
///
/// The EGL display is process-wide and stays initialised after the context is destroyed
/// (eglTerminate would also end the contexts of other threads).
class OffscreenContext {
 public:
  /// Creates the context and makes it current on this thread.
  /// @throws std::runtime_error naming the EGL error when EGL, the surfaceless platform, desktop
  ///   OpenGL or version 3.3 core is unavailable.
  OffscreenContext();
  /// Releases the context (it must not be current on another thread).
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// Makes this context current on the calling thread.
  /// @throws std::runtime_error with the EGL error (e.g. it is current on another thread).
  void makeCurrent();
  /// True if this context is current on the calling thread.
  bool isCurrent() const;
  /// GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) ...".
  const std::string& description() const { return description_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string description_;
};

/// The name of an EGL error code, e.g. "EGL_BAD_MATCH".
std::string eglErrorName(int error);

}  // namespace visgrab::render
