// The original VisGraB experiment XML through visgrab::taskio::readGraspFile (--grasps, which
// detects the format) and readExperimentXml. LoadError is the documented outcome for a malformed
// file; rejected grasps are diagnostics in the result.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/taskio/experiment_xml.hpp"
#include "visgrab/taskio/grasp_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = visgrab::fuzz::writeScratchFile("fuzz.xml", visgrab::fuzz::asText(data, size));
  try {
    const auto contents = visgrab::taskio::readGraspFile(file);
  } catch (const rw::common::LoadError&) {
  }
  try {
    const auto direct = visgrab::taskio::readExperimentXml(file);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
