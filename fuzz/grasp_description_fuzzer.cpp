// A hand's grasp description (<hand>.grasp.xml) through visgrab::grasp::loadHandGraspSetup, as
// --hand reads it. The scratch folder holds the project's three hands (scenes/hands/*: their
// workcells, dynamics and collision setups), so that a description naming one of them is
// checked against the hand too. LoadError is the documented outcome.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  for (const char* hand : {"scenes/hands/pg70", "scenes/hands/sdh", "scenes/hands/robotiq2f85"}) {
    visgrab::fuzz::copyProjectFiles(hand);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      visgrab::fuzz::writeScratchFile("fuzz.grasp.xml", visgrab::fuzz::asText(data, size));
  try {
    const auto setup = visgrab::grasp::loadHandGraspSetup(file);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
