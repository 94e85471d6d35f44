#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "visgrab/importers/nd_array.hpp"

namespace visgrab::importers {

/// The largest array the NPY and NPZ readers accept, in bytes of file data (256 MiB: 2 million
/// GraspNet grasps of 17 float64; more is refused with a message, not allocated).
inline constexpr std::size_t kMaxArrayBytes = std::size_t{256} << 20;

/// Reads NumPy's NPY format (numpy.lib.format, versions 1.0, 2.0 and 3.0) from `bytes`: the
/// header's 'descr' (little/big-endian f4, f8, i1, i2, i4, i8, u1, u2, u4, u8, b1), 'shape' and
/// 'fortran_order' (C or Fortran order, returned in C order). `name` names the input in messages.
/// @throws ImportError naming `name` and what was expected: bad magic or version, a malformed
/// header, an object array ('O': pickled Python objects, never read), a structured, string or
/// complex dtype, a data size that does not match the shape, or data beyond kMaxArrayBytes.
NdArray parseNpy(std::string_view bytes, const std::string& name);

/// parseNpy on the content of `file`. @throws ImportError also when it cannot be read.
NdArray readNpy(const std::filesystem::path& file);

/// Reads `file` whole (at most `limit` bytes). @throws ImportError naming it.
std::string readFileBytes(const std::filesystem::path& file, std::size_t limit);

}  // namespace visgrab::importers
