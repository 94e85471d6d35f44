#pragma once

#include <ode/ode.h>

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/kinematics/state.hpp"
#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/simulator/simulator.hpp"

// Private to rwsim_simulator: the mapping of a DynamicWorkCell onto one ODE world.
namespace rwsim::simulator::detail {

/// One body of the dynamic workcell as simulated.
struct SimBody {
  /// The body in DynamicWorkCell::bodies().
  dynamics::BodyId bodyId;
  /// How it moves.
  dynamics::BodyKind kind = dynamics::BodyKind::kFixed;
  /// The ODE body, placed at the centre of mass; null for fixed bodies.
  dBodyID id = nullptr;
  /// Centre of mass in the body frame (the ODE body's origin).
  rw::math::Vector3D cog = rw::math::Vector3D::Zero();
  /// World pose of a fixed body's frame.
  rw::math::Transform3D X_W_fixed = rw::math::Transform3D::Identity();
  /// Frame origin at creation (escape test).
  rw::math::Vector3D startPosition = rw::math::Vector3D::Zero();
  /// Commanded linear velocity of a kinematic body's frame origin (world).
  rw::math::Vector3D commandLinear = rw::math::Vector3D::Zero();
  /// Commanded angular velocity of a kinematic body (world).
  rw::math::Vector3D commandAngular = rw::math::Vector3D::Zero();
  /// True when the frame is Movable and its transform goes into the State.
  bool movableFrame = false;
};

/// One joint of a rigid device: an ODE hinge or slider with the joint limits as stops and its
/// built-in velocity motor. ODE handles "at a stop and driven away from it" with a one-step
/// external force (its fudge factor); to avoid that jump, setMotor() releases a stop for the step
/// in which the motor drives the joint away from it. (A separate AMotor, as RobWork used, makes
/// the stop and motor rows redundant and ODE's dense LCP then fails with "s <= 0".)
struct SimJoint {
  /// The joint frame.
  rw::kinematics::FrameId frame;
  /// Hinge (true) or slider.
  bool revolute = true;
  /// The ODE joint (body 1 = the link, body 2 = the parent body or the static world).
  dJointID id = nullptr;
  /// Lower stop in ODE's joint coordinate (q - q0); -infinity when none.
  double loStop = -dInfinity;
  /// Upper stop in ODE's joint coordinate; +infinity when none.
  double hiStop = dInfinity;
  /// Joint value when the ODE joint was made; ODE measures from there.
  double q0 = 0.0;
  /// q - q0 after the last step, to unwrap ODE's hinge angle (it wraps at +-pi).
  double lastRelative = 0.0;
  /// True when a dependent joint follows this one: only then are the two speeds below kept.
  bool leads = false;
  /// Joint speed after the last step (a leading joint's).
  double lastVelocity = 0.0;
  /// Mean joint speed over the last two steps (what a dependent joint follows; see
  /// Simulator's driveMotors).
  double meanVelocity = 0.0;
  /// DOF index of an active joint; -1 for dependent and passive joints.
  int activeIndex = -1;
  /// For a dependent joint, the index of its owner in SimDevice::joints.
  std::optional<std::size_t> owner;
  /// Coupling gain of a dependent joint.
  double gain = 1.0;
  /// Coupling offset of a dependent joint.
  double offset = 0.0;
  /// Motor force/torque limit.
  double forceLimit = 0.0;
  /// Motor velocity target (active joints; dependent ones are computed each step).
  double velocityTarget = 0.0;
};

/// A rigid device's joints.
struct SimDevice {
  /// Joints in Device::joints() order.
  std::vector<SimJoint> joints;
  /// DOF index -> index into joints.
  std::vector<std::size_t> active;
  /// Fixed joints that weld the leg ends of a parallel device's junctions (rwsim::dynamics::
  /// loopClosures without a closing joint); 6 constraint rows each.
  std::vector<dJointID> welds;
};

/// A constraint of the dynamic workcell (dynamics::Constraint) as one ODE joint. As in
/// RobWorkSim's ODE engine the parent is ODE's first body and the child its second, so ODE's
/// coordinates are minus the child's motion relative to the parent. A fixed child is ODE's
/// static world (body 0). A fixed parent is OdeWorld's static anchor, a kinematic ODE body that
/// never moves: attached to body 0 first, ODE swaps the two bodies and then measures a hinge's
/// stops in the opposite sense to its angle.
struct SimConstraint {
  /// Index in DynamicWorkCell::constraints().
  std::size_t index = 0;
  /// What it leaves free.
  dynamics::ConstraintType type = dynamics::ConstraintType::kFixed;
  /// The ODE joint; null for a Free constraint (no joint).
  dJointID id = nullptr;
  /// Stops in ODE's coordinates, one (low, high) pair per free DOF when the constraint has
  /// limits; empty otherwise.
  std::vector<std::pair<double, double>> odeStops;
};

/// An ODE world holding every body, joint and motor of a dynamic workcell in one State.
/// Owns the ODE objects; not copyable.
class OdeWorld {
 public:
  /// Builds the world with bodies where `state` puts them, at rest; each object's
  /// (trial::isVariedObject()) mass and inertia times `objectMassScale` (1: the dwc's values);
  /// the dwc's gravity, or none when `gravity` is false.
  /// @throws std::invalid_argument for bodies or devices ODE cannot simulate (mass <= 0,
  /// inertia not positive definite, a joint link that is not a rigid body, a constraint with a
  /// spring, ...).
  OdeWorld(const dynamics::DynamicWorkCell& dwc, const rw::kinematics::State& state,
           const SimulatorOptions& options, double objectMassScale, bool gravity = true);
  ~OdeWorld();
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  /// The ODE world.
  dWorldID world() const { return world_; }
  /// The joint group for this step's contacts.
  dJointGroupID contactGroup() const { return contactGroup_; }
  /// Bodies, indexed like DynamicWorkCell::bodies().
  std::vector<SimBody>& bodies() { return bodies_; }
  /// Bodies.
  const std::vector<SimBody>& bodies() const { return bodies_; }
  /// Devices, indexed like DynamicWorkCell::devices().
  std::vector<SimDevice>& devices() { return devices_; }
  /// Devices.
  const std::vector<SimDevice>& devices() const { return devices_; }
  /// Constraints, indexed like DynamicWorkCell::constraints().
  const std::vector<SimConstraint>& constraints() const { return constraints_; }
  /// Constraint rows the constraint's joint gives ODE's next step: 6 for Fixed, 5 for Prismatic
  /// and Revolute, 4 for Universal, Piston and PrismaticRotoid, 3 for Spherical and
  /// PrismaticUniversal, 0 for Free, plus 1 per DOF at or past one of its stops.
  std::size_t constraintRows(const SimConstraint& constraint) const;
  /// Marks the world as left inconsistent by an ODE error thrown out of a step: its ODE objects
  /// are then leaked instead of destroyed (destroying them would trip ODE's own assertions).
  void poison() { poisoned_ = true; }

