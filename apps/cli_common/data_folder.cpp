#include "cli_common/data_folder.hpp"

#include <system_error>

namespace visgrab::cli {

std::filesystem::path installedDataFolder(const std::filesystem::path& executable) {
  return executable.parent_path().parent_path() / "share" / "visgrab" / "scenes";
}

std::filesystem::path defaultDataFolder(const std::filesystem::path& buildTreeScenes) {
  // Linux: the running program's own path. Unreadable (no /proc): the build tree's data.
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return buildTreeScenes;
  std::filesystem::path installed = installedDataFolder(self);
  if (std::filesystem::is_directory(installed, error)) return installed;
  return buildTreeScenes;
}

}  // namespace visgrab::cli
