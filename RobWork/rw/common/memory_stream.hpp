#pragma once

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace rw::common {

/// A C stdio stream that writes into memory (POSIX open_memstream), for libraries that report
/// through a FILE* (Qhull's error stream): file() to hand over, text() to read what was written.
/// If the memory stream cannot be opened, file() is stderr and text() is empty.
class MemoryStream {
 public:
  MemoryStream() : file_(open_memstream(&buffer_, &size_)) {}
  ~MemoryStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);  // open_memstream allocates with malloc
  }
  MemoryStream(const MemoryStream&) = delete;
  MemoryStream& operator=(const MemoryStream&) = delete;
  /// The stream to write to.
  FILE* file() const { return file_ != nullptr ? file_ : stderr; }
  /// Everything written so far.
  std::string text() {
    if (file_ == nullptr) return {};
    std::fflush(file_);
    return {buffer_, size_};
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
};

}  // namespace rw::common
