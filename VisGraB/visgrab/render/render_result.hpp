#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::render {

/// A single-channel image, rows from top to bottom, pixels left to right.
template <class T>
struct ScalarImage {
  int width = 0;
  int height = 0;
  /// width * height values, row-major.
  std::vector<T> values;
  /// The value at image row `row` (from the top) and column `col` (from the left).
  /// @pre 0 <= row < height, 0 <= col < width.
  const T& at(int row, int col) const {
    return values[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(col)];
  }
};

/// Camera z (metres along the optical axis) of the visible surface at each pixel centre;
/// +infinity where nothing is drawn.
using DepthImage = ScalarImage<float>;

/// SceneItem::instanceId of the visible surface at each pixel centre; 0 for background.
using InstanceIdImage = ScalarImage<std::uint16_t>;

/// The outputs of one render, all of the camera's width x height.
struct RenderResult {
  /// sRGB colour, anti-aliased (multisampled and resolved).
  visual::RgbImage colour;
  /// Depth sampled at pixel centres, without anti-aliasing.
  DepthImage depth;
  /// Instance ids sampled at pixel centres, without anti-aliasing.
  InstanceIdImage instanceIds;
};

}  // namespace visgrab::render
