#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace rw::common {

/// Largest input file the loaders read (protection against runaway inputs).
inline constexpr std::size_t kMaxFileBytes = std::size_t{64} << 20;

/// Reads a whole file into `text`. Returns an empty string on success, otherwise why it could
/// not be read ("no such file", "it is a folder, not a file", "it is larger than 64 MiB", ...),
/// phrased to follow "cannot read FILE: ".
std::string readTextFile(const std::filesystem::path& file, std::string& text);

/// The whole file. @throws rw::common::LoadError naming the file and why it cannot be read.
std::string readTextFileOrThrow(const std::filesystem::path& file);

}  // namespace rw::common
