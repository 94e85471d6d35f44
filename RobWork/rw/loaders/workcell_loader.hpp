#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/models/workcell.hpp"

/// Readers of RobWork's XML formats.
namespace rw::loaders {

/// Include redirects: an `<Include file>` whose file, as resolved (relative to the including
/// file's folder), is the same file as a key is read from the mapped file instead. Keys and
/// values are paths as a program names them (absolute, or relative to the working folder);
/// a key matches however the Include spells the path (`a/../hand.wc.xml`, a symbolic link).
/// Relative paths inside the replacement resolve against the replacement's own folder and
/// messages name it. A replacement that cannot be read is an error at the Include's line.
/// Used to put another hand in a scene: the scene's `<Include>` of its hand goes to the other
/// hand's file (docs/workcell-format.md, "Include redirects").
using IncludeRedirects = std::map<std::filesystem::path, std::filesystem::path>;

/// The replacement `redirects` gives for the included file `resolved` (the Include's path
/// joined to its folder), or nullopt when no key names that file.
std::optional<std::filesystem::path> redirectedInclude(const IncludeRedirects& redirects,
                                                       const std::filesystem::path& resolved);

/// How a workcell is loaded besides its file.
struct WorkCellLoadOptions {
  /// Included files read from other files (see IncludeRedirects); empty: none.
  IncludeRedirects includeRedirects;
};

/// Loads a RobWork workcell file (`.wc.xml`, reference §1): validates it against
/// xml/workcell.xsd, expands Include/Define/Use, builds frames, devices, geometry, the collision
/// and proximity setups and the default state. Warnings (things RobWork accepts silently, such
/// as an ignored refframe or a dropped property type) are appended to `warnings` if given, also
/// when the load fails.
/// @throws LoadError with every diagnostic found (what(): the errors, each at file:line:column).
std::unique_ptr<rw::models::WorkCell> loadWorkCell(
    const std::filesystem::path& file, std::vector<common::Diagnostic>* warnings = nullptr);

/// Same as loadWorkCell, with `options` (Include redirects).
/// @throws LoadError as loadWorkCell; a redirect whose replacement cannot be read is an error
/// at the redirected Include (file:line).
std::unique_ptr<rw::models::WorkCell> loadWorkCell(
    const std::filesystem::path& file, const WorkCellLoadOptions& options,
    std::vector<common::Diagnostic>* warnings = nullptr);

/// Same as loadWorkCell, reading the top-level XML from `xml`. Relative paths (Include,
/// Polytope, setup files) resolve against the folder of `virtualFile`, and diagnostics name it.
/// @throws LoadError listing every error found.
std::unique_ptr<rw::models::WorkCell> loadWorkCellFromString(
    std::string_view xml, const std::filesystem::path& virtualFile,
    std::vector<common::Diagnostic>* warnings = nullptr);

/// Same as loadWorkCellFromString, with `options` (Include redirects).
/// @throws LoadError listing every error found.
std::unique_ptr<rw::models::WorkCell> loadWorkCellFromString(
    std::string_view xml, const std::filesystem::path& virtualFile,
    const WorkCellLoadOptions& options, std::vector<common::Diagnostic>* warnings = nullptr);

/// Checks a workcell file as loadWorkCell would and returns every error and warning, in the
/// order found. Never throws for bad input (for `visgrab wc check`).
std::vector<common::Diagnostic> checkWorkCell(const std::filesystem::path& file);

}  // namespace rw::loaders
