#pragma once

// Internal to visgrab_render: GLSL 3.30 core sources of the renderer's programs.

namespace visgrab::render::detail {

/// Shaded colour pass: world-space Lambert + Blinn-Phong, optional texture and shadow map.
extern const char* const kShadedVertexShader;
/// Shaded colour pass, fragment stage; writes sRGB-encoded colour.
extern const char* const kShadedFragmentShader;
/// Depth and instance-id pass: camera z (float) and id (uint) per pixel centre.
extern const char* const kIdVertexShader;
/// Depth and instance-id pass, fragment stage.
extern const char* const kIdFragmentShader;
/// Shadow-map pass (depth only).
extern const char* const kShadowVertexShader;
/// Shadow-map pass, fragment stage (empty).
extern const char* const kShadowFragmentShader;

}  // namespace visgrab::render::detail
