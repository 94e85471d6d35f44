#pragma once

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rw/math/types.hpp"

namespace rw::geometry {

/// Triangles of one object of a mesh file as our own readers give them: vertices in the object's
/// frame, corners as the file winds them, and the object's pose in the file's frame.
struct MeshPart {
  /// The object's pose in the file's frame (AC3D: its and its parents' rot and loc).
  Eigen::Affine3d X_FO = Eigen::Affine3d::Identity();
  /// Vertex positions in the object's frame, each rounded to float as assimp stored them.
  std::vector<rw::math::Vector3D> vertices;
  /// Triangles as zero-based indices into `vertices`.
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Splits the polygon with corners `corners` (indices into `vertices`, at least 3) into triangles
/// appended to `out`, as assimp's aiProcess_Triangulate does: a triangle is kept, a quad is cut
/// at its concave corner (or at corner 0), a larger polygon is ear-clipped in the plane its
/// Newell normal is closest to, ears taken in order starting at corner 0 with the last corner as
/// its neighbour (a flat corner counts as convex); when no ear is left (a polygon that is not
/// simple) the triangles cut so far are kept and the rest is dropped, as assimp 5.2 does.
/// `budget` is decremented by the work done and must stay positive.
/// @returns false when the work would exceed `budget` (the caller reports it).
bool triangulatePolygon(std::span<const rw::math::Vector3D> vertices,
                        std::span<const std::uint32_t> corners,
                        std::vector<std::array<std::uint32_t, 3>>& out, std::int64_t& budget);

/// Work allowed for triangulating one file's polygons (point-in-triangle tests, about 2^30:
/// seconds at most; a convex polygon of n corners needs about n^2, a concave one up to n^3).
constexpr std::int64_t kTriangulationBudget = std::int64_t{1} << 30;

/// `value` rounded to float and back, as assimp (which reads in float) stores coordinates.
inline double asFloat(double value) { return static_cast<double>(static_cast<float>(value)); }

/// `text` in double quotes for a message: at most 40 characters, unprintable ones as '?'.
std::string shown(std::string_view text);

/// Throws MeshLoadError "<file>:<line>: error: <what>".
[[noreturn]] void failAtLine(const std::filesystem::path& file, std::size_t line,
                             const std::string& what);

/// Throws MeshLoadError "<file>: error: at byte <offset>: <what>".
[[noreturn]] void failAtByte(const std::filesystem::path& file, std::size_t offset,
                             const std::string& what);

}  // namespace rw::geometry
