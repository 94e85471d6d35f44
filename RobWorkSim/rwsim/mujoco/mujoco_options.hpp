#pragma once

#include <string>

namespace rwsim::mujoco {

/// MuJoCo's settings for a dynamic workcell's trials (the dwc gives none of these). The defaults
/// are the values that hold the SDH box in MuJoCo 2.2.2 (docs/performance.md "MuJoCo
/// comparison"); every field changes results and is written into the factory's settings().
struct MujocoOptions {
  /// Integration step, s. MuJoCo's contact time constant cannot go below two steps; at the
  /// project's 5 ms the contacts are so soft that the fingers sink into the box edges and squeeze
  /// it out, at 2 ms with solrefTimeConstant 0.004 the box is held.
  double timeStep = 0.002;
  /// Contact (and coupling) stiffness: solref's time constant, s (>= 2 time steps, see timeStep).
  double solrefTimeConstant = 0.004;
  /// solref's damping ratio (1: critically damped, no bounce off the fingers).
  double solrefDampingRatio = 1.0;
  /// Friction cone: "elliptic" (a pyramidal cone let the box slip out of the SDH).
  std::string cone = "elliptic";
  /// Ratio of frictional to normal constraint impedance; 10 makes sticking friction stiff, so a
  /// held box does not creep down between the fingers.
  double impratio = 10.0;
  /// Constraint solver: "Newton" was fastest on the SDH box (CG 1.4x, PGS 3.5x slower per trial).
  std::string solver = "Newton";
  /// Integrator: "implicit" integrates the servos' velocity feedback implicitly, so the stiff
  /// finger and base servos stay stable (an explicit one-step torque law oscillated).
  std::string integrator = "implicit";
  /// Gain kv of the finger motors' velocity servos, N m s/rad (or N s/m): torque =
  /// kv (target - velocity), clipped to the force limit. About 2 closes the SDH like the project's
  /// velocity constraint (which gives the full force limit for any speed error). MuJoCo 2.2.2's
  /// implicit integrator applies the feedback's derivative even while the torque is clipped: a
  /// saturated joint responds as if its inertia were larger by kv * timeStep (0.004 kg m^2).
  double motorGain = 2.0;
  /// Armature of every device joint, kg m^2 (kg for a prismatic one): an inertia added to the
  /// joint's, as a motor's reflected rotor inertia. The constraint solver computes the contact
  /// forces with the joint-space inertia it knows, while the implicit integrator moves a joint
  /// whose servo saturates as if it were heavier by motorGain * timeStep (above); an SDH distal
  /// joint (1.1e-4 kg m^2 about its axis) then took a 37 times smaller step than its contact
  /// forces were computed for, and the fingers never came to rest (the closing hit the 5 s cap in
  /// 104 of 200 baseline trials). With an armature of motorGain * timeStep the two see inertias
  /// of the same size; held-against-not-held agreement with ODE moves by half a point between
  /// 0.001 and 0.016 (docs/validation.md, "ODE against MuJoCo").
  double motorArmature = 0.004;
  /// Gain kv of a prismatic joint's velocity servo, N s/m (motorGain is a revolute joint's; the
  /// same number in N s/m was 175 times too weak for the Franka: a finger stopped on an object
  /// while its PD commands 0.2 m/s pushed with kv 0.2 = 0.4 N instead of its 70 N limit, and every
  /// Franka and PG70 grasp was dropped). 1000 gives the limit, as the project's velocity
  /// constraint does, once the stopped finger is commanded faster than limit / kv: 0.07 m/s for
  /// the Franka's 70 N, 0.05 m/s for the PG70's 50 N, while the trial's PD (P 10/s) commands
  /// 0.2 m/s to a finger 0.02 m short of its closing target; force limits up to 200 N reach
  /// their limit there. (The SDH's kv 2 gives its 2.1 N m above 1.05 rad/s, 0.1 rad short.)
  double prismaticMotorGain = 1000.0;
  /// Armature of every prismatic device joint, kg: prismaticMotorGain * timeStep, for the reason
  /// given at motorArmature. A finger at its force limit then accelerates at limit / (2 kg +
  /// its mass), 35 m/s^2 for the Franka: it reaches the PD's 0.4 m/s in 11 ms and 2.3 mm.
  double prismaticMotorArmature = 2.0;
  /// Mass of a kinematic body, kg (the dwc gives none; the pose is driven, see kinematicArmature).
  double kinematicMass = 1.0;
  /// Armature of a kinematic body's six joints (kg, kg m^2). The engine writes the commanded
  /// velocity into them before every step; with this inertia a load of 1 N (1 N m) changes it by
  /// only 1e-5 m/s^2 (rad/s^2), so the body moves as commanded, as a kinematic body should.
  double kinematicArmature = 1e5;
  /// Segments of the convex polygon that stands for the circle of a cone or frustum (their
  /// mesh hull; a cylinder stays a true cylinder).
  int roundSegments = 64;
  /// A rigid body faster than this (m/s) is a runaway (as the ODE engine's maxSpeed).
  double maxSpeed = 50.0;
  /// A rigid body farther than this from its place at reset (m) is a runaway (escapeDistance).
  double escapeDistance = 50.0;
};

}  // namespace rwsim::mujoco
