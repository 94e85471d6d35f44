#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_tree.hpp"
#include "rwsim/loaders/detail/dwc_description.hpp"

namespace rwsim::loaders::detail {

/// How messages name a dynamic workcell element: `<RigidBody frame="object">`, `<Pair
/// first="A" second="B">` (the first of the attributes frame, device, joint, object, body,
/// name, id, file, workcell that is present), or just `<Mass>`.
std::string describeElement(const rw::common::XmlElement& element);

/// For the schema reader: why the numbers of a number element cannot be read (empty if they
/// can or the element has none).
std::string explainDynamicWorkCellValueError(const rw::common::XmlElement& element);

/// First pass: reads the root <DynamicWorkcell> and its top-level elements (Includes already
/// expanded, in document order) into a description, checking values, counts and required
/// children, and reading the material, friction and restitution maps in document order as
/// RobWork does (reference §2.2-2.5). Things RobWork accepts or ignores silently are warnings.
/// Returns nullopt if an error was reported.
std::optional<DynamicWorkCellDesc> parseDynamicWorkCellDescription(
    const rw::common::XmlElement& root, const std::vector<rw::common::XmlElement>& topLevel,
    rw::common::DiagnosticSink& sink);

}  // namespace rwsim::loaders::detail
