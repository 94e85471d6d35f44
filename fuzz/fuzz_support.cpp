#include "fuzz_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace visgrab::fuzz {

namespace {

std::filesystem::path& scratchPath() {
  static std::filesystem::path path;
  return path;
}

void removeScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(scratchPath(), ec);
}

}  // namespace

const std::filesystem::path& scratchDir() {
  std::filesystem::path& path = scratchPath();
  if (path.empty()) {
    std::error_code ec;
    std::string pattern =
        (std::filesystem::temp_directory_path(ec) / "visgrab-fuzz-XXXXXX").string();
    if (ec || ::mkdtemp(pattern.data()) == nullptr) {
      std::perror("visgrab fuzz: cannot make a scratch folder");
      std::abort();
    }
    path = pattern;
    std::atexit(removeScratchDir);
  }
  return path;
}

std::filesystem::path writeScratchFile(std::string_view name, std::string_view bytes) {
  std::filesystem::path file = scratchDir() / std::filesystem::path(name);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "visgrab fuzz: cannot write %s\n", file.c_str());
    std::abort();
  }
  return file;
}

void copyProjectFiles(std::string_view folder) {
  const std::filesystem::path from = std::filesystem::path(VISGRAB_SOURCE_DIR) / folder;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(from, ec)) {
    if (!entry.is_regular_file(ec)) continue;
    std::filesystem::copy_file(entry.path(), scratchDir() / entry.path().filename(),
                               std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) break;
  }
  if (ec) {
    std::fprintf(stderr, "visgrab fuzz: cannot copy %s: %s\n", from.c_str(), ec.message().c_str());
    std::abort();
  }
}

}  // namespace visgrab::fuzz
