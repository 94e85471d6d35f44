// The object database description (scenes/objects/objects.xml) through
// visgrab::objects::loadObjectSpecs, as the generator reads it. LoadError is the documented
// outcome.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/objects/object_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      visgrab::fuzz::writeScratchFile("objects.xml", visgrab::fuzz::asText(data, size));
  try {
    const auto spec = visgrab::objects::loadObjectSpecs(file);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
