#pragma once

#include <vector>

#include "rw/graspplanning/grasp_wrench_space.hpp"
#include "rw/math/types.hpp"
#include "rwsim/simulator/grasp_trial.hpp"

namespace rwsim::simulator {

/// How gwsQualities() builds its hulls.
struct GwsQualityOptions {
  /// Edges of each friction cone (RobWork: 10).
  int coneEdges = 10;
  /// The VisGraB-era rule for Q_GWS: with fewer contacts than this, each gets a jittered copy.
  int duplicateBelow = 4;
  /// How the hulls are built (both exact; the lazy hull is 5-20 times faster on SDH contacts).
  rw::graspplanning::GwsHull hull = rw::graspplanning::GwsHull::kLazy;
};

/// The two grasp-wrench-space qualities of a held grasp.
struct GwsQualities {
  /// Q_GWS as the paper's tables computed it.
  double qGws = 0.0;
  /// Q_GWS with unit normal forces.
  double qGwsUnit = 0.0;
};

/// The trial's contacts as the grasp-quality library's (position, normal, mu, normal force and
/// the whole measured force).
std::vector<rw::graspplanning::Contact3D> toContacts3D(const std::vector<TrialContact>& contacts);

/// Q_GWS and Q_GWS,unit of `contacts` on an object with centre of mass `cog` and largest radius
/// `r` (torques are scaled by 1/r, paper eq. 6); both 0 without contacts or with r <= 0.
///  - qGws (the paper's §2.4.1 as the VisGraB-era simulator computed its tables): each cone is
///    centred on the measured contact force f_i and scaled by |f_i|; forces below 1e-4 N are
///    skipped; if fewer than duplicateBelow contacts remain, each gets a copy with its force
///    direction's components moved by up to +-0.1 (then renormalised) and its position by up
///    to +-2 mm, drawn from a fixed-seed generator after putting the contacts in a canonical
///    order (rw::graspplanning::gwsEpsilon, steps 1-4), so the value depends on the contacts
///    only, not on their order or the thread.
///  - qGwsUnit (RobWork's GraspTaskSimulator): cones on the contact normals, unit normal forces,
///    no copies.
/// No contact is merged or dropped to save time: both hulls are grown lazily (see
/// rw::graspplanning::gwsEpsilonOfWrenches), which is exact to 1e-12 of the largest wrench.
/// @throws std::invalid_argument if coneEdges < 3.
GwsQualities gwsQualities(const std::vector<TrialContact>& contacts, const rw::math::Vector3D& cog,
                          double r, const GwsQualityOptions& options = {});

}  // namespace rwsim::simulator
