#include "cli_common/data_folder.hpp"

#include <algorithm>
#include <stdexcept>
#include <system_error>

#include "visgrab/results/run_protocol.hpp"

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

std::vector<std::string> knownHands(const std::filesystem::path& data) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& hand : std::filesystem::directory_iterator(data / "hands", error)) {
    if (!hand.is_directory(error)) continue;
    std::error_code inner;
    for (const auto& file : std::filesystem::directory_iterator(hand.path(), inner)) {
      if (file.path().filename().string().ends_with(".grasp.xml")) {
        names.push_back(hand.path().filename().string());
        break;
      }
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::filesystem::path handPath(const std::string& text, const std::filesystem::path& data) {
  std::error_code error;
  const bool looksLikePath = text.find('/') != std::string::npos || text.ends_with(".xml");
  if (text.empty() || looksLikePath || std::filesystem::exists(text, error)) return text;
  const auto known = knownHands(data);
  if (std::find(known.begin(), known.end(), text) != known.end()) return data / "hands" / text;
  std::string list;
  for (const auto& h : known) list += (list.empty() ? "" : ", ") + h;
  throw std::invalid_argument("unknown hand \"" + text + "\": not a file or folder, and " +
                              (data / "hands").string() +
                              " has no hand of that name (known: " + list + ")");
}

std::filesystem::path protocolPath(const std::string& text, const std::filesystem::path& data) {
  std::error_code error;
  const bool looksLikePath = text.find('/') != std::string::npos || text.ends_with(".xml");
  if (text.empty() || looksLikePath || std::filesystem::is_regular_file(text, error)) return text;
  const std::filesystem::path file = results::namedProtocolFile(data, text);
  if (std::filesystem::is_regular_file(file, error)) return file;
  std::string list;
  for (const auto& p : results::knownProtocols(data)) list += (list.empty() ? "" : ", ") + p;
  throw std::invalid_argument("unknown protocol \"" + text + "\": not a file, and " +
                              file.parent_path().string() +
                              " has no protocol of that name (known: " + list + ")");
}

}  // namespace visgrab::cli
