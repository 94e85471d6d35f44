#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rw/models/workcell.hpp"

namespace rw::loaders {

/// A work cell rendered as RobWork workcell XML: the main document and the setup files that it
/// refers to by name.
struct WorkCellFiles {
  /// The `.wc.xml` document.
  std::string workcell;
  /// File name (in the main document's folder) and text of each setup file the document names
  /// with `<CollisionSetup file=...>` or `<ProximitySetup file=...>`, in that order.
  std::vector<std::pair<std::string, std::string>> setupFiles;
};

/// Renders `wc` as one RobWork `.wc.xml` document that RobWork's loader reads and that loads back
/// to the same model, plus its setup files: the collision setup (always, so that a reader never
/// falls back to a default exclude list) as `<stem>.collision.xml` and, if the proximity setup
/// has rules beyond the collision setup's excludes, `<stem>.proximity.xml`.
///
/// Output is deterministic. Workcell-level frames carry an explicit `refframe`. Devices are
/// written as `SerialDevice`/`TreeDevice` with their frames in topological order, names relative
/// to the device, an explicit `refframe` on every frame but the base. Because RobWork attaches a
/// device's base to the last workcell-level `<Frame>` declared before the device (WORLD if none),
/// devices mounted on WORLD come first, before any frame, and every other device follows
/// directly after the frame it is mounted on; and since RobWork attaches the first
/// workcell-level frame to WORLD whatever it names, a child of WORLD is written first.
/// Transforms are `<RPY>` (degrees) and `<Pos>`, numbers in shortest round-trip form. Mesh files
/// are written with their extension, relative to `targetDir` when the two share a folder below
/// the file system's root, else absolute (also when `targetDir` is empty). Colours are not part
/// of the format and are not written.
///
/// @throws std::invalid_argument if the model cannot be expressed in RobWork's format: a device
/// frame not named "<device>.<name>", a device base mounted on another device's frame, a frame
/// of a device whose parent is outside it, a SerialDevice that is not a chain, a TreeDevice
/// whose end effectors would give another joint order, a joint outside every device with limits
/// or a coupling, or no workcell-level frame on WORLD while other workcell-level frames exist.
WorkCellFiles renderWorkCell(const rw::models::WorkCell& wc, const std::filesystem::path& targetDir,
                             std::string_view stem);

/// The main document of renderWorkCell() alone, self-contained: it refers to no setup file, so
/// a reader applies its default collision setup. Mesh paths are relative to `targetDir`.
/// @throws std::invalid_argument as renderWorkCell().
std::string writeWorkCell(const rw::models::WorkCell& wc, const std::filesystem::path& targetDir);

/// Writes `wc` to `file` (created or replaced) and its setup files next to it, named after the
/// file without its `.wc.xml` (or `.xml`) ending: `scene.wc.xml` gets `scene.collision.xml` and,
/// when needed, `scene.proximity.xml`.
/// @throws std::invalid_argument as renderWorkCell(); std::runtime_error naming the file when a
/// file cannot be written.
void saveWorkCell(const rw::models::WorkCell& wc, const std::filesystem::path& file);

}  // namespace rw::loaders
