#include "visgrab/objects/detail/texture_painter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace visgrab::objects::detail {

float materialSpecular(SurfaceMaterial m) {
  switch (m) {
    case SurfaceMaterial::kMetal:
      return 0.6f;
    case SurfaceMaterial::kGlass:
      return 0.5f;
    case SurfaceMaterial::kPlastic:
      return 0.3f;
    case SurfaceMaterial::kCardboard:
      return 0.05f;
  }
  return 0.1f;
}

namespace {

std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Hash of a lattice point in [-1, 1].
double latticeValue(std::uint64_t seed, std::int64_t x, std::int64_t y) {
  const std::uint64_t h = mix(seed ^ mix(static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
                                         static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4FULL));
  return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

// Smooth value noise in [-1, 1], lattice spacing 1.
double valueNoise(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx);
  const auto iy = static_cast<std::int64_t>(fy);
  const double tx = x - fx;
  const double ty = y - fy;
  const double sx = tx * tx * (3.0 - 2.0 * tx);
  const double sy = ty * ty * (3.0 - 2.0 * ty);
  const double a = latticeValue(seed, ix, iy);
  const double b = latticeValue(seed, ix + 1, iy);
  const double c = latticeValue(seed, ix, iy + 1);
  const double d = latticeValue(seed, ix + 1, iy + 1);
  return (a + (b - a) * sx) * (1.0 - sy) + (c + (d - c) * sx) * sy;
}

float luminance(const Eigen::Vector3f& c) {
  return 0.299f * c.x() + 0.587f * c.y() + 0.114f * c.z();
}

struct Clip {
  int x0, y0, x1, y1;  // half-open
  explicit Clip(const PixelRect& r) : x0(r[0]), y0(r[1]), x1(r[0] + r[2]), y1(r[1] + r[3]) {}
};

void fillRect(Canvas& c, const Clip& clip, double x0, double y0, double x1, double y1,
              const Eigen::Vector3f& colour) {
  const int ax = std::max(clip.x0, static_cast<int>(std::floor(x0)));
  const int ay = std::max(clip.y0, static_cast<int>(std::floor(y0)));
  const int bx = std::min(clip.x1, static_cast<int>(std::ceil(x1)));
  const int by = std::min(clip.y1, static_cast<int>(std::ceil(y1)));
  for (int y = ay; y < by; ++y) {
    for (int x = ax; x < bx; ++x) c.at(x, y) = colour;
  }
}

// Fills the ellipse with centre (cx, cy) and radii rx, ry; `ring` > 0 paints only a rim.
void fillEllipse(Canvas& c, const Clip& clip, double cx, double cy, double rx, double ry,
                 const Eigen::Vector3f& colour, double ring = 0.0) {
  const int ax = std::max(clip.x0, static_cast<int>(std::floor(cx - rx)));
  const int ay = std::max(clip.y0, static_cast<int>(std::floor(cy - ry)));
  const int bx = std::min(clip.x1, static_cast<int>(std::ceil(cx + rx)));
  const int by = std::min(clip.y1, static_cast<int>(std::ceil(cy + ry)));
  const double inner = ring > 0.0 ? std::pow(std::max(0.0, 1.0 - ring / std::min(rx, ry)), 2) : -1;
  for (int y = ay; y < by; ++y) {
    for (int x = ax; x < bx; ++x) {
      const double dx = (x + 0.5 - cx) / rx;
      const double dy = (y + 0.5 - cy) / ry;
      const double d = dx * dx + dy * dy;
      if (d <= 1.0 && d >= inner) c.at(x, y) = colour;
    }
  }
}

Eigen::Vector3f pick(const std::vector<Eigen::Vector3f>& palette, Random& random) {
  return palette[static_cast<std::size_t>(random.integer(0, static_cast<int>(palette.size()) - 1))];
}

// Rows of text-like glyphs (5x7 random bitmaps grouped in words) filling `rect`; the ink is dark
// on light ground and light on dark ground, decided per glyph.
void paintGlyphRows(Canvas& c, const Clip& clip, double left, double top, double width,
                    double height, double glyph, Random& random) {
  const double line = glyph * 1.55;
  const double cell = glyph * 0.62;
  const double gap = glyph * 0.16;
  for (double y0 = top; y0 + glyph <= top + height; y0 += line) {
    const double right = left + width * (y0 + 2 * line > top + height ? random.uniform(0.4, 1.0)
                                                                      : random.uniform(0.85, 1.0));
    double x = left;
    while (true) {
      const int letters = random.integer(2, 9);
      if (x + letters * (cell + gap) > right) break;
      for (int l = 0; l < letters; ++l, x += cell + gap) {
        const std::uint64_t bits = random.next() | 0x1ULL;
        const int cx = std::clamp(static_cast<int>(x + cell / 2), clip.x0, clip.x1 - 1);
        const int cy = std::clamp(static_cast<int>(y0 + glyph / 2), clip.y0, clip.y1 - 1);
        const bool dark = luminance(c.at(cx, cy)) > 0.45f;
        const Eigen::Vector3f ink =
            dark ? Eigen::Vector3f(0.07f, 0.07f, 0.09f) : Eigen::Vector3f(0.96f, 0.96f, 0.94f);
        const int ax = std::max(clip.x0, static_cast<int>(std::floor(x)));
        const int ay = std::max(clip.y0, static_cast<int>(std::floor(y0)));
        const int bx = std::min(clip.x1, static_cast<int>(std::ceil(x + cell)));
        const int by = std::min(clip.y1, static_cast<int>(std::ceil(y0 + glyph)));
        for (int py = ay; py < by; ++py) {
          const int row = std::clamp(static_cast<int>((py + 0.5 - y0) / glyph * 7.0), 0, 6);
          for (int px = ax; px < bx; ++px) {
            const int col = std::clamp(static_cast<int>((px + 0.5 - x) / cell * 5.0), 0, 4);
            if ((bits >> (row * 5 + col)) & 1ULL) c.at(px, py) = ink;
          }
        }
      }
      x += glyph * 0.7;
    }
  }
}

// Adds luminance grain: value noise at two scales (in texels) and per-texel speckle.
void addGrain(Canvas& c, const Clip& clip, std::uint64_t seed, double fineScale, double fine,
              double coarseScale, double coarse, double speckle, double stretchX = 1.0) {
  for (int y = clip.y0; y < clip.y1; ++y) {
    for (int x = clip.x0; x < clip.x1; ++x) {
      const double n =
          fine * valueNoise(seed, x / (fineScale * stretchX), y / fineScale) +
          coarse * valueNoise(seed + 1, x / (coarseScale * stretchX), y / coarseScale) +
          speckle * latticeValue(seed + 2, x, y);
      c.at(x, y).array() += static_cast<float>(n);
    }
  }
}

}  // namespace

