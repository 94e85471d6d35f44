#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "rw/geometry/mesh_parts.hpp"

namespace rw::geometry {

/// Reads the PLY file `file` whose bytes are `bytes` (ASCII, binary little or big endian): the
/// x, y, z of element `vertex` and the `vertex_indices` (or `vertex_index`) lists of element
/// `face`, polygons triangulated as assimp does; every other element and property is skipped.
/// Faces of 1 or 2 corners are dropped, a face of none is an error (assimp aborts on one). An
/// ASCII body has one entry per line and nothing after the last element. Gives one part
/// (vertices rounded to float).
/// @throws MeshLoadError naming the file and the line (ASCII) or byte offset (binary) and what
///   was expected: bad header, unknown type, counts larger than the rest of the file could hold,
///   a truncated body, a value that is not a number, a non-finite coordinate, an index out of
///   range.
std::vector<MeshPart> readPly(const std::filesystem::path& file, std::string_view bytes);

}  // namespace rw::geometry
