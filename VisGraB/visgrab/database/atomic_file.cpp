#include "visgrab/database/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "rw/common/write_error.hpp"

namespace visgrab::database {

namespace fs = std::filesystem;

namespace {

std::atomic<unsigned> temporaryCounter{0};

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
  throw std::runtime_error("cannot write " + file.string() + ": " + why);
}

[[noreturn]] void fail(const fs::path& file, std::error_code why) {
  throw rw::common::WriteError(file, why);
}

std::error_code lastError() { return {errno, std::generic_category()}; }

}  // namespace

void writeFileAtomically(const fs::path& file, std::string_view bytes) {
  std::error_code ec;
  if (file.has_parent_path()) {
    fs::create_directories(file.parent_path(), ec);
    if (ec) fail(file.parent_path(), ec);
  }
  const fs::path temporary =
      file.parent_path() / ("." + file.filename().string() + ".tmp" + std::to_string(::getpid()) +
                            "-" + std::to_string(temporaryCounter++));
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(file, lastError());
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::error_code why = lastError();
      ::close(fd);
      fs::remove(temporary, ec);
      fail(file, why);
    }
    written += static_cast<std::size_t>(n);
  }
  // Close even when the sync failed (the descriptor must not leak); the first failure counts.
  std::error_code why;
  if (::fsync(fd) != 0) why = lastError();
  if (::close(fd) != 0 && !why) why = lastError();
  if (why) {
    fs::remove(temporary, ec);
    fail(file, why);
  }
  fs::rename(temporary, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    fail(file, ec);
  }
}

void writeImageAtomically(const fs::path& file, const cv::Mat& image, PngCompression png) {
  std::vector<uchar> encoded;
  bool ok = false;
  try {
    const std::string ext = file.extension().string();
    std::vector<int> params;
    if (ext == ".png" || ext == ".PNG") {
      // OpenCV resets the strategy when it reads the level: the strategy must come after it.
      params = {cv::IMWRITE_PNG_COMPRESSION, 9};
      if (png == PngCompression::kHuffmanOnly) {
        params.insert(params.end(),
                      {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY});
      } else if (png == PngCompression::kRle) {
        params.insert(params.end(), {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_RLE});
      }
    }
    ok = !image.empty() && cv::imencode(ext, image, encoded, params);
  } catch (const cv::Exception& e) {
    fail(file, "the image cannot be encoded: " + e.msg);
  }
  if (!ok) fail(file, "the image cannot be encoded as " + file.extension().string());
  writeFileAtomically(
      file, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

}  // namespace visgrab::database
