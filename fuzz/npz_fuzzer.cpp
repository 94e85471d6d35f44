// The NPZ reader (a zip through libzip, each member through the NPY reader) and the
// Contact-GraspNet importer on it, from memory. ImportError is the documented outcome.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "visgrab/importers/grasp_importers.hpp"
#include "visgrab/importers/npz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto npz =
        visgrab::importers::NpzFile::fromBytes(visgrab::fuzz::asText(data, size), "fuzz.npz");
    for (const auto& name : npz.names()) {
      try {
        const auto array = npz.array(name);
      } catch (const visgrab::importers::ImportError&) {
      }
    }
  } catch (const visgrab::importers::ImportError&) {
  }
  // The importer reads the same bytes from a file, as the CLI does.
  const auto file = visgrab::fuzz::writeScratchFile("fuzz.npz", visgrab::fuzz::asText(data, size));
  visgrab::importers::ImportContext context;
  context.jaw.stroke = 0.08;
  try {
    const auto result =
        visgrab::importers::importContactGraspnet(file, rw::math::Transform3D::Identity(), context);
  } catch (const visgrab::importers::ImportError&) {
  }
  return 0;
}
