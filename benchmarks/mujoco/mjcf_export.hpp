#pragma once

#include <string>
#include <vector>

#include "rwsim/dynamics/dynamic_workcell.hpp"

// MJCF export of a dynamic workcell, for the MuJoCo comparison benchmark only (never a
// dependency of a library or app).
namespace visgrab::mujoco {

/// Settings of the exported model that the dwc does not give (defaults: the values that hold the
/// SDH box in MuJoCo 2.2.2, docs/performance.md "MuJoCo comparison").
struct MjcfOptions {
  /// Time step, s (at the project's 5 ms MuJoCo's contacts are too soft to hold the box).
  double timeStep = 0.002;
  /// Contact solref: time constant (s, >= 2 time steps) and damping ratio.
  double solrefTimeConstant = 0.004;
  /// See solrefTimeConstant.
  double solrefDampingRatio = 1.0;
  /// Ratio of frictional to normal constraint impedance (elliptic cones).
  double impratio = 10.0;
  /// Mass given to a kinematic body (the dwc's have none; heavy, so that contact forces barely
  /// move it within a step), kg.
  double kinematicMass = 100.0;
};

/// The exported model and how its names map back to the dwc.
struct MjcfModel {
  /// The MJCF document.
  std::string xml;
  /// Per dwc body (index as DynamicWorkCell::bodies()): its MJCF body name (the dwc name).
  std::vector<std::string> bodyNames;
  /// Per dwc body: the MJCF names of its three slide joints x, y, z (world axes) for a
  /// kinematic body, empty otherwise; their motors carry the same names.
  std::vector<std::vector<std::string>> slideJoints;
  /// Per rigid device (index as DynamicWorkCell::devices()), per active joint: the MJCF joint
  /// name (the frame name); its motor carries the same name.
  std::vector<std::vector<std::string>> activeJoints;
  /// Frames whose collision geometry no body carries (the project's simulator ignores them as
  /// well; not exported).
  std::vector<std::string> skippedFrames;
};

/// Writes `dwc` as MJCF: every body at q = 0 in the kinematic tree (device links below the body
/// above their joint, other bodies below the world), its collision primitives (box, sphere,
/// cylinder, plane on fixed bodies), mass, centre of mass and full inertia; a hinge or slide joint
/// with limits for each link, a free joint for each rigid body, three world-axis slide joints
/// with a motor each for each kinematic body; a motor per active joint limited to the dwc's
/// ForceLimit (the velocity law is the trial's: MujocoGraspTrial); each dependent joint as a
/// joint equality; gravity; MuJoCo's options (implicit integrator, Newton solver, elliptic
/// cones); and one
/// explicit contact pair per pair of shapes the project's contact detection checks (a rigid body
/// involved, not joint-connected, allowed by the proximity setup) with the pair's Coulomb
/// friction from the material map (all other contacts off).
/// @throws std::invalid_argument naming the frame for geometry this export cannot write (meshes,
/// cones, tubes, frustums, a plane on a moving body), a device link that is not on a joint frame,
/// or a device joint without a link body.
MjcfModel exportMjcf(const rwsim::dynamics::DynamicWorkCell& dwc, const MjcfOptions& options = {});

}  // namespace visgrab::mujoco
