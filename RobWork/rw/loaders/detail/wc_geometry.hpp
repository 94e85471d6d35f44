#pragma once

#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/loaders/detail/wc_description.hpp"
#include "rw/models/workcell.hpp"

namespace rw::loaders::detail {

/// Creates the geometry of every model and attaches it to the object of its frame (which must
/// exist in `wc`). Polytope files are resolved as RobWork does (STL first for collision, AC3D
/// first for drawing) and each resolved file is read once per call. A missing or unreadable
/// mesh is an error at its Polytope element; the rest of the geometry is still made.
void addGeometry(rw::models::WorkCell& wc, const std::vector<ModelDesc>& models,
                 common::DiagnosticSink& sink);

}  // namespace rw::loaders::detail
