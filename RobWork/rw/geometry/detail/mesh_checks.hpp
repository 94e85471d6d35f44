#pragma once

#include <filesystem>

namespace rw::geometry::detail {

/// The checks loadMesh makes before it lets assimp read `file`, for other code that hands mesh
/// files to assimp (the renderer): .stl/.stla/.stlb must be a well-formed STL, .ply/.ac/.ac3d
/// must be read by our own reader without error. Other formats are not checked.
/// @throws MeshLoadError naming the file (and line) and what is wrong.
void checkBeforeAssimp(const std::filesystem::path& file);

}  // namespace rw::geometry::detail