std::uint64_t Random::next() {
  state_ += 0x9E3779B97F4A7C15ULL;
  return mix(state_);
}

double Random::uniform() { return static_cast<double>(next() >> 11) / 9007199254740992.0; }

int Random::integer(int lo, int hi) {
  return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1));
}

Canvas::Canvas(int width, int height, const Eigen::Vector3f& fill)
    : width_(width), height_(height), pixels_(static_cast<std::size_t>(width) * height, fill) {}

visual::RgbImage Canvas::toImage() const {
  visual::RgbImage image;
  image.width = width_;
  image.height = height_;
  image.pixels.resize(pixels_.size() * 3);
  for (std::size_t i = 0; i < pixels_.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const float v = std::clamp(pixels_[i][k], 0.0f, 1.0f);
      image.pixels[3 * i + k] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  }
  return image;
}

Eigen::Vector3f linearToSrgb(const Eigen::Vector3f& linear) {
  Eigen::Vector3f out;
  for (int k = 0; k < 3; ++k) {
    const float v = std::clamp(linear[k], 0.0f, 1.0f);
    out[k] = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  }
  return out;
}

void paintPrinted(Canvas& canvas, const PixelRect& area, double texelsPerMetre,
                  const Eigen::Vector3f& background, const std::vector<Eigen::Vector3f>& palette,
                  Random& random) {
  const Clip clip(area);
  const double mm = texelsPerMetre / 1000.0;
  const double w = area[2];
  const double h = area[3];
  const double left = area[0];
  const double top = area[1];
  const double shade = random.uniform(-0.08, 0.08);
  for (int y = clip.y0; y < clip.y1; ++y) {
    const float f = static_cast<float>(1.0 + shade * ((y - top) / h - 0.5));
    for (int x = clip.x0; x < clip.x1; ++x) canvas.at(x, y) = background * f;
  }
  for (int i = random.integer(2, 5); i > 0; --i) {
    const double bw = random.uniform(0.25, 0.85) * w;
    const double bh = random.uniform(0.1, 0.45) * h;
    const double x = left + random.uniform(-0.1, 1.0) * (w - bw * 0.5);
    const double y = top + random.uniform(-0.1, 1.0) * (h - bh * 0.5);
    fillRect(canvas, clip, x, y, x + bw, y + bh, pick(palette, random));
  }
  {  // a band of diagonal stripes
    const double bh = random.uniform(0.08, 0.25) * h;
    const double y = top + random.uniform(0.0, 1.0) * (h - bh);
    const double period = random.uniform(3.0, 8.0) * mm;
    const Eigen::Vector3f a = pick(palette, random);
    const Eigen::Vector3f b = pick(palette, random) * 0.6f + Eigen::Vector3f::Constant(0.35f);
    for (int py = std::max(clip.y0, static_cast<int>(y)); py < std::min<double>(clip.y1, y + bh);
         ++py) {
      for (int px = clip.x0; px < clip.x1; ++px) {
        canvas.at(px, py) = static_cast<int>(std::floor((px + py) / period)) % 2 == 0 ? a : b;
      }
    }
  }
  const double small = std::min(w, h);
  for (int i = random.integer(1, 3); i > 0; --i) {  // logo discs with a rim and a headline
    const double r = random.uniform(0.12, 0.32) * small;
    const double cx = left + random.uniform(0.15, 0.85) * w;
    const double cy = top + random.uniform(0.15, 0.85) * h;
    fillEllipse(canvas, clip, cx, cy, r * random.uniform(1.0, 1.6), r, pick(palette, random));
    fillEllipse(canvas, clip, cx, cy, r * 1.6, r, pick(palette, random), 1.5 * mm);
  }
  if (random.uniform() < 0.6) {  // a bar code
    const double bw = std::min(0.4 * w, 35.0 * mm);
    const double bh = std::min(0.2 * h, 18.0 * mm);
    const double x0 = left + random.uniform(0.0, 1.0) * (w - bw);
    const double y0 = top + random.uniform(0.0, 1.0) * (h - bh);
    fillRect(canvas, clip, x0, y0, x0 + bw, y0 + bh, Eigen::Vector3f::Constant(0.95f));
    for (double x = x0 + 2 * mm; x < x0 + bw - 2 * mm;) {
      const double bar = random.uniform(0.3, 1.2) * mm;
      fillRect(canvas, clip, x, y0 + mm, x + bar, y0 + bh - mm, Eigen::Vector3f::Constant(0.05f));
      x += bar + random.uniform(0.3, 1.2) * mm;
    }
  }
  {  // a headline
    const double glyph = std::min(random.uniform(6.0, 12.0) * mm, 0.22 * h);
    const double y = top + random.uniform(0.05, 0.7) * h;
    paintGlyphRows(canvas, clip, left + 0.08 * w, y, 0.84 * w, glyph * 1.2, glyph, random);
  }
  const int paragraphs = std::max(3, static_cast<int>(w * h / (45.0 * 45.0 * mm * mm)));
  for (int i = 0; i < paragraphs; ++i) {
    const double pw = random.uniform(0.3, 0.9) * w;
    const double ph = random.uniform(0.08, 0.3) * h;
    const double x = left + random.uniform(0.0, 1.0) * (w - pw);
    const double y = top + random.uniform(0.0, 1.0) * (h - ph);
    paintGlyphRows(canvas, clip, x, y, pw, ph, random.uniform(1.5, 3.5) * mm, random);
  }
  addGrain(canvas, clip, random.next(), 0.8 * mm, 0.10, 2.5 * mm, 0.07, 0.03);
}

