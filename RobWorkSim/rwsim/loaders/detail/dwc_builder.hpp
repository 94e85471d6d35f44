#pragma once

#include <memory>
#include <string>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/models/workcell.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/loaders/detail/dwc_description.hpp"

namespace rwsim::loaders::detail {

/// Second pass: builds the dynamic workcell from its description and the loaded workcell.
/// Resolves frames, joints and devices (names in a RigidDevice are relative to the device),
/// checks frame types, materials and object types, computes the bodies' geometry frames and
/// mass properties (EstimateInertia, reference §2.4, with the inertia about the COG), and adds
/// bodies, devices and controllers. Every problem is reported at the element it comes from.
/// Returns null if an error was reported.
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> buildDynamicWorkCell(
    const DynamicWorkCellDesc& desc, std::unique_ptr<rw::models::WorkCell> workcell,
    rw::common::DiagnosticSink& sink);

}  // namespace rwsim::loaders::detail
