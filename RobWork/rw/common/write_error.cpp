#include "rw/common/write_error.hpp"

#include <cerrno>
#include <utility>

namespace rw::common {

WriteError::WriteError(std::filesystem::path file, std::error_code reason)
    : std::runtime_error("cannot write " + file.string() + ": " + reason.message()),
      file_(std::move(file)),
      reason_(reason) {}

void throwWriteError(const std::filesystem::path& file) {
  throw WriteError(file, std::error_code(errno, std::generic_category()));
}

}  // namespace rw::common