void paintMaterial(Canvas& canvas, const PixelRect& area, double texelsPerMetre,
                   SurfaceMaterial material, const Eigen::Vector3f& colour, bool turned,
                   Random& random) {
  const Clip clip(area);
  const double mm = texelsPerMetre / 1000.0;
  fillRect(canvas, clip, area[0], area[1], area[0] + area[2], area[1] + area[3], colour);
  const std::uint64_t seed = random.next();
  switch (material) {
    case SurfaceMaterial::kMetal: {
      if (turned) {
        const double cx = area[0] + area[2] / 2.0;
        const double cy = area[1] + area[3] / 2.0;
        const double rmax = std::min(area[2], area[3]) / 2.0;
        std::vector<double> grooves;
        for (int i = random.integer(3, 6); i > 0; --i) grooves.push_back(random.uniform(0.2, 0.97));
        for (int y = clip.y0; y < clip.y1; ++y) {
          for (int x = clip.x0; x < clip.x1; ++x) {
            const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
            double v = 0.07 * std::sin(2.0 * std::numbers::pi * r / (0.9 * mm));
            for (double g : grooves) {
              if (std::abs(r - g * rmax) < 0.4 * mm) v -= 0.25;
            }
            canvas.at(x, y).array() += static_cast<float>(v);
          }
        }
        addGrain(canvas, clip, seed, 0.6 * mm, 0.06, 3.0 * mm, 0.05, 0.05);
      } else {
        addGrain(canvas, clip, seed, 0.4 * mm, 0.10, 3.0 * mm, 0.06, 0.05, 40.0);
      }
      break;
    }
    case SurfaceMaterial::kGlass: {
      const double area2 = static_cast<double>(area[2]) * area[3];
      const int pieces = static_cast<int>(area2 / (9.0 * mm * mm));
      for (int i = 0; i < pieces; ++i) {
        const double r = random.uniform(0.8, 3.0) * mm;
        const Eigen::Vector3f c = colour * static_cast<float>(random.uniform(0.45, 1.7));
        fillEllipse(canvas, clip, area[0] + random.uniform() * area[2],
                    area[1] + random.uniform() * area[3], r * random.uniform(0.7, 1.4), r, c);
      }
      addGrain(canvas, clip, seed, 0.7 * mm, 0.06, 3.0 * mm, 0.04, 0.04);
      break;
    }
    case SurfaceMaterial::kCardboard:
      addGrain(canvas, clip, seed, 0.6 * mm, 0.08, 2.0 * mm, 0.05, 0.04, 3.0);
      break;
    case SurfaceMaterial::kPlastic: {
      addGrain(canvas, clip, seed, 0.9 * mm, 0.09, 3.0 * mm, 0.05, 0.035);
      // A little small print (a logo line and a recycling note).
      const double pw = random.uniform(0.2, 0.4) * area[2];
      const double ph = std::min(random.uniform(0.1, 0.2) * area[3], 12.0 * mm);
      paintGlyphRows(canvas, clip, area[0] + random.uniform() * (area[2] - pw),
                     area[1] + random.uniform() * (area[3] - ph), pw, ph,
                     random.uniform(1.5, 2.5) * mm, random);
      break;
    }
  }
}

