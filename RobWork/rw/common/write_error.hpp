#pragma once

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace rw::common {

/// A file that could not be written, created, synced or renamed (disk full, folder deleted,
/// no permission): the file and the system's reason. Unlike bad input, which skips one item, it
/// stops the whole job: a run that goes on would only lose more.
class WriteError : public std::runtime_error {
 public:
  /// "cannot write <file>: <reason's message>".
  WriteError(std::filesystem::path file, std::error_code reason);
  /// The file.
  const std::filesystem::path& file() const { return file_; }
  /// The system's reason.
  const std::error_code& reason() const { return reason_; }

 private:
  std::filesystem::path file_;
  std::error_code reason_;
};

/// Throws WriteError for `file` with the reason in errno.
[[noreturn]] void throwWriteError(const std::filesystem::path& file);

}  // namespace rw::common
