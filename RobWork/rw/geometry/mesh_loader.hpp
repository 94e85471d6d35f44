#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "rw/geometry/geometry.hpp"

namespace rw::geometry {

/// Thrown when a mesh file cannot be read; what() names the file and the reason.
class MeshLoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Which use a mesh file is resolved for: RobWork prefers STL for collision and AC3D for drawing.
enum class MeshUse { kCollision, kVisual };

/// Resolves a `<Polytope file="...">` name the way RobWork does (reference §1.3): the name as
/// given if it is a file, otherwise the name plus each extension in the order for `use`
/// (collision: .stl .stla .stlb .pcd .tri .dae .ac .ac3d .3ds .obj, also .ply; visual: .tri .ac
/// .ac3d .3ds .obj .ivg .dae .stl .stla .stlb .pcd .ply), each tried as written, lower and upper
/// case. Relative names are taken against `baseDir`. Returns nullopt if nothing exists.
std::optional<std::filesystem::path> resolveMeshFile(const std::filesystem::path& baseDir,
                                                     const std::string& name, MeshUse use);

/// Reads a triangle mesh, merging all sub-meshes with their node transforms, identical vertices
/// joined (by position). PLY (.ply) and AC3D (.ac, .ac3d) are read by our own readers
/// (ply_reader.hpp, ac3d_reader.hpp: the triangles assimp gave, coordinates in float as there);
/// STL (ascii or binary, checked first), OBJ and anything else assimp reads by assimp. Units are
/// kept (metres).
/// @throws MeshLoadError naming the file when it is missing, unreadable, empty or not a mesh;
///   for PLY and AC3D also the line (or byte offset) and what was expected there.
std::shared_ptr<const TriMesh> loadMesh(const std::filesystem::path& file);

}  // namespace rw::geometry
