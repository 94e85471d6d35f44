#pragma once

#include <algorithm>
#include <cmath>

namespace visgrab::render {

/// The sRGB encoding of a linear intensity (clamped to [0, 1]), in [0, 1]: what the renderer
/// writes for a linear colour (e.g. Scene::background).
inline float encodeSrgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

/// The linear intensity of an sRGB-encoded value in [0, 1] (the inverse of encodeSrgb).
inline float decodeSrgb(float encoded) {
  const float c = std::clamp(encoded, 0.0f, 1.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace visgrab::render
