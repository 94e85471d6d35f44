#pragma once

#include <optional>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_tree.hpp"
#include "rw/loaders/detail/wc_description.hpp"

namespace rw::loaders::detail {

/// First pass: turns the expanded top-level elements of a workcell file into a description.
/// Checks where each element may appear, reads values and units, applies RobWork's naming and
/// attachment rules (reference §1.3, §1.4, §1.6). Name lookups that need the whole file
/// (refframes, Depend owners, refjoints) are left to the builder. `file` locates problems that
/// concern the whole file. Returns nullopt if an error was reported.
std::optional<WorkCellDesc> parseWorkCellDescription(
    const std::vector<common::XmlElement>& topLevel, const common::SourceLocation& file,
    common::DiagnosticSink& sink);

}  // namespace rw::loaders::detail
