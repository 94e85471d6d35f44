#pragma once

#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/models/workcell.hpp"

/// Readers of RobWork's XML formats.
namespace rw::loaders {

/// Loads a RobWork workcell file (`.wc.xml`, reference §1): validates it against
/// xml/workcell.xsd, expands Include/Define/Use, builds frames, devices, geometry, the collision
/// and proximity setups and the default state. Warnings (things RobWork accepts silently, such
/// as an ignored refframe or a dropped property type) are appended to `warnings` if given, also
/// when the load fails.
/// @throws LoadError with every diagnostic found (what(): the errors, each at file:line:column).
std::unique_ptr<rw::models::WorkCell> loadWorkCell(
    const std::filesystem::path& file, std::vector<common::Diagnostic>* warnings = nullptr);

/// Same as loadWorkCell, reading the top-level XML from `xml`. Relative paths (Include,
/// Polytope, setup files) resolve against the folder of `virtualFile`, and diagnostics name it.
/// @throws LoadError listing every error found.
std::unique_ptr<rw::models::WorkCell> loadWorkCellFromString(
    std::string_view xml, const std::filesystem::path& virtualFile,
    std::vector<common::Diagnostic>* warnings = nullptr);

/// Checks a workcell file as loadWorkCell would and returns every error and warning, in the
/// order found. Never throws for bad input (for `visgrab wc check`).
std::vector<common::Diagnostic> checkWorkCell(const std::filesystem::path& file);

}  // namespace rw::loaders
