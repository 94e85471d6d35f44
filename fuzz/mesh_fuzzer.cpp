// Mesh files through rw::geometry::loadMesh, as a workcell's <Polytope> reads them (PLY and AC3D
// by our own readers, the rest by assimp). The first input byte picks the file name's extension
// (the loader chooses its reader by it; the seeds start with that byte, see scripts/fuzz.sh),
// the rest is the file. MeshLoadError is the documented outcome for bad input. A file loadMesh
// accepts also goes through the renderer's visgrab::render::loadVisualMeshes (the same checks,
// then assimp for PLY and AC3D too), whose documented error is std::runtime_error.
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_support.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "visgrab/render/mesh_loader.hpp"

namespace {

constexpr std::array<const char*, 8> kExtensions = {".stl", ".obj", ".ply", ".ac",
                                                    ".off", ".3ds", ".dae", ".stlb"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string name = std::string("mesh") + kExtensions[data[0] % kExtensions.size()];
  const auto file =
      visgrab::fuzz::writeScratchFile(name, visgrab::fuzz::asText(data + 1, size - 1));
  try {
    const auto mesh = rw::geometry::loadMesh(file);
  } catch (const rw::geometry::MeshLoadError&) {
    return 0;
  }
  try {
    const auto meshes = visgrab::render::loadVisualMeshes(file);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
