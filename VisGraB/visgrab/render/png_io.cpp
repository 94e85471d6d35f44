#include "visgrab/render/png_io.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "rw/common/write_error.hpp"

namespace visgrab::render {

namespace {

std::vector<std::uint8_t> readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the file");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

constexpr std::array<std::uint8_t, 8> kPngSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

/// Largest image we decode, in pixels (the rendered pictures and textures are far below it):
/// OpenCV allocates the whole image from the size in the header before it reads the pixels,
/// so a 60-byte file announcing 30000 x 30000 pixels would take 2.7 GB.
constexpr std::uint64_t kMaxPixels = std::uint64_t{1} << 26U;

std::uint64_t bigEndian32(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value = (value << 8U) | bytes[at + i];
  return value;
}

/// Rejects a PNG whose header (IHDR) announces more than kMaxPixels pixels.
void checkPngSize(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() < 24 || std::memcmp(bytes.data(), kPngSignature.data(), 8) != 0 ||
      std::memcmp(bytes.data() + 12, "IHDR", 4) != 0) {
    return;  // not a PNG with a header: the decoder says what is wrong
  }
  const std::uint64_t width = bigEndian32(bytes, 16);
  const std::uint64_t height = bigEndian32(bytes, 20);
  if (width > kMaxPixels || height > kMaxPixels || width * height > kMaxPixels) {
    throw std::runtime_error(path.string() + ": the PNG announces " + std::to_string(width) +
                             " x " + std::to_string(height) + " pixels, more than the " +
                             std::to_string(kMaxPixels) + " this reader accepts");
  }
}

visual::RgbImage decode(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  checkPngSize(path, bytes);
  cv::Mat bgr;
  try {
    bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path.string() + ": cannot decode the image: " + e.what());
  }
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw std::runtime_error(path.string() + ": cannot decode the image (corrupt or truncated)");
  }
  visual::RgbImage image;
  image.width = bgr.cols;
  image.height = bgr.rows;
  image.pixels.resize(static_cast<std::size_t>(bgr.cols) * static_cast<std::size_t>(bgr.rows) * 3);
  cv::Mat rgb(bgr.rows, bgr.cols, CV_8UC3, image.pixels.data());
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return image;
}

}  // namespace

void writePng(const std::filesystem::path& path, const visual::RgbImage& image, int compression) {
  if (image.empty() || image.pixels.size() != static_cast<std::size_t>(image.width) *
                                                  static_cast<std::size_t>(image.height) * 3) {
    throw std::invalid_argument("writePng: " + path.string() + ": empty or inconsistent image");
  }
  if (compression < 0 || compression > 9) {
    throw std::invalid_argument("writePng: compression level " + std::to_string(compression) +
                                " outside 0..9");
  }
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-const-cast): cv::Mat wraps without copying.
  const cv::Mat rgb(image.height, image.width, CV_8UC3,
                    const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<std::uint8_t> bytes;
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, compression};
  if (!cv::imencode(".png", bgr, bytes, params)) {
    throw std::runtime_error(path.string() + ": cannot encode the PNG");
  }
  errno = 0;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  out.close();
  // The stream keeps no reason; errno holds the failed system call's (EIO if none set it).
  if (!out) throw rw::common::WriteError(path, {errno != 0 ? errno : EIO, std::generic_category()});
}

visual::RgbImage readPng(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = readBytes(path);
  if (bytes.size() < kPngSignature.size() ||
      std::memcmp(bytes.data(), kPngSignature.data(), kPngSignature.size()) != 0) {
    throw std::runtime_error(path.string() + ": not a PNG file");
  }
  return decode(path, bytes);
}

visual::RgbImage readImage(const std::filesystem::path& path) {
  return decode(path, readBytes(path));
}

}  // namespace visgrab::render
