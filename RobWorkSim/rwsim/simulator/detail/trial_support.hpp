#pragma once

#include <vector>

#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/simulator/simulator.hpp"

// Private to rwsim_simulator: contact bookkeeping and quality of a grasp trial.
namespace rwsim::simulator::detail {

/// Number of loaded hand-object contact points per body (index like bodies()); a point counts
/// when its normal force exceeds `threshold`.
std::vector<int> handContactCounts(const std::vector<SolvedBodyContact>& contacts,
                                   const std::vector<bool>& isHandBody, double threshold);

/// Total normal force of the hand on each body (index like bodies()), N, over the contact points
/// whose normal force exceeds `threshold`.
std::vector<double> handNormalForces(const std::vector<SolvedBodyContact>& contacts,
                                     const std::vector<bool>& isHandBody, double threshold);

/// The loaded contacts between the hand and `object`, in the object's frame (X_W_object is the
/// object's pose), normals pointing into the object, mu from the pair's materials times
/// `frictionScale` (the trial's PhysicsVariation).
std::vector<TrialContact> objectContacts(const dynamics::DynamicWorkCell& dwc,
                                         const std::vector<SolvedBodyContact>& contacts,
                                         const std::vector<bool>& isHandBody,
                                         dynamics::BodyId object,
                                         const rw::math::Transform3D& X_W_object, double threshold,
                                         double frictionScale);

/// Largest distance from a body's centre of mass to a vertex of its collision geometry, m
/// (0 without geometry).
double maxRadiusFromCog(const dynamics::DynamicWorkCell& dwc, dynamics::BodyId body);

}  // namespace rwsim::simulator::detail
