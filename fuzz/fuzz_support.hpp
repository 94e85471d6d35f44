#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

/// Helpers shared by the libFuzzer harnesses (docs/fuzzing.md).
namespace visgrab::fuzz {

/// The fuzzer's input as text (bytes as they are; no terminating zero is needed).
inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// This process's scratch folder, made on first use and removed when the process exits.
const std::filesystem::path& scratchDir();

/// Writes `bytes` to scratchDir()/`name` (replacing it) and returns the path.
/// Aborts if the file cannot be written: the harness could not test anything.
std::filesystem::path writeScratchFile(std::string_view name, std::string_view bytes);

/// Copies the files of the project folder `folder` (relative to the source tree, not recursive)
/// into scratchDir(), so that names in the input can refer to them. Aborts if it cannot.
void copyProjectFiles(std::string_view folder);

}  // namespace visgrab::fuzz
