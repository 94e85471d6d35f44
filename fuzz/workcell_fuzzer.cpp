// Workcell files (.wc.xml) through rw::loaders::loadWorkCell, the program's entry point. The
// input is written to the scratch folder, so Include and Polytope names resolve there (and fail
// unless they name the input itself); LoadError is the documented outcome for bad input.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "rw/loaders/workcell_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      visgrab::fuzz::writeScratchFile("fuzz.wc.xml", visgrab::fuzz::asText(data, size));
  std::vector<rw::common::Diagnostic> warnings;
  try {
    const auto workcell = rw::loaders::loadWorkCell(file, &warnings);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
