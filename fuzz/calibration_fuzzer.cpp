// A scene's stereo calibration (OpenCV FileStorage YAML) through
// visgrab::database::readCalibration, as Database::calibration reads it. CalibrationError is the
// documented outcome for a file that cannot be read.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "visgrab/database/stereo_calibration.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      visgrab::fuzz::writeScratchFile("calibration.yml", visgrab::fuzz::asText(data, size));
  try {
    const auto calibration = visgrab::database::readCalibration(file);
  } catch (const visgrab::database::CalibrationError&) {
  }
  return 0;
}
