#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "visgrab/objects/object_spec.hpp"
#include "visgrab/visual/visual_mesh.hpp"

/// Internal helpers of the object generator: procedural textures.
namespace visgrab::objects::detail {

/// Texels per metre of object textures (0.5 mm texels: a 7x7 block-matching window seen through
/// the texture covers 3.5 mm).
inline constexpr double kObjectTexelsPerMetre = 2000.0;
/// Texels per metre of table textures (1 mm texels).
inline constexpr double kTableTexelsPerMetre = 1000.0;

/// A deterministic random source (splitmix64), identical on every platform.
class Random {
 public:
  /// A source started from `seed`.
  explicit Random(std::uint64_t seed) : state_(seed) {}
  /// The next 64 random bits.
  std::uint64_t next();
  /// Uniform in [0, 1).
  double uniform();
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi].
  int integer(int lo, int hi);

 private:
  std::uint64_t state_;
};

/// An RGB float image being painted, values in [0, 1] (sRGB-encoded, as stored in PNG).
class Canvas {
 public:
  /// A canvas of w x h texels filled with `fill`.
  Canvas(int width, int height, const Eigen::Vector3f& fill);
  /// Width in texels.
  int width() const { return width_; }
  /// Height in texels.
  int height() const { return height_; }
  /// The texel at (x, y) (no bounds check).
  Eigen::Vector3f& at(int x, int y) { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  /// The 8-bit image (values clamped and rounded).
  visual::RgbImage toImage() const;

 private:
  int width_;
  int height_;
  std::vector<Eigen::Vector3f> pixels_;
};

/// A rectangle of texels: left, top, width, height.
using PixelRect = std::array<int, 4>;

/// Specular strength of a plain surface material (cardboard 0.05 ... metal 0.6).
float materialSpecular(SurfaceMaterial material);

/// sRGB encoding of a linear colour.
Eigen::Vector3f linearToSrgb(const Eigen::Vector3f& linear);

/// Paints a printed packaging design (background, colour blocks, stripes, a logo with large
/// glyphs, paragraphs of small text-like glyph rows, print grain) into `area`.
void paintPrinted(Canvas& canvas, const PixelRect& area, double texelsPerMetre,
                  const Eigen::Vector3f& background, const std::vector<Eigen::Vector3f>& palette,
                  Random& random);

/// Paints a plain material (plastic mottling with a little small print, brushed or turned metal,
/// glass with fruit pieces behind it, cardboard fibres) into `area`; `turned` draws concentric
/// rings about the area's centre (lids).
void paintMaterial(Canvas& canvas, const PixelRect& area, double texelsPerMetre,
                   SurfaceMaterial material, const Eigen::Vector3f& colour, bool turned,
                   Random& random);

/// The texture of a table: plain (faint low-contrast grain) or cluttered (colourful print).
visual::RgbImage tableTexture(const TableSpec& table);

}  // namespace visgrab::objects::detail
