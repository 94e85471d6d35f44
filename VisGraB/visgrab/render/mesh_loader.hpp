#pragma once

#include <filesystem>
#include <vector>

#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::render {

/// Reads a mesh file with assimp (OBJ with its .mtl and textures, STL, PLY, AC3D and the other
/// formats assimp reads) into one VisualMesh per assimp mesh, with node transforms applied.
/// First the file passes the checks rw::geometry::loadMesh makes (rw/geometry/detail/
/// mesh_checks.hpp): an STL its structure check, a PLY or AC3D file our own reader in full
/// (assimp loops or allocates tens of GB on some malformed ones), so a bad file is refused with
/// its line before assimp sees it.
///
/// Each mesh gets its material's diffuse colour (Kd), a specular strength from Ks (mean of its
/// components, clamped to [0, 1]) and, if the material names one, its diffuse texture (read
/// relative to the mesh file's folder; one shared image per distinct file). Texture coordinates
/// are converted from assimp's (and OBJ's) v-up convention to VisualMesh's v-down one
/// (v = 1 - v_obj). Missing normals are computed (smooth); polygons are triangulated; points
/// and lines are dropped.
/// @throws std::runtime_error naming the file and what is wrong: missing file, a file our checks
///   (rw::geometry::MeshLoadError, with the line) or assimp cannot parse, no triangle meshes, a
///   missing or unreadable texture file.
std::vector<visual::VisualMesh> loadVisualMeshes(const std::filesystem::path& path);

}  // namespace visgrab::render
