#pragma once

#include <string>
#include <vector>

#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/mujoco/mujoco_options.hpp"

/// MuJoCo (optional engine, Debian libmujoco-dev): the MJCF export of a dynamic workcell and the
/// engine behind the physics seam (mujoco_engine.hpp).
namespace rwsim::mujoco {

/// The exported model and how its names map back to the dwc.
struct MjcfModel {
  /// The MJCF document.
  std::string xml;
  /// Per dwc body (index as DynamicWorkCell::bodies()): its MJCF body name (the dwc name).
  std::vector<std::string> bodyNames;
  /// Per dwc body: for a kinematic body the MJCF names of its six joints (slides along the body
  /// frame's x, y, z, then hinges about them, all at the frame origin), empty otherwise.
  std::vector<std::vector<std::string>> kinematicJoints;
  /// Per rigid device (index as DynamicWorkCell::devices()), per active joint: the MJCF joint
  /// name (the frame name); its motor carries the same name.
  std::vector<std::vector<std::string>> activeJoints;
  /// Frames whose collision geometry no body carries (the project's simulator ignores them as
  /// well; not exported).
  std::vector<std::string> skippedFrames;
};

/// Writes `dwc` as MJCF: every body at q = 0 in the kinematic tree (device links below the body
/// above their joint, other bodies below the world); its collision geometry, one geom per piece
/// (Box, Sphere, Cylinder as themselves; a convex mesh as a box when it is a cuboid, else as an
/// MJCF mesh, which MuJoCo uses as its convex hull; Cone and Frustum as the hull of
/// options.roundSegments-gons; Plane on a fixed body); mass, centre of mass and full inertia; a
/// hinge or slide joint with limits for each link, a free joint for each other rigid body, six
/// joints (slides and hinges at the frame origin, armature options.kinematicArmature) for each
/// kinematic body; a torque-limited velocity servo (gain options.motorGain on a revolute joint,
/// options.prismaticMotorGain on a prismatic one, force range the dwc's ForceLimit) per active
/// joint, and every link joint the armature of its type (motorArmature, prismaticMotorArmature);
/// each dependent joint as a joint equality (MuJoCo's equality has no force limit, the ODE engine's
/// coupling motor has); gravity; the solver options; and one explicit contact pair per pair of
/// shapes the project's contact detection checks (a rigid body involved, not joint-connected,
/// allowed by the proximity setup) with the pair's Coulomb friction from the material map (all
/// other contacts off).
/// @throws std::invalid_argument naming the frame (and body) for geometry MuJoCo cannot
/// represent faithfully (a non-convex or flat mesh, a tube, a plane on a moving body), naming
/// the body for a device link that is not on a joint frame, a device joint without a link body,
/// a kinematic device link, and for a dwc with constraints or loop closures (not exported).
MjcfModel exportMjcf(const dynamics::DynamicWorkCell& dwc, const MujocoOptions& options = {});

}  // namespace rwsim::mujoco
