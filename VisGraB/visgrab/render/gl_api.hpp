#pragma once

// Internal to visgrab_render: the OpenGL declarations its sources use. Not included by any
// public header, so that a Qt viewer can include the renderer's headers beside Qt's own GL ones.
//
// Entry points: GL_GLEXT_PROTOTYPES with <GL/glcorearb.h>, linked against glvnd's libOpenGL
// (CMake OpenGL::OpenGL). On Debian 12 (glvnd 1.6) libOpenGL exports every core entry point up
// to 4.6 and forwards each call to the vendor library of whatever context is current (EGL here,
// GLX or EGL under Qt), so no eglGetProcAddress table is needed.

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

#include <string>

namespace visgrab::render::detail {

/// The name of an OpenGL error code, e.g. "GL_INVALID_OPERATION".
std::string glErrorName(GLenum error);

/// Throws std::runtime_error("OpenGL error GL_...: <what>") if glGetError reports an error
/// (draining all pending errors).
void checkGl(const char* what);

/// Compiles and links a program from vertex and fragment shader sources.
/// @throws std::runtime_error with the shader's name and the compiler's log.
GLuint buildProgram(const char* name, const char* vertexSource, const char* fragmentSource);

}  // namespace visgrab::render::detail
