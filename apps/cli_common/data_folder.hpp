#pragma once

#include <filesystem>
#include <string>
#include <vector>

/// Where visgrab and visgrab-viewer find the project's scene data (hands, objects, cameras,
/// materials) when neither --data nor $VISGRAB_DATA names it.
namespace visgrab::cli {

/// The scene data of an installed program: installedDataFolder() of the running program when
/// that folder exists (`cmake --install` puts the data there, README "Installing"), else
/// `buildTreeScenes` (the source tree's scenes/ folder, for programs run from the build tree).
std::filesystem::path defaultDataFolder(const std::filesystem::path& buildTreeScenes);

/// The installed data folder of a program at `executable` (`<its folder>/../share/visgrab/scenes`),
/// whether or not it exists.
std::filesystem::path installedDataFolder(const std::filesystem::path& executable);

/// The hands in `data`/hands: the folders that hold a `*.grasp.xml`, sorted by name.
std::vector<std::string> knownHands(const std::filesystem::path& data);

/// The hand `text` names on a command line or to the Python module's Hand(): an existing file or
/// folder, or text that looks like a path (holds '/' or ends in ".xml"), as it is (a missing one
/// is the loader's error); otherwise a hand's name, `data`/hands/`text` ("sdh", "pg70", ...).
/// @throws std::invalid_argument for an unknown name, listing the known ones.
std::filesystem::path handPath(const std::string& text, const std::filesystem::path& data);

/// The trial protocol `text` names (`--protocol`, Python's run(protocol=)): an existing file, or
/// text that looks like a path (holds '/' or ends in ".xml"), as it is; otherwise a protocol's
/// name, `data`/protocols/`text`.xml ("lift", "shake"; results::namedProtocolFile, where the
/// replays look for a run's protocol too).
/// @throws std::invalid_argument for an unknown name, listing the known ones.
std::filesystem::path protocolPath(const std::string& text, const std::filesystem::path& data);

}  // namespace visgrab::cli
