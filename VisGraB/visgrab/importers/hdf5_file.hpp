#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/importers/nd_array.hpp"

namespace visgrab::importers {

/// The largest HDF5 file these readers take (1 GiB; ACRONYM's grasp files have a few MB).
inline constexpr std::size_t kMaxHdf5FileBytes = std::size_t{1} << 30;

/// An HDF5 file opened read-only through Debian's libhdf5 (C API): numeric datasets as NdArray
/// and string datasets by path ("grasps/transforms"). HDF5's own error printing is off while this
/// reads; its failures become ImportError naming the file, the dataset and HDF5's reason. Calls
/// into libhdf5 are serialised (Debian's serial build is not thread-safe). The file is read
/// whole and the metadata of every object it opens is checked from the bytes before libhdf5
/// reads it (detail::Hdf5Structure): libhdf5 1.10.8 allocates, and can crash on, sizes and
/// addresses of a damaged file before checking them.
class Hdf5File {
 public:
  /// Opens `file`. @throws ImportError naming it (missing, not HDF5, damaged).
  static Hdf5File open(const std::filesystem::path& file);
  /// Opens a file image held in memory (HDF5's core driver), named `name` in messages.
  /// @throws ImportError as open.
  static Hdf5File fromBytes(std::string_view bytes, const std::string& name);

  Hdf5File(Hdf5File&&) noexcept;
  Hdf5File& operator=(Hdf5File&&) noexcept;
  ~Hdf5File();

  /// True if `path` names a dataset.
  bool hasDataset(const std::string& path) const;
  /// The numeric (integer or float) dataset at `path`, as doubles in C order. When `rank` >= 0
  /// it must have that many dimensions; `expected` (e.g. "N x 4 x 4") is what the message says
  /// was expected. @throws ImportError naming the file and the path: missing, not numeric, other
  /// rank, larger than kMaxArrayBytes, unreadable.
  NdArray numbers(const std::string& path, int rank = -1, const std::string& expected = "") const;
  /// The string dataset at `path` (a scalar, fixed or variable length).
  /// @throws ImportError naming the file and the path.
  std::string text(const std::string& path) const;
  /// The name of the file, as given.
  const std::string& name() const { return name_; }

 private:
  Hdf5File() = default;
  static Hdf5File fromImage(std::string bytes, const std::string& name, const std::string& failure);
  std::string name_;
  std::string image_;    // the file's bytes, checked by detail::Hdf5Structure
  long long file_ = -1;  // hid_t
};

}  // namespace visgrab::importers