visual::RgbImage tableTexture(const TableSpec& table) {
  const double mm = kTableTexelsPerMetre / 1000.0;
  const int w = static_cast<int>(std::ceil(table.x * kTableTexelsPerMetre));
  const int h = static_cast<int>(std::ceil(table.y * kTableTexelsPerMetre));
  const Eigen::Vector3f base = linearToSrgb(table.colour);
  Canvas canvas(w, h, base);
  const PixelRect all{0, 0, w, h};
  const Clip clip(all);
  Random random(0x7AB1E000ULL + table.seed);
  if (table.pattern == TablePattern::kPlain) {
    addGrain(canvas, clip, random.next(), 4.0 * mm, 0.010, 40.0 * mm, 0.008, 0.004, 8.0);
    return canvas.toImage();
  }
  std::vector<Eigen::Vector3f> palette;
  for (int i = 0; i < 9; ++i) {  // saturated colours from hue, saturation, value
    const double hue = random.uniform(0.0, 6.0);
    const double s = random.uniform(0.55, 1.0);
    const double v = random.uniform(0.45, 1.0);
    const double f = hue - std::floor(hue);
    const auto p = static_cast<float>(v * (1 - s));
    const auto q = static_cast<float>(v * (1 - s * f));
    const auto t = static_cast<float>(v * (1 - s * (1 - f)));
    const auto vv = static_cast<float>(v);
    const std::array<Eigen::Vector3f, 6> sextant{
        Eigen::Vector3f(vv, t, p), Eigen::Vector3f(q, vv, p), Eigen::Vector3f(p, vv, t),
        Eigen::Vector3f(p, q, vv), Eigen::Vector3f(t, p, vv), Eigen::Vector3f(vv, p, q)};
    palette.push_back(sextant[static_cast<std::size_t>(hue) % 6]);
  }
  palette.push_back(Eigen::Vector3f::Constant(0.95f));
  palette.push_back(Eigen::Vector3f::Constant(0.08f));
  for (int i = 0; i < 1500; ++i) {  // large and medium shapes
    const double x = random.uniform(-0.05, 1.0) * w;
    const double y = random.uniform(-0.05, 1.0) * h;
    const double s = random.uniform(5.0, 45.0) * mm;
    const int kind = random.integer(0, 2);
    if (kind == 0) {
      fillEllipse(canvas, clip, x, y, s, s * random.uniform(0.5, 1.0), pick(palette, random));
    } else if (kind == 1) {
      fillRect(canvas, clip, x, y, x + s, y + s * random.uniform(0.3, 1.2), pick(palette, random));
    } else {  // a flower: five petals round a centre
      const Eigen::Vector3f petal = pick(palette, random);
      for (int k = 0; k < 5; ++k) {
        const double a = 2.0 * std::numbers::pi * k / 5.0;
        fillEllipse(canvas, clip, x + 0.5 * s * std::cos(a), y + 0.5 * s * std::sin(a), 0.35 * s,
                    0.35 * s, petal);
      }
      fillEllipse(canvas, clip, x, y, 0.25 * s, 0.25 * s, pick(palette, random));
    }
  }
  const int confetti = static_cast<int>(w * h / (5.0 * 5.0 * mm * mm));
  for (int i = 0; i < confetti; ++i) {
    const double r = random.uniform(1.0, 3.5) * mm;
    fillEllipse(canvas, clip, random.uniform() * w, random.uniform() * h, r, r,
                pick(palette, random));
  }
  addGrain(canvas, clip, random.next(), 1.5 * mm, 0.08, 6.0 * mm, 0.05, 0.04);
  return canvas.toImage();
}

}  // namespace visgrab::objects::detail
