#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

/// Readers of the files today's grasp-generation methods write (NPY, NPZ, HDF5, JSON) and the
/// importers that turn their grasps into jaw grasps (docs/grasp-format.md, "Importing grasps").
namespace visgrab::importers {

/// A file that cannot be read or imported as a whole; what() names the file, the key (array,
/// dataset or member) where there is one, and what was expected.
class ImportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An N-d array of numbers as read from a file, converted to double, in C (row-major) order.
struct NdArray {
  /// Extent of each dimension; empty for a scalar (one value).
  std::vector<std::size_t> shape;
  /// The values, row-major (the last index varies fastest), shape's product of them.
  std::vector<double> values;
  /// The element type as the file gave it (an NPY descr such as "<f4", or an HDF5 class name).
  std::string dtype;

  /// The shape as text: "(2000, 4, 4)", "()" for a scalar.
  std::string shapeText() const;
  /// The value at row-major flat index `i` (no check).
  double operator[](std::size_t i) const { return values[i]; }
};

}  // namespace visgrab::importers
