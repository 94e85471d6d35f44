#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rw/kinematics/state.hpp"
#include "rw/math/types.hpp"
#include "rwsim/contacts/contact_detector.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/trial/physics_engine.hpp"
#include "rwsim/trial/trial_types.hpp"

namespace rwsim::simulator {

using trial::SimulatorOptions;
using trial::SolvedBodyContact;
using trial::SolvedContact;
using trial::StepStatus;

/// One ODE world over a dynamic workcell (ODE is private to this module). Not copyable; one per
/// thread. The DynamicWorkCell must outlive it.
///
/// Model: rigid bodies are ODE bodies at their centre of mass with the dwc's mass and inertia
/// (the body frame is X_W_cog * cog^-1); kinematic bodies are ODE kinematic bodies moved by
/// setKinematicVelocity(); fixed bodies have no ODE body. Each joint of a rigid device is an ODE
/// hinge (revolute) or slider (prismatic) about/along the joint frame's z axis between its link
/// body and the nearest body above it, with the joint limits as stops and a velocity motor
/// whose force limit is the dwc's ForceLimit (setMotorForceLimits: per DOF). A dependent joint
/// is driven each step with owner_vel * gain + (owner_q * gain + offset - q) / dt (RobWork's
/// scheme) under its own force limit. Bodies joined by a joint never touch each other.
///
/// Contacts: each step ContactDetector finds the contacts at the current poses; each point
/// becomes an ODE contact joint with Coulomb friction (Approx1, the pyramid's first axis along
/// the slip or, when sticking, along last step's friction force), mu of the two materials,
/// restitution of the two object types, soft CFM/ERP from the options. Separated points
/// (depth < 0, within the margin) are speculative: the gap may close within the step, no
/// further. ODE's fatal errors become kNumericalFailure, never an exit or abort. The same
/// input gives bitwise the same result in any thread (WorldStep; WorldQuickStep uses ODE's
/// global random generator and is only deterministic single-threaded).
///
/// A PhysicsVariation scales every pair's mu (before the contact joints get it) and the mass
/// and inertia given ODE for each object (trial::isVariedObject()); one without gravity gives the
/// ODE world none; the identity leaves every value as the dwc has it.
class Simulator final : public trial::PhysicsEngine {
 public:
  /// Creates the world, bodies, joints and motors, with the dwc's friction and object masses
  /// scaled by `variation`. @throws std::runtime_error if ODE is not double precision;
  /// std::invalid_argument for an invalid variation (trial::PhysicsVariation::check()).
  explicit Simulator(const dynamics::DynamicWorkCell& dwc, SimulatorOptions options = {},
                     const trial::PhysicsVariation& variation = {});
  /// Same, sharing a contact detector made for `dwc` (detection is const and thread-safe, so
  /// simulators in many threads may share one); options.contacts is then the detector's.
  /// @throws std::invalid_argument if `detector` is null or as above.
  Simulator(const dynamics::DynamicWorkCell& dwc,
            std::shared_ptr<const contacts::ContactDetector> detector,
            SimulatorOptions options = {}, const trial::PhysicsVariation& variation = {});
  ~Simulator() override;

  /// Puts every body where `state` says, at rest; time restarts at 0. Motor targets, force
  /// limits (back to the dwc's) and kinematic velocities are cleared; the status is kOk again.
  void reset(const rw::kinematics::State& state) override;
  /// Advances by options().timeStep: contacts, controllers' commands, integration. After a
  /// failure every further step returns the same status until reset().
  StepStatus step() override;
  /// Why the failing step failed (empty while every step succeeded).
  const std::string& failureDetail() const override;
  /// ODE's non-fatal messages since reset() (e.g. "LCP internal error"), "; "-separated.
  const std::string& engineMessages() const override;
  /// Simulated time since reset, s.
  double time() const override;
  /// options().timeStep, s.
  double timeStep() const override;
  /// The state after the last step (movable frames of bodies, joint values of devices).
  const rw::kinematics::State& state() const override;

  /// World pose of a body's frame.
  rw::math::Transform3D bodyPose(dynamics::BodyId body) const override;
  /// Linear velocity of a body's frame origin, m/s.
  rw::math::Vector3D bodyLinearVelocity(dynamics::BodyId body) const override;
  /// Angular velocity, rad/s.
  rw::math::Vector3D bodyAngularVelocity(dynamics::BodyId body) const override;
  /// Commands a kinematic body's velocity (world frame, about its frame origin) until changed.
  void setKinematicVelocity(dynamics::BodyId body, const rw::math::Vector3D& linear,
                            const rw::math::Vector3D& angular) override;

  /// Joint positions of a rigid device's active joints (DOF order).
  rw::math::Q jointPositions(dynamics::DeviceId device) const override;
  /// Joint velocities (DOF order).
  rw::math::Q jointVelocities(dynamics::DeviceId device) const override;
  /// Motor velocity targets per DOF (dependent joints follow their owners).
  void setMotorVelocityTargets(dynamics::DeviceId device, const rw::math::Q& velocities) override;
  /// Motor torque/force limits per DOF (a dependent joint takes its owner's).
  void setMotorForceLimits(dynamics::DeviceId device, const rw::math::Q& limits) override;

  /// Contacts of the last step with their forces.
  const std::vector<SolvedBodyContact>& contacts() const override;
  /// Constraint rows the last step gave ODE's solver, summed over its islands: 5 per hinge or
  /// slider, 1 more while its motor or a stop acts, 3 per contact with friction (1 without),
  /// and per constraint 6 (Fixed), 5 (Prismatic, Revolute), 4 (Universal, Piston,
  /// PrismaticRotoid) or 3 (Spherical, PrismaticUniversal), 1 more per DOF on a stop.
  /// The dense LCP's cost grows with the cube of an island's rows.
  std::size_t lastStepRows() const;
  /// The options in use.
  const SimulatorOptions& options() const;
  /// The physics variation in use.
  const trial::PhysicsVariation& variation() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The factory of ODE engines (Simulator) for `dwc`'s trials: name "ode", settings the ODE
/// version and `options`; the engines share `detector` (null: each makes its own); create()
/// with a variation passes it to the Simulator.
std::shared_ptr<const trial::EngineFactory> odeEngineFactory(
    const dynamics::DynamicWorkCell& dwc, SimulatorOptions options,
    std::shared_ptr<const contacts::ContactDetector> detector = nullptr);

/// Options from a dwc file's PhysicsEngine properties over `defaults`.
/// @throws std::invalid_argument for a known key with a bad value.
SimulatorOptions optionsFromEngineProperties(const dynamics::DynamicWorkCell& dwc,
                                             SimulatorOptions defaults = {});

}  // namespace rwsim::simulator
