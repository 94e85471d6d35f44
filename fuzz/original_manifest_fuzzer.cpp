// An original VisGraB benchmark manifest through
// visgrab::database::Database::openOriginalManifest (which also derives each scene's
// conditions), as --db MANIFEST.xml reads it. LoadError is the documented outcome.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/database/database.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      visgrab::fuzz::writeScratchFile("manifest.xml", visgrab::fuzz::asText(data, size));
  try {
    const auto db = visgrab::database::Database::openOriginalManifest(file);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
