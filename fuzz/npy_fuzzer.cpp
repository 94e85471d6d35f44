// The NPY reader (visgrab::importers::parseNpy) on raw bytes: ImportError is the documented
// outcome for anything that is not a readable numeric array.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "visgrab/importers/npy.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto array = visgrab::importers::parseNpy(visgrab::fuzz::asText(data, size), "fuzz.npy");
  } catch (const visgrab::importers::ImportError&) {
  }
  return 0;
}
