#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/geometry/mesh_loader.hpp"

/// Independent checks on triangle meshes shared by the geometry tests.
namespace visgrab::test {

/// Signed volume by the divergence theorem: sum of v0 . (v1 x v2) / 6 (> 0 for outward winding).
inline double signedVolume(const rw::geometry::TriMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const auto& a = mesh.vertices[t[0]];
    const auto& b = mesh.vertices[t[1]];
    const auto& c = mesh.vertices[t[2]];
    sum += a.dot(b.cross(c));
  }
  return sum / 6.0;
}

/// Succeeds when every directed edge a->b occurs exactly once and its reverse b->a exactly once:
/// the mesh is closed (each edge shared by two triangles) and consistently wound.
inline ::testing::AssertionResult isClosedAndConsistent(const rw::geometry::TriMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    const int reverseCount = reverse == directed.end() ? 0 : reverse->second;
    if (count != 1 || reverseCount != 1) {
      std::ostringstream os;
      os << "edge " << edge.first << "->" << edge.second << " occurs " << count
         << " times, its reverse " << reverseCount << " times";
      return ::testing::AssertionFailure() << os.str();
    }
  }
  return ::testing::AssertionSuccess();
}

/// A triangle's nine corner coordinates.
using Triangle = std::array<double, 9>;

/// A triangle's corners starting at its lexicographically smallest one (winding kept).
inline Triangle canonical(const rw::math::Vector3D& a, const rw::math::Vector3D& b,
                          const rw::math::Vector3D& c) {
  std::array<std::array<double, 3>, 3> corners = {
      {{a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}, {c.x(), c.y(), c.z()}}};
  std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
  Triangle t{};
  for (int k = 0; k < 9; ++k) t[k] = corners[k / 3][k % 3];
  return t;
}

/// The mesh's triangles as sorted corner coordinates, for exact comparison.
inline std::vector<Triangle> trianglesOf(const rw::geometry::TriMesh& mesh) {
  std::vector<Triangle> result;
  for (const auto& t : mesh.triangles) {
    result.push_back(canonical(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
  }
  std::sort(result.begin(), result.end());
  return result;
}

/// Sorted canonical triangles of the given corner triples, for comparison with trianglesOf.
inline std::vector<Triangle> trianglesFrom(
    const std::vector<std::array<rw::math::Vector3D, 3>>& corners) {
  std::vector<Triangle> result;
  for (const auto& c : corners) result.push_back(canonical(c[0], c[1], c[2]));
  std::sort(result.begin(), result.end());
  return result;
}

/// Expects loadMesh(file) to throw MeshLoadError starting "<file><where>: " (where is ":<line>"
/// or empty) and containing `fragment`.
inline void expectLocatedError(const std::filesystem::path& file, const std::string& where,
                               const std::string& fragment) {
  try {
    rw::geometry::loadMesh(file);
    ADD_FAILURE() << file << " loaded, expected an error containing: " << fragment;
  } catch (const rw::geometry::MeshLoadError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(file.string() + where + ": ", 0), 0U) << what;
    EXPECT_NE(what.find("error: "), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

}  // namespace visgrab::test
