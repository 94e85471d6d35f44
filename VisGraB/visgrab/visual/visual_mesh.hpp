#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

/// Types shared by everything that makes, loads or draws the appearance of a model.
namespace visgrab::visual {

/// An 8-bit RGB image, rows from top to bottom, pixels left to right, 3 bytes per pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  /// width * height * 3 bytes.
  std::vector<std::uint8_t> pixels;
  /// True when the image holds no pixels.
  bool empty() const { return width <= 0 || height <= 0; }
};

/// A triangle mesh with per-vertex normals and, optionally, texture coordinates, in metres in
/// its own frame. Triangles wind counter-clockwise seen from outside.
///
/// Texture coordinates: u runs left to right, v top to bottom over the texture image
/// ((0, 0) is the top-left corner of pixel row 0); the renderer flips as its API needs.
/// The surface colour is `texture(uv) * colour` when there is a texture, else `colour`.
struct VisualMesh {
  std::vector<Eigen::Vector3f> positions;
  /// One unit normal per position.
  std::vector<Eigen::Vector3f> normals;
  /// Empty, or one per position.
  std::vector<Eigen::Vector2f> uvs;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Linear RGB in [0, 1].
  Eigen::Vector3f colour{0.8f, 0.8f, 0.8f};
  /// Specular strength in [0, 1] (0 = matte cardboard, ~0.5 = glossy plastic or metal).
  float specular = 0.1f;
  /// Shared so that many instances of one object draw from one image.
  std::shared_ptr<const RgbImage> texture;
};

}  // namespace visgrab::visual
