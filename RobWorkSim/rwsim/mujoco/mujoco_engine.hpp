#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rw/kinematics/state.hpp"
#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/mujoco/mjcf_export.hpp"
#include "rwsim/mujoco/mujoco_options.hpp"
#include "rwsim/trial/physics_engine.hpp"

namespace rwsim::mujoco {

/// The compiled MJCF model of one dwc, shared by the engines of its trials (MuJoCo is private to
/// this module).
struct CompiledModel;

/// One MuJoCo world over a dynamic workcell (exportMjcf()), with its own model copy and data.
/// Not copyable; one per thread. The DynamicWorkCell must outlive it. Made by
/// mujocoEngineFactory().
///
/// Model differences from the ODE engine (rwsim::simulator::Simulator):
///  - Motors: a velocity servo torque = kv (target - velocity) clipped to the force limit
///    (MujocoOptions::motorGain for a revolute joint, prismaticMotorGain for a prismatic one),
///    not a velocity constraint that reaches the limit for any speed error; a loaded joint
///    therefore lags its target by load / kv.
///  - A dependent (coupled) joint is a joint equality, which has no force limit (ODE's coupling
///    motor has its owner's).
///  - Contacts are MuJoCo's soft constraints (solref, elliptic cones, impratio) found by MuJoCo's
///    own collision functions: one point per pair of convex meshes (MPR), up to four or eight for
///    box pairs, planes and cylinders; the project's detector keeps up to four per manifold.
///  - Time step MujocoOptions::timeStep (2 ms) instead of ODE's 5 ms.
///  - A kinematic body is a body with three slides and three hinges at its frame origin, placed by
///    writing its pose into this engine's model copy at reset() and moved by writing the joints'
///    velocities before each step, with a large armature so that loads barely change them.
/// A step fails (kNumericalFailure) on a non-finite pose or velocity or a MuJoCo warning that
/// makes the step unreliable (bad qpos/qvel/qacc/ctrl, contact or constraint buffer full; the
/// detail names it), and is a runaway (kRunaway) as in the ODE engine (maxSpeed,
/// escapeDistance). Other warnings (near-singular inertia) go to engineMessages().
///
/// A PhysicsVariation other than the identity scales this engine's model copy: the sliding
/// friction of every contact pair (the export makes every contact an explicit pair with the
/// material table's mu; torsional and rolling values are unused at condim 3), and the mass and
/// principal inertia of each object's body (trial::isVariedObject()); MuJoCo's constants
/// derived from them (mj_setConst: the inverse weights behind the constraints' softness, the
/// mean inertia, subtree masses) are then recomputed, as compiling the scaled MJCF would. A
/// variation without gravity zeroes the copy's opt.gravity. The identity leaves the copy as
/// compiled.
class MujocoEngine final : public trial::PhysicsEngine {
 public:
  /// An engine on `model` (compiled from `dwc`), at the dwc's default state, with friction and
  /// object masses scaled by `variation`.
  /// @throws std::invalid_argument for an invalid variation (trial::PhysicsVariation::check()).
  MujocoEngine(const dynamics::DynamicWorkCell& dwc, std::shared_ptr<const CompiledModel> model,
               const trial::PhysicsVariation& variation = {});
  ~MujocoEngine() override;

  /// Puts every body where `state` says, at rest; time restarts at 0. Motor targets, force
  /// limits (back to the dwc's) and kinematic velocities are cleared; the status is kOk again.
  void reset(const rw::kinematics::State& state) override;
  /// Advances by timeStep(). After a failure every further step returns the same status until
  /// reset().
  trial::StepStatus step() override;
  /// MujocoOptions::timeStep, s.
  double timeStep() const override;
  /// Simulated time since reset, s.
  double time() const override;
  /// Why the failing step failed (empty while every step succeeded).
  const std::string& failureDetail() const override;
  /// MuJoCo's non-fatal warnings since reset(), "; "-separated (empty when none).
  const std::string& engineMessages() const override;
  /// The state after the last step (movable frames of bodies, joint values of devices).
  const rw::kinematics::State& state() const override;

  /// World pose of a body's frame.
  rw::math::Transform3D bodyPose(dynamics::BodyId body) const override;
  /// Linear velocity of a body's frame origin, m/s.
  rw::math::Vector3D bodyLinearVelocity(dynamics::BodyId body) const override;
  /// Angular velocity, rad/s.
  rw::math::Vector3D bodyAngularVelocity(dynamics::BodyId body) const override;
  /// Commands a kinematic body's velocity (world frame, about its frame origin) until changed.
  /// @throws std::invalid_argument if the body is not kinematic.
  void setKinematicVelocity(dynamics::BodyId body, const rw::math::Vector3D& linear,
                            const rw::math::Vector3D& angular) override;

  /// Joint positions of a rigid device's active joints (DOF order).
  rw::math::Q jointPositions(dynamics::DeviceId device) const override;
  /// Joint velocities (DOF order).
  rw::math::Q jointVelocities(dynamics::DeviceId device) const override;
  /// Motor velocity targets per DOF (the servos' set points; dependent joints follow their
  /// owners through the equality). @throws std::invalid_argument for a wrong size.
  void setMotorVelocityTargets(dynamics::DeviceId device, const rw::math::Q& velocities) override;
  /// Motor torque/force limits per DOF (this engine's actuator force ranges).
  /// @throws std::invalid_argument for a wrong size or a negative or non-finite limit.
  void setMotorForceLimits(dynamics::DeviceId device, const rw::math::Q& limits) override;

  /// Contacts of the last step between dwc bodies, with MuJoCo's solver forces (world frame;
  /// normal from bodyA to bodyB, force on bodyB from bodyA; bodyA has the lower index).
  const std::vector<trial::SolvedBodyContact>& contacts() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The factory of MuJoCo engines for `dwc`'s trials: name "mujoco", settings the MuJoCo version
/// and every option that changes results. Exports and compiles the MJCF once; each create()
/// gives an engine with its own model copy and data (varied as create(variation) asks). The first
/// call sets MuJoCo's global warning handler to one that only lets mjData count them (the engines
/// read the counts).
/// @throws std::invalid_argument if the dwc cannot be exported (exportMjcf()), or
/// std::runtime_error with MuJoCo's message, naming the dwc, if the model does not compile.
std::shared_ptr<const trial::EngineFactory> mujocoEngineFactory(
    const dynamics::DynamicWorkCell& dwc, MujocoOptions options = {});

}  // namespace rwsim::mujoco
