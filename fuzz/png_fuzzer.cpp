// Images through visgrab::render::readPng (object textures, rendered pictures) and readImage
// (any format OpenCV decodes, as a database's scene images are read). std::runtime_error is the
// documented outcome for a file that is not a (decodable) image.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz_support.hpp"
#include "visgrab/render/png_io.hpp"

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
  return 0;
}
