#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "rw/math/types.hpp"

namespace visgrab::render {

/// Refers to a mesh uploaded to one GlRenderer (valid only with that renderer).
struct MeshHandle {
  /// Index into the renderer's mesh table.
  std::uint32_t index = 0;
};

/// One drawn instance of an uploaded mesh.
struct SceneItem {
  /// The mesh to draw.
  MeshHandle mesh;
  /// The mesh frame's pose in the world.
  rw::math::Transform3D X_WM = rw::math::Transform3D::Identity();
  /// Written to the instance-id image where this item is visible; 0 means background.
  std::uint16_t instanceId = 0;
  /// Scale along the mesh frame's axes, applied before X_WM (all > 0; e.g. a unit arrow
  /// stretched to a force's length). Normals are transformed correctly.
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  /// When set, replaces the mesh's colour (a texture still modulates it): e.g. a hand tinted
  /// by a grasp's outcome. Linear RGB in [0, 1].
  std::optional<Eigen::Vector3f> colour = std::nullopt;
  /// When set, replaces the mesh's specular strength (VisualMesh::specular).
  std::optional<float> specular = std::nullopt;
  /// When set, replaces the scene's Blinn-Phong exponent (Lighting::shininess) for this item.
  std::optional<float> shininess = std::nullopt;
};

/// A light source. Colours are linear RGB intensities (1 = full white).
struct Light {
  /// Kinds of light.
  enum class Type {
    /// At infinity; `direction_W` is where its light travels.
    kDirectional,
    /// At `position_W`, shining equally in all directions, without distance falloff.
    kPoint,
  };
  /// The kind of light.
  Type type = Type::kDirectional;
  /// Direction in which a directional light's rays travel, world frame (need not be unit).
  rw::math::Vector3D direction_W{0.0, 0.0, -1.0};
  /// Position of a point light, world frame, metres.
  rw::math::Vector3D position_W = rw::math::Vector3D::Zero();
  /// Linear RGB intensity.
  Eigen::Vector3f colour{0.8f, 0.8f, 0.8f};
  /// Whether this light casts shadows (honoured for the first such directional light only).
  bool castsShadows = false;
};

/// Lighting of a scene: surface colour = albedo * (ambient + sum_l colour_l * max(0, n . l))
/// + specular * sum_l colour_l * max(0, n . h)^shininess (Lambert + Blinn-Phong, linear RGB),
/// encoded to sRGB in the output image.
struct Lighting {
  /// Ambient light, linear RGB.
  Eigen::Vector3f ambient{0.25f, 0.25f, 0.25f};
  /// At most GlRenderer::kMaxLights lights.
  std::vector<Light> lights{Light{}};
  /// Blinn-Phong exponent of the specular highlight.
  float shininess = 32.0f;
};

/// Everything drawn in one image except the camera.
struct Scene {
  /// The drawn instances.
  std::vector<SceneItem> items;
  /// The lights.
  Lighting lighting;
  /// Background colour, linear RGB in [0, 1] (encoded to sRGB like surfaces).
  Eigen::Vector3f background{0.0f, 0.0f, 0.0f};
};

}  // namespace visgrab::render
