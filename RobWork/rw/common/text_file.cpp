#include "rw/common/text_file.hpp"

#include "rw/common/diagnostic.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace rw::common {

namespace fs = std::filesystem;

std::string readTextFile(const fs::path& file, std::string& text) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) return "it is a folder, not a file";
  if (!fs::exists(file, ec)) return "no such file";
  errno = 0;
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    return std::string("it cannot be opened: ") +
           (errno != 0 ? std::strerror(errno) : "reason unknown");
  }
  text.clear();
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes) return "it is larger than 64 MiB";
  }
  if (in.bad()) return "reading it failed";
  return {};
}

std::string readTextFileOrThrow(const std::filesystem::path& file) {
  std::string text;
  const std::string why = readTextFile(file, text);
  if (!why.empty()) {
    Diagnostic d;
    d.file = file.string();
    d.message = "cannot read " + file.string() + ": " + why;
    throw LoadError({d});
  }
  return text;
}

}  // namespace rw::common
