// A generated database's index through visgrab::database::Database::open (the scratch folder
// is the database; the input is its index.xml), as every command that takes --db reads it.
// LoadError is the documented outcome for a corrupt index.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/database/database.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  visgrab::fuzz::writeScratchFile("index.xml", visgrab::fuzz::asText(data, size));
  try {
    const auto db = visgrab::database::Database::open(visgrab::fuzz::scratchDir());
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
