#pragma once

#include <filesystem>

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

}  // namespace visgrab::cli
