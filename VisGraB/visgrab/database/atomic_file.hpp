#pragma once

#include <filesystem>
#include <string_view>

namespace cv {
class Mat;
}

namespace visgrab::database {

/// Writes `bytes` to `file` atomically: into a temporary file in the same folder, flushed to
/// disk, then renamed over `file`. Readers see the old or the new content, never a part.
/// Creates missing parent folders. @throws rw::common::WriteError (the file and the system's
/// reason) if it cannot be written, std::runtime_error naming the file otherwise.
void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes);

/// How writeImageAtomically compresses a PNG; both are lossless (the same decoded pixels).
enum class PngCompression {
  /// zlib level 9: the smallest file for drawings and clean renders.
  kBest,
  /// Huffman coding only, no string matching: for images with per-pixel sensor noise (the
  /// database's stereo pairs), where matching finds next to nothing: about 4 times faster
  /// than kBest and a few per cent smaller (docs/performance.md).
  kHuffmanOnly,
  /// Run-length matching only (zlib Z_RLE) after PNG's row filters: for images of large flat or
  /// evenly sloped regions with speckle (a disparity map, an instance mask): about 40 times
  /// faster than kBest on a 16-bit disparity map and under 10 per cent larger
  /// (scene_products_benchmark, docs/database-format.md).
  kRle,
};

/// Encodes `image` in the format given by `file`'s extension (.png, ...) and writes it with
/// writeFileAtomically; a PNG as `png` says. @throws std::runtime_error if it cannot be
/// encoded or written.
void writeImageAtomically(const std::filesystem::path& file, const cv::Mat& image,
                          PngCompression png = PngCompression::kBest);

}  // namespace visgrab::database
