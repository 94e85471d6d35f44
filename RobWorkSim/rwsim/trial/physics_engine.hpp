#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rw/kinematics/state.hpp"
#include "rw/math/types.hpp"
#include "rwsim/contacts/contact_detector.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/trial/physics_variation.hpp"

/// The physics seam: what a grasp trial asks of an engine. The trial's protocol
/// (rwsim::simulator::GraspTrial) is written once against PhysicsEngine; ODE
/// (rwsim::simulator::Simulator, the benchmark's engine and the default) and MuJoCo (the optional
/// rwsim_mujoco module) are adapters behind it.
namespace rwsim::trial {

/// Result of one step.
enum class StepStatus {
  kOk,                ///< the step succeeded
  kNumericalFailure,  ///< a pose or velocity became NaN/inf, or the engine reported a fatal error
  kRunaway,           ///< a rigid body exceeded the speed limit or escaped
};

/// A contact point with the force the solver applied in the step (world coordinates).
struct SolvedContact {
  /// The geometric contact (normal from body A towards body B).
  contacts::ContactPoint point;
  /// Force on body B from body A, N (equal and opposite on A).
  rw::math::Vector3D force = rw::math::Vector3D::Zero();
};

/// Contacts of one body pair after a step, with solver forces.
struct SolvedBodyContact {
  /// First body.
  dynamics::BodyId bodyA;
  /// Second body.
  dynamics::BodyId bodyB;
  /// Points with their forces.
  std::vector<SolvedContact> points;
};

/// One simulated world over a dynamic workcell, stepped by one thread (one per trial). The
/// DynamicWorkCell must outlive it. Bodies and devices are the dwc's (BodyId, DeviceId); a body's
/// pose is its frame's world pose. Joints are driven by velocity motors with a force limit per
/// DOF (a dependent joint follows its owner); a kinematic body moves with the velocity it is
/// given until changed.
class PhysicsEngine {
 public:
  virtual ~PhysicsEngine() = default;
  PhysicsEngine() = default;
  PhysicsEngine(const PhysicsEngine&) = delete;
  PhysicsEngine& operator=(const PhysicsEngine&) = delete;

  /// Puts every body where `state` says, at rest; time restarts at 0. Motor targets, force
  /// limits (back to the dwc's) and kinematic velocities are cleared; the status is kOk again.
  virtual void reset(const rw::kinematics::State& state) = 0;
  /// Advances by timeStep(). After a failure every further step returns the same status until
  /// reset().
  virtual StepStatus step() = 0;
  /// The integration step, s.
  virtual double timeStep() const = 0;
  /// Simulated time since reset, s.
  virtual double time() const = 0;
  /// Why the failing step failed (empty while every step succeeded).
  virtual const std::string& failureDetail() const = 0;
  /// The engine's non-fatal messages since reset(), "; "-separated (empty when none).
  virtual const std::string& engineMessages() const = 0;
  /// The state after the last step (movable frames of bodies, joint values of devices).
  virtual const rw::kinematics::State& state() const = 0;

  /// World pose of a body's frame.
  virtual rw::math::Transform3D bodyPose(dynamics::BodyId body) const = 0;
  /// Linear velocity of a body's frame origin, m/s.
  virtual rw::math::Vector3D bodyLinearVelocity(dynamics::BodyId body) const = 0;
  /// Angular velocity, rad/s.
  virtual rw::math::Vector3D bodyAngularVelocity(dynamics::BodyId body) const = 0;
  /// Commands a kinematic body's velocity (world frame, about its frame origin) until changed.
  virtual void setKinematicVelocity(dynamics::BodyId body, const rw::math::Vector3D& linear,
                                    const rw::math::Vector3D& angular) = 0;

  /// Joint positions of a rigid device's active joints (DOF order).
  virtual rw::math::Q jointPositions(dynamics::DeviceId device) const = 0;
  /// Joint velocities (DOF order).
  virtual rw::math::Q jointVelocities(dynamics::DeviceId device) const = 0;
  /// Motor velocity targets per DOF (dependent joints follow their owners).
  virtual void setMotorVelocityTargets(dynamics::DeviceId device,
                                       const rw::math::Q& velocities) = 0;
  /// Motor torque/force limits per DOF (a dependent joint takes its owner's).
  virtual void setMotorForceLimits(dynamics::DeviceId device, const rw::math::Q& limits) = 0;

  /// Contacts of the last step with their forces.
  virtual const std::vector<SolvedBodyContact>& contacts() const = 0;
};

/// Makes the engines of one dwc's trials (const and thread-safe: trials in many threads share
/// one factory, each create() gives a new engine).
class EngineFactory {
 public:
  virtual ~EngineFactory() = default;
  /// The engine's name as `visgrab run --engine` takes it ("ode", "mujoco").
  virtual std::string name() const = 0;
  /// The engine's version and the settings that decide its results, one line (recorded in
  /// run.csv, so that runs on different settings are not merged or resumed into each other).
  virtual std::string settings() const = 0;
  /// A new engine at the dwc's default state, on the dwc's own physical values.
  std::unique_ptr<PhysicsEngine> create() const { return create(PhysicsVariation{}); }
  /// A new engine at the dwc's default state whose friction coefficients and object masses are
  /// the dwc's scaled by `variation` (the identity gives create()'s engine, bit for bit).
  /// @throws std::invalid_argument if a scale is not finite and > 0 (PhysicsVariation::check()).
  virtual std::unique_ptr<PhysicsEngine> create(const PhysicsVariation& variation) const = 0;
};

}  // namespace rwsim::trial
