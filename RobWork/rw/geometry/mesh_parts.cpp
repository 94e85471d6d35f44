#include "rw/geometry/mesh_parts.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "rw/geometry/mesh_loader.hpp"

namespace rw::geometry {
namespace {

using rw::math::Vector3D;

/// Twice the signed area of the 2D triangle (a, b, c): positive when it turns left.
double twiceArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
}

/// True when `p` lies strictly inside the triangle (a, b, c), by barycentric coordinates.
bool strictlyInside(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& p) {
  const Eigen::Vector2d v0 = b - a;
  const Eigen::Vector2d v1 = c - a;
  const Eigen::Vector2d v2 = p - a;
  const double d00 = v0.dot(v0);
  const double d01 = v0.dot(v1);
  const double d02 = v0.dot(v2);
  const double d11 = v1.dot(v1);
  const double d12 = v1.dot(v2);
  const double inverse = 1.0 / (d00 * d11 - d01 * d01);
  const double u = (d11 * d02 - d01 * d12) * inverse;
  const double v = (d00 * d12 - d01 * d02) * inverse;
  return u > 0.0 && v > 0.0 && u + v < 1.0;
}

/// The quad's corner at which it is concave (the two angles next to the diagonal from it add up
/// to more than pi), or 0 for a convex quad. Computed in float as assimp does, so that a quad
/// with a straight corner is cut where assimp cut it.
std::size_t concaveCorner(std::span<const Vector3D> vertices, std::span<const std::uint32_t> q) {
  const auto at = [&](std::size_t i) { return vertices[q[i % 4]].cast<float>(); };
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3f v = at(i);
    const Eigen::Vector3f left = (at(i + 3) - v).normalized();
    const Eigen::Vector3f diagonal = (at(i + 2) - v).normalized();
    const Eigen::Vector3f right = (at(i + 1) - v).normalized();
    // Not clamped, as in assimp: a rounded cosine beyond +-1 gives NaN, which is not concave.
    const float angle = std::acos(left.dot(diagonal)) + std::acos(right.dot(diagonal));
    if (angle > std::numbers::pi_v<float>) return i;
  }
  return 0;
}

/// The polygon's corners projected onto the coordinate plane its Newell normal is closest to,
/// the axes ordered so that the polygon turns left (counter-clockwise) in the projection.
std::vector<Eigen::Vector2d> project(std::span<const Vector3D> vertices,
                                     std::span<const std::uint32_t> corners) {
  Vector3D normal = Vector3D::Zero();
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Vector3D& a = vertices[corners[i]];
    const Vector3D& b = vertices[corners[(i + 1) % corners.size()]];
    normal += Vector3D((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                       (a.x() - b.x()) * (a.y() + b.y()));
  }
  const Vector3D magnitude = normal.cwiseAbs();
  int first = 0;
  int second = 1;
  double sign = normal.z();
  if (magnitude.x() > magnitude.y()) {
    if (magnitude.x() > magnitude.z()) {
      first = 1;
      second = 2;
      sign = normal.x();
    }
  } else if (magnitude.y() > magnitude.z()) {
    first = 2;
    second = 0;
    sign = normal.y();
  }
  if (sign < 0.0) std::swap(first, second);
  std::vector<Eigen::Vector2d> points;
  points.reserve(corners.size());
  for (const std::uint32_t c : corners) {
    points.emplace_back(vertices[c][first], vertices[c][second]);
  }
  return points;
}

/// True when the corner `ear` (between `prev` and `next`) cuts off a convex (or flat) triangle that
/// holds no other corner of the polygon (compared by position, so repeated positions do not count).
bool isEar(const std::vector<Eigen::Vector2d>& points, std::size_t prev, std::size_t ear,
           std::size_t next, std::int64_t& budget) {
  const Eigen::Vector2d& a = points[prev];
  const Eigen::Vector2d& b = points[ear];
  const Eigen::Vector2d& c = points[next];
  if (twiceArea(a, b, c) < 0.0) return false;  // reflex; a straight corner counts, as in assimp
  budget -= static_cast<std::int64_t>(points.size());
  for (const Eigen::Vector2d& p : points) {
    if (p != a && p != b && p != c && strictlyInside(a, b, c, p)) return false;
  }
  return true;
}

/// Ear clipping of a polygon of more than 4 corners; false when the budget runs out.
bool clipEars(std::span<const Vector3D> vertices, std::span<const std::uint32_t> corners,
              std::vector<std::array<std::uint32_t, 3>>& out, std::int64_t& budget) {
  const std::vector<Eigen::Vector2d> points = project(vertices, corners);
  const std::size_t n = corners.size();
  std::vector<bool> done(n, false);
  std::size_t left = n;
  std::size_t prev = n - 1;
  std::size_t next = 0;
  while (left > 3) {
    std::size_t ear = next;
    int wraps = 0;
    for (;; prev = ear, ear = next) {
      if (--budget <= 0) return false;  // every step counts, reflex corners too
      next = ear + 1;
      while (done[next % n]) ++next;
      next %= n;
      if (next < ear && ++wraps == 2) break;
      if (isEar(points, prev, ear, next, budget)) break;
      if (budget <= 0) return false;
    }
    if (wraps == 2) return true;  // no ear: not a simple polygon; assimp keeps what it has
    out.push_back({corners[prev], corners[ear], corners[next]});
    done[ear] = true;
    --left;
  }
  std::array<std::uint32_t, 3> last{};
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!done[i]) last[k++] = corners[i];
  }
  out.push_back(last);
  return true;
}

}  // namespace

bool triangulatePolygon(std::span<const Vector3D> vertices, std::span<const std::uint32_t> corners,
                        std::vector<std::array<std::uint32_t, 3>>& out, std::int64_t& budget) {
  if (corners.size() == 3) {
    out.push_back({corners[0], corners[1], corners[2]});
  } else if (corners.size() == 4) {
    const std::size_t s = concaveCorner(vertices, corners);
    out.push_back({corners[s], corners[(s + 1) % 4], corners[(s + 2) % 4]});
    out.push_back({corners[s], corners[(s + 2) % 4], corners[(s + 3) % 4]});
  } else if (corners.size() > 4) {
    budget -= static_cast<std::int64_t>(corners.size());
    if (budget <= 0 || !clipEars(vertices, corners, out, budget)) return false;
  }
  return budget > 0;
}

std::string shown(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  std::string out = "\"";
  for (const char c : text.substr(0, kMaxShown)) {
    const auto u = static_cast<unsigned char>(c);
    out.push_back(u >= 0x20 && u < 0x7F ? c : '?');
  }
  if (text.size() > kMaxShown) out += "...";
  return out + "\"";
}

void failAtLine(const std::filesystem::path& file, std::size_t line, const std::string& what) {
  throw MeshLoadError(file.string() + ":" + std::to_string(line) + ": error: " + what);
}

void failAtByte(const std::filesystem::path& file, std::size_t offset, const std::string& what) {
  throw MeshLoadError(file.string() + ": error: at byte " + std::to_string(offset) + ": " + what);
}

}  // namespace rw::geometry
