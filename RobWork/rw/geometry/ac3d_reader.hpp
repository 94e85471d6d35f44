#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "rw/geometry/mesh_parts.hpp"

namespace rw::geometry {

/// How deep AC3D objects may nest (kids of kids ...); deeper files are refused.
constexpr int kMaxAc3dDepth = 64;

/// Reads the AC3D file `file` whose bytes are `bytes` (header "AC3D" and a hex version digit):
/// MATERIAL lines, OBJECT world/poly/group/light with name, data, texture, texrep, texoff, rot,
/// loc, crease, url, numvert, numsurf and kids (children read recursively, at most
/// kMaxAc3dDepth deep). Gives one part per object with polygon surfaces, placed by its and its
/// parents' rot (nine numbers, row by row) and loc: p_parent = rot * p + loc. Polygon surfaces
/// (type 0) are triangulated as assimp does; closed-line and line surfaces (types 1, 2) and
/// polygons of fewer than 3 corners give no triangles. `subdiv` above 0 is refused (assimp
/// would subdivide the surface, we do not).
/// @throws MeshLoadError naming the file and line and what was expected for anything else:
///   unknown keywords, counts larger than the rest of the file could hold, a truncated file,
///   numbers that are not finite, material or vertex indices out of range.
std::vector<MeshPart> readAc3d(const std::filesystem::path& file, std::string_view bytes);

}  // namespace rw::geometry