  /// World pose of a body's frame.
  rw::math::Transform3D framePose(const SimBody& body) const;
  /// Joint value (continuous across ODE's +-pi wrap of hinge angles).
  double jointPosition(const SimJoint& joint) const;
  /// Remembers every joint's value for unwrapping; call after each step.
  void trackJoints();
  /// Joint speed.
  double jointVelocity(const SimJoint& joint) const;
  /// Sets a joint motor's velocity target and force limit for the next step (and releases a
  /// stop the joint sits on when the motor drives it away).
  /// Returns the constraint rows the joint then gives the next step (see constraintRows()).
  std::size_t setMotor(const SimJoint& joint, double velocity, double forceLimit) const;
  /// Constraint rows the joint gives ODE's next step as its motor and stops are set now: 5 for
  /// the hinge or slider, 1 more when its motor has a force limit above 0 or it sits on a stop
  /// (0 without a joint). For joints setMotor() did not set this step (passive ones).
  std::size_t constraintRows(const SimJoint& joint) const;

 private:
  void createBodies(const dynamics::DynamicWorkCell& dwc, const rw::kinematics::State& state,
                    double objectMassScale);
  void createDevices(const dynamics::DynamicWorkCell& dwc, const rw::kinematics::State& state);
  void createConstraints(const dynamics::DynamicWorkCell& dwc, const rw::kinematics::State& state);
  void destroy();
  void closeLoops(const dynamics::DynamicWorkCell& dwc, const dynamics::RigidDevice& rd,
                  const rw::kinematics::FKTable& fk, SimDevice& sim);
  void attachJoint(SimJoint& joint, dynamics::BodyId link, dynamics::BodyId parent,
                   const rw::math::Transform3D& X_W_joint, bool passive);

  dWorldID world_ = nullptr;
  dThreadingImplementationID threading_ = nullptr;
  dJointGroupID contactGroup_ = nullptr;
  bool poisoned_ = false;
  std::vector<SimBody> bodies_;
  std::vector<SimDevice> devices_;
  std::vector<SimConstraint> constraints_;
  dBodyID staticAnchor_ = nullptr;
};

/// Pose of an ODE body's own frame (its centre of mass).
rw::math::Transform3D odePose(dBodyID body);

}  // namespace rwsim::simulator::detail
