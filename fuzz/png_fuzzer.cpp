// Images through visgrab::render::readPng (object textures, rendered pictures), readImage (any
// format OpenCV decodes) and visgrab::database::Database::leftImage (a scene's stereo image; the
// scratch folder is a one-scene database whose left image is the input). std::runtime_error
// (readPng, readImage) and DatabaseError are the documented outcomes for a file that is not a
// decodable image.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include "fuzz_support.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/render/png_io.hpp"

namespace {

constexpr const char* kSceneId = "textured/single/cocacola/03";

constexpr const char* kIndex = R"(<?xml version="1.0" encoding="UTF-8"?>
<VisGraBDatabase formatVersion="1" seed="1" generator="fuzz">
  <Scene id="textured/single/cocacola/03" texture="textured" kind="single" arrangement="standing" pose="3">
    <Files left="image.png" right="image.png" calibration="calibration.yml" workcell="scene.wc.xml"
           dynamicWorkcell="scene.dwc.xml"/>
    <Object id="5" name="cocacola"><Pos>0 0 0</Pos><RPY>0 0 0</RPY></Object>
  </Scene>
</VisGraBDatabase>
)";

std::optional<visgrab::database::Database>& database() {
  static std::optional<visgrab::database::Database> db;
  return db;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  visgrab::fuzz::writeScratchFile("index.xml", kIndex);
  database() = visgrab::database::Database::open(visgrab::fuzz::scratchDir());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = visgrab::fuzz::writeScratchFile("image.png", visgrab::fuzz::asText(data, size));
  try {
    const auto image = visgrab::render::readPng(file);
  } catch (const std::runtime_error&) {
  }
  try {
    const auto image = visgrab::render::readImage(file);
  } catch (const std::runtime_error&) {
  }
  try {
    const auto image = database()->leftImage(kSceneId);
  } catch (const visgrab::database::DatabaseError&) {
  }
  return 0;
}
