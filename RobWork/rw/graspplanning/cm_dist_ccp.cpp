#include "rw/graspplanning/cm_dist_ccp.hpp"

#include <cmath>

namespace rw::graspplanning {

double cmDistCcp(std::span<const Contact3D> contacts, const rw::math::Vector3D& centerOfMass,
                 double maxDist) {
  if (contacts.empty() || !centerOfMass.allFinite() || !std::isfinite(maxDist) || maxDist <= 0.0) {
    return 0.0;
  }
  rw::math::Vector3D sum = rw::math::Vector3D::Zero();
  for (const Contact3D& c : contacts) sum += c.position;
  const rw::math::Vector3D mean = sum / static_cast<double>(contacts.size());
  if (!mean.allFinite()) return 0.0;
  const double d = (centerOfMass - mean).norm();
  return d <= maxDist ? (maxDist - d) / maxDist : 0.0;
}

}  // namespace rw::graspplanning
