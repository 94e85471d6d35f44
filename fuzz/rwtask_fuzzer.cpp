// RobWork task files (.rwtask.xml) through visgrab::taskio::readGraspFile (--grasps, which detects
// the format and turns the targets into grasp requests) and readRwTask (the task itself).
// LoadError is the documented outcome for a malformed file.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/taskio/grasp_file.hpp"
#include "visgrab/taskio/rwtask_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      visgrab::fuzz::writeScratchFile("fuzz.rwtask.xml", visgrab::fuzz::asText(data, size));
  try {
    const auto contents = visgrab::taskio::readGraspFile(file);
  } catch (const rw::common::LoadError&) {
  }
  try {
    const auto direct = visgrab::taskio::readRwTask(file);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
