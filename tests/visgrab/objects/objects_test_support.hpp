#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "support/test_support.hpp"
#include "visgrab/objects/object_model.hpp"
#include "visgrab/objects/object_spec.hpp"

/// Helpers shared by the object tests: the project's spec and models (generated once per test
/// program), mesh checks and texture statistics computed independently of the generator.
namespace visgrab::test::objects {

/// scenes/objects/objects.xml, loaded once.
inline const visgrab::objects::ObjectDatabaseSpec& projectSpec() {
  static const auto spec =
      visgrab::objects::loadObjectSpecs(sourceDir() / "scenes/objects/objects.xml");
  return spec;
}

/// The model of projectSpec().objects[index], generated on first use and kept. A test about one
/// object (each runs in its own process under CTest) thus generates just that one.
inline const visgrab::objects::ObjectModel& projectModel(std::size_t index) {
  static std::map<std::size_t, visgrab::objects::ObjectModel> models;
  auto it = models.find(index);
  if (it == models.end()) {
    it = models.emplace(index, visgrab::objects::generateObject(projectSpec().objects.at(index)))
             .first;
  }
  return it->second;
}

/// The 18 models generated from projectSpec(), in file order, generated once.
inline const std::vector<visgrab::objects::ObjectModel>& projectModels() {
  static const auto models = [] {
    std::vector<visgrab::objects::ObjectModel> out;
    for (std::size_t i = 0; i < projectSpec().objects.size(); ++i) out.push_back(projectModel(i));
    return out;
  }();
  return models;
}

/// A triangle soup: positions of the three corners of each triangle, in winding order.
using Triangle = std::array<Eigen::Vector3d, 3>;

/// The triangles of all visual parts of a model.
inline std::vector<Triangle> visualTriangles(const visgrab::objects::ObjectModel& model) {
  std::vector<Triangle> out;
  for (const auto& part : model.visual) {
    const auto& m = part.mesh;
    for (const auto& t : m.triangles) {
      out.push_back({m.positions[t[0]].cast<double>(), m.positions[t[1]].cast<double>(),
                     m.positions[t[2]].cast<double>()});
    }
  }
  return out;
}

/// The triangles of an indexed mesh.
inline std::vector<Triangle> meshTriangles(const rw::geometry::TriMesh& mesh) {
  std::vector<Triangle> out;
  for (const auto& t : mesh.triangles) {
    out.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  }
  return out;
}

/// Key of a position rounded to 0.1 micrometre (joins corners that coincide).
inline std::array<std::int64_t, 3> positionKey(const Eigen::Vector3d& p) {
  return {std::llround(p.x() * 1e7), std::llround(p.y() * 1e7), std::llround(p.z() * 1e7)};
}

/// Number of directed edges (corners joined by position) not matched by exactly one opposite
/// edge: 0 for a closed surface wound consistently (each edge in exactly two triangles, once
/// in each direction).
inline int unmatchedEdges(const std::vector<Triangle>& triangles) {
  using Key = std::array<std::int64_t, 3>;
  std::map<std::pair<Key, Key>, int> directed;
  for (const Triangle& t : triangles) {
    for (int i = 0; i < 3; ++i) ++directed[{positionKey(t[i]), positionKey(t[(i + 1) % 3])}];
  }
  int bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad;
  }
  return bad;
}

/// Signed volume enclosed by the triangles (positive when wound outwards).
inline double signedVolume(const std::vector<Triangle>& triangles) {
  double v = 0.0;
  for (const Triangle& t : triangles) v += t[0].dot(t[1].cross(t[2])) / 6.0;
  return v;
}

/// Distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
inline double pointTriangleDistance(const Eigen::Vector3d& p, const Triangle& t) {
  const Eigen::Vector3d& a = t[0];
  const Eigen::Vector3d& b = t[1];
  const Eigen::Vector3d& c = t[2];
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

/// Per texel of an RGB image: the standard deviation of the grey level (0..255) over the 7x7
/// window centred on it (windows clipped at the border).
inline std::vector<double> localStdDev(const visual::RgbImage& image, int radius = 3) {
  const int w = image.width, h = image.height;
  std::vector<double> sum((w + 1) * static_cast<std::size_t>(h + 1), 0.0);
  std::vector<double> sq(sum.size(), 0.0);
  auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * (w + 1) + x; };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::uint8_t* p = &image.pixels[3 * (static_cast<std::size_t>(y) * w + x)];
      const double g = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
      sum[at(x + 1, y + 1)] = g + sum[at(x, y + 1)] + sum[at(x + 1, y)] - sum[at(x, y)];
      sq[at(x + 1, y + 1)] = g * g + sq[at(x, y + 1)] + sq[at(x + 1, y)] - sq[at(x, y)];
    }
  }
  std::vector<double> out(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(w, x + radius + 1);
      const int y0 = std::max(0, y - radius), y1 = std::min(h, y + radius + 1);
      const double n = static_cast<double>(x1 - x0) * (y1 - y0);
      const double s = sum[at(x1, y1)] - sum[at(x0, y1)] - sum[at(x1, y0)] + sum[at(x0, y0)];
      const double s2 = sq[at(x1, y1)] - sq[at(x0, y1)] - sq[at(x1, y0)] + sq[at(x0, y0)];
      out[static_cast<std::size_t>(y) * w + x] =
          std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)));
    }
  }
  return out;
}

/// Texels of a mesh's texture that its triangles cover (rasterised in UV space).
inline std::vector<bool> uvCoverage(const visual::VisualMesh& mesh) {
  const int w = mesh.texture->width, h = mesh.texture->height;
  std::vector<bool> covered(static_cast<std::size_t>(w) * h, false);
  for (const auto& t : mesh.triangles) {
    std::array<Eigen::Vector2d, 3> p;
    for (int i = 0; i < 3; ++i) {
      p[i] = Eigen::Vector2d(mesh.uvs[t[i]].x() * w, mesh.uvs[t[i]].y() * h);
    }
    const double area =
        (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
    if (std::abs(area) < 1e-12) continue;
    const int x0 =
        std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
    const int x1 =
        std::min(w - 1, static_cast<int>(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 =
        std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
    const int y1 =
        std::min(h - 1, static_cast<int>(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d q(x + 0.5, y + 0.5);
        bool inside = true;
        for (int i = 0; i < 3 && inside; ++i) {
          const Eigen::Vector2d e = p[(i + 1) % 3] - p[i];
          const Eigen::Vector2d d = q - p[i];
          inside = (e.x() * d.y() - e.y() * d.x()) * area >= 0.0;
        }
        if (inside) covered[static_cast<std::size_t>(y) * w + x] = true;
      }
    }
  }
  return covered;
}

/// Fraction of the covered texels whose local standard deviation exceeds `threshold`.
inline double texturedFraction(const visual::VisualMesh& mesh, double threshold) {
  const auto stddev = localStdDev(*mesh.texture);
  const auto covered = uvCoverage(mesh);
  std::size_t n = 0, above = 0;
  for (std::size_t i = 0; i < covered.size(); ++i) {
    if (!covered[i]) continue;
    ++n;
    if (stddev[i] > threshold) ++above;
  }
  return n == 0 ? 0.0 : static_cast<double>(above) / n;
}

}  // namespace visgrab::test::objects
