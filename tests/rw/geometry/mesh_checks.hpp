#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <sstream>
#include <utility>

#include "rw/geometry/geometry.hpp"

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

}  // namespace visgrab::test
