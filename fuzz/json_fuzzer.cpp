// GraspGen's .json grasp files: the strict JSON reader (visgrab::importers::parseJson) on the raw
// bytes, then the bytes as a file through the ACRONYM importer (importAcronym: grasps.transforms
// to jaw grasps) and readAcronymLabels (grasps.object_in_gripper), as `visgrab import acronym`
// reads them. ImportError is the documented outcome. The importer tells JSON from HDF5 by the
// first byte that is not white space ('{' is JSON); other inputs do not reach it here (the hdf5
// harness covers that reader).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.hpp"
#include "visgrab/importers/acronym.hpp"
#include "visgrab/importers/grasp_importers.hpp"
#include "visgrab/importers/json_value.hpp"

namespace {

bool startsAsJsonObject(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && text[first] == '{';
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = visgrab::fuzz::asText(data, size);
  try {
    const auto doc = visgrab::importers::parseJson(text, "fuzz.json");
  } catch (const visgrab::importers::ImportError&) {
  }
  if (!startsAsJsonObject(text)) return 0;
  const auto file = visgrab::fuzz::writeScratchFile("fuzz.json", text);
  visgrab::importers::ImportContext context;
  context.jaw.stroke = visgrab::importers::kPandaOpening;
  try {
    const auto result =
        visgrab::importers::importAcronym(file, rw::math::Transform3D::Identity(), context);
  } catch (const visgrab::importers::ImportError&) {
  }
  try {
    const auto labels = visgrab::importers::readAcronymLabels(file);
  } catch (const visgrab::importers::ImportError&) {
  }
  return 0;
}
