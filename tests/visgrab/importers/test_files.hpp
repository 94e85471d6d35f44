#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

/// Writers of the importers' test files, independent of the readers under test: NPY bytes by
/// the format's layout, zips through libzip, HDF5 through its C API.
namespace visgrab::test {

/// An NPY file's bytes: magic, version `major`.0, the header dict (padded so the data starts at
/// a multiple of 64 bytes, '\n'-terminated), then `data` as given.
std::string npyBytes(const std::string& descr, const std::vector<std::size_t>& shape,
                     const std::string& data, bool fortranOrder = false, int major = 1);

/// `values` as little-endian float64 bytes.
std::string f8(const std::vector<double>& values);
/// `values` as little-endian float32 bytes.
std::string f4(const std::vector<float>& values);

/// Writes a zip at `file` with the members (name, bytes), deflated when `compress`.
void writeZip(const std::filesystem::path& file,
              const std::vector<std::pair<std::string, std::string>>& members,
              bool compress = true);

/// One dataset for writeHdf5: a path ("grasps/transforms"), its shape and float64 values, or
/// an int64 one, or a variable-length string.
struct H5Dataset {
  /// Path; missing groups are made.
  std::string path{};
  /// Shape (empty: a scalar).
  std::vector<unsigned long long> shape{};
  /// The values (row-major) of a numeric dataset.
  std::vector<double> values{};
  /// Stored as int64 instead of float64.
  bool integer = false;
  /// A variable-length string dataset instead (shape and values unused).
  bool isText = false;
  /// The string of a string dataset.
  std::string text{};
  /// Chunk shape of a numeric dataset stored in chunks (empty: contiguous), as ACRONYM's are.
  std::vector<unsigned long long> chunks{};
  /// Its chunks deflated (gzip level 4, as ACRONYM's).
  bool deflate = false;
  /// Its chunks shuffled before deflating and checksummed after (h5py's shuffle=True,
  /// fletcher32=True).
  bool shuffleAndChecksum = false;
};

/// Writes an HDF5 file with `datasets`.
void writeHdf5(const std::filesystem::path& file, const std::vector<H5Dataset>& datasets);

/// Checks that `text` contains `part`.
::testing::AssertionResult hasSubstr(const char* textExpr, const char* partExpr,
                                     const std::string& text, const std::string& part);

}  // namespace visgrab::test

/// Expects the string `text` to contain `part`.
#define EXPECT_HAS(text, part) EXPECT_PRED_FORMAT2(::visgrab::test::hasSubstr, text, part)
