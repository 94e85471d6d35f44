// The plain grasp list (docs/grasp-format.md) through visgrab::taskio::readGraspFile (--grasps,
// which detects the format) and readGraspList. Bad lines are diagnostics in the result; LoadError
// is the documented outcome for a file that is XML but malformed.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/taskio/grasp_file.hpp"
#include "visgrab/taskio/grasp_list.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = visgrab::fuzz::writeScratchFile("fuzz.csv", visgrab::fuzz::asText(data, size));
  try {
    const auto contents = visgrab::taskio::readGraspFile(file);
  } catch (const rw::common::LoadError&) {
  }
  try {
    const auto direct = visgrab::taskio::readGraspList(file);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
