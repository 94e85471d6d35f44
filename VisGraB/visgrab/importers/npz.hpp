#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/importers/nd_array.hpp"

namespace visgrab::importers {

/// A NumPy .npz file (a zip of .npy members, stored or deflated), read whole through libzip:
/// its arrays by name ("grasps" for the member grasps.npy).
class NpzFile {
 public:
  /// Opens `file`. @throws ImportError naming it: not a zip, a damaged member, more than
  /// kMaxArrayBytes in one member.
  static NpzFile open(const std::filesystem::path& file);
  /// The same from the bytes of a file, named `name` in messages. @throws ImportError.
  static NpzFile fromBytes(std::string_view bytes, const std::string& name);

  /// The array names (member names without ".npy"), sorted.
  std::vector<std::string> names() const;
  /// True if there is an array `key`.
  bool contains(const std::string& key) const { return members_.count(key) > 0; }
  /// The array `key` read as NPY (parseNpy). @throws ImportError naming the file and the key
  /// when it is missing (listing the names there are) or not a readable NPY array.
  NdArray array(const std::string& key) const;
  /// The name of the file, as given.
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  std::map<std::string, std::string> members_;
};

}  // namespace visgrab::importers
