#pragma once

#include <span>

#include "rw/graspplanning/contact3d.hpp"
#include "rw/math/types.hpp"

namespace rw::graspplanning {

/// RobWork's CMDistCCP quality: with d = |cm - mean contact position|, (maxDist - d) / maxDist if
/// d <= maxDist, else 0. Every contact counts (no deduplication, as in RobWork). Returns 0 for no
/// contacts and for non-finite input or maxDist <= 0. GraspTaskSimulator passes maxDist = 2 r.
double cmDistCcp(std::span<const Contact3D> contacts, const rw::math::Vector3D& centerOfMass,
                 double maxDist);

}  // namespace rw::graspplanning
