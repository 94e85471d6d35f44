#pragma once

#include <filesystem>
#include <string_view>

namespace cv {
class Mat;
}

namespace visgrab::database {

/// Writes `bytes` to `file` atomically: into a temporary file in the same folder, flushed to
/// disk, then renamed over `file`. Readers see the old or the new content, never a part.
/// Creates missing parent folders. @throws rw::common::WriteError (the file and the system's
/// reason) if it cannot be written, std::runtime_error naming the file otherwise.
void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes);

/// Encodes `image` in the format given by `file`'s extension (.png, ...) and writes it with
/// writeFileAtomically. @throws std::runtime_error if it cannot be encoded or written.
void writeImageAtomically(const std::filesystem::path& file, const cv::Mat& image);

}  // namespace visgrab::database
