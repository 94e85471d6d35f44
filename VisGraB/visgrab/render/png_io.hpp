#pragma once

#include <filesystem>

#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::render {

/// Writes an 8-bit RGB PNG with zlib compression level `compression` (0 = none .. 9 = smallest).
/// @throws std::invalid_argument for an empty or inconsistent image or a level outside 0..9;
///   rw::common::WriteError (the path and the reason) when the file cannot be written.
void writePng(const std::filesystem::path& path, const visual::RgbImage& image,
              int compression = 3);

/// Reads a PNG as 8-bit RGB (grey is expanded, alpha dropped, 16-bit scaled down).
/// @throws std::runtime_error naming the path when the file is missing, is not a PNG, is
///   corrupt or truncated, or announces more than 2^26 pixels.
visual::RgbImage readPng(const std::filesystem::path& path);

/// Reads any image format OpenCV decodes (PNG, JPEG, BMP, ...) as 8-bit RGB (PNG: at most 2^26
/// pixels, as readPng).
/// @throws std::runtime_error naming the path when the file is missing or cannot be decoded.
visual::RgbImage readImage(const std::filesystem::path& path);

}  // namespace visgrab::render
