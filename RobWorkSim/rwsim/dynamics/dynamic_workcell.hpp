#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rw/models/workcell.hpp"
#include "rwsim/dynamics/constraint.hpp"
#include "rwsim/dynamics/ids.hpp"
#include "rwsim/dynamics/material_map.hpp"

namespace rwsim::dynamics {

/// How a body moves.
enum class BodyKind {
  kRigid,      ///< free body under gravity and contacts (RigidBody, device links)
  kKinematic,  ///< moved by a commanded trajectory, unaffected by forces (KinematicBody/Base)
  kFixed,      ///< never moves (FixedBody/FixedBase)
};

/// Mass properties of a body in its body frame.
struct MassProperties {
  /// Mass in kg.
  double mass = 0.0;
  /// Centre of mass in the body frame.
  rw::math::Vector3D cog = rw::math::Vector3D::Zero();
  /// Inertia tensor about the centre of mass, body-frame axes, kg m^2.
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// One body of the dynamic workcell.
struct Body {
  /// Name: the full name of the body frame.
  std::string name;
  /// The body frame (Movable for rigid and kinematic bodies, a joint frame for device links).
  rw::kinematics::FrameId frame;
  /// How it moves.
  BodyKind kind = BodyKind::kRigid;
  /// Mass properties (rigid bodies; kinematic and fixed bodies keep zeros).
  MassProperties mass;
  /// Material id (declared in materials()).
  std::string material;
  /// Object type id (for restitution).
  std::string objectType;
  /// Frames whose collision geometry belongs to this body: the body frame, the frames rigidly
  /// attached below it that are no body of their own, and `Associate`d frames.
  std::vector<rw::kinematics::FrameId> geometryFrames;
  /// The device of device bases and links; none otherwise.
  DeviceId device;
  /// Body properties (e.g. LinearDamping, AngularDamping).
  rw::kinematics::PropertyMap properties;
};

/// How the simulator closes one leg of a parallel device's junction against the junction's
/// first leg. The links of every leg are simulated as a tree (one body per link, a hinge or
/// slider per joint); each junction then adds, per leg after the first, one joint between the
/// bodies that carry the leg ends (a project extension: RobWorkSim has no dwc syntax for
/// parallel devices).
struct LoopClosure {
  /// Index of the junction in ParallelKinematics::junctions().
  std::size_t junction = 0;
  /// Index of the leg closed against leg 0.
  std::size_t leg = 0;
  /// The joint that closes the loop: a joint on the way from a leg end up to the body carrying
  /// it that has no link body of its own (RobWork's models end a leg with such a joint, e.g.
  /// the Robotiq's LinkConnection). It becomes a hinge or slider between `parent` and `child`.
  /// None when both leg ends sit rigidly on their bodies: the two bodies are then welded.
  rw::kinematics::FrameId joint;
  /// The body above `joint` (for a weld: the body carrying leg 0's end).
  BodyId parent;
  /// The body carrying the other leg's end, which moves with `joint` (for a weld: the body
  /// carrying this leg's end).
  BodyId child;
};

/// A device simulated with rigid links driven by joint motors (RobWork's RigidDevice).
struct RigidDevice {
  /// The kinematic device in the workcell.
  const rw::models::Device* device = nullptr;
  /// The base body.
  BodyId baseBody;
  /// For each joint of device->joints() (dependent ones included), the link body or none.
  std::vector<BodyId> linkBodies;
  /// Motor force/torque limit of each joint of device->joints() (N m or N).
  std::vector<double> forceLimits;
  /// How the simulator closes each junction of a parallel device (empty otherwise): set by
  /// DynamicWorkCell::addDevice (rwsim::dynamics::loopClosures); whatever it held is replaced.
  std::vector<LoopClosure> loopClosures;
};

/// A PD joint controller (RobWork's PDDeviceController).
struct PDController {
  /// Controller name (e.g. "GraspController").
  std::string name;
  /// The controlled device.
  DeviceId device;
  /// Position, CntPosition, Velocity, Force or Current (only Position is simulated).
  std::string type = "Position";
  /// Proportional gain per DOF (1/s for RobWork's velocity-output law).
  Eigen::VectorXd p;
  /// Derivative gain per DOF (s).
  Eigen::VectorXd d;
  /// Controller period from the file (RobWork stores it but does not use it).
  double timeStep = 0.01;
};

/// A workcell plus everything the simulator needs: bodies, devices, materials, controllers,
/// gravity and engine settings. Built once by the loader (or in code), then used const.
class DynamicWorkCell {
 public:
  /// Takes the kinematic workcell. @throws std::invalid_argument if it is null.
  explicit DynamicWorkCell(std::unique_ptr<rw::models::WorkCell> workcell);

  /// The kinematic workcell.
  const rw::models::WorkCell& workcell() const { return *workcell_; }
  /// All bodies.
  const std::vector<Body>& bodies() const { return bodies_; }
  /// The body with this name (frame name), or none.
  BodyId findBody(std::string_view name) const;
  /// The body whose geometry frames include `frame`, or none.
  BodyId bodyOfFrame(rw::kinematics::FrameId frame) const;
  /// The body nearest above `frame`: the first frame on the path from its parent to the world
  /// that belongs to a body; none if there is none.
  BodyId bodyAbove(rw::kinematics::FrameId frame) const;
  /// The body with this id. Precondition: `id` is valid and < bodies().size().
  const Body& body(BodyId id) const { return bodies_[id.index()]; }
  /// Rigid devices.
  const std::vector<RigidDevice>& devices() const { return devices_; }
  /// The rigid device over the kinematic device with this name, or none.
  DeviceId findDevice(std::string_view name) const;
  /// The rigid device with this id. Precondition: `id` is valid and < devices().size().
  const RigidDevice& device(DeviceId id) const { return devices_[id.index()]; }
  /// PD controllers.
  const std::vector<PDController>& controllers() const { return controllers_; }
  /// The controller with this name, or nullptr.
  const PDController* findController(std::string_view name) const;
  /// Body-to-body constraints (RobWorkSim's `<Constraint>`).
  const std::vector<Constraint>& constraints() const { return constraints_; }
  /// The constraint with this name, or nullptr.
  const Constraint* findConstraint(std::string_view name) const;
  /// Materials, friction and restitution.
  const MaterialMap& materials() const { return materials_; }
  /// Gravity in world coordinates, m/s^2.
  const rw::math::Vector3D& gravity() const { return gravity_; }
  /// Physics-engine properties from the file (name -> value text), e.g. "StepMethod".
  const std::map<std::string, std::string>& engineProperties() const { return engineProperties_; }
  /// File the dynamic workcell was loaded from (empty when built in code).
  const std::string& fileName() const { return fileName_; }

  /// Adds a body and returns its id. An empty `geometryFrames` is filled with
  /// rigidlyAttachedFrames(frame, stopAt = the frames of the bodies added so far), so bodies on
  /// Fixed frames below another body's frame must be added first (or their frames listed).
  /// `device` must be none: addDevice sets it.
  /// @throws std::invalid_argument on an empty or duplicate name, an unknown frame, a frame (or
  /// geometry frame) that belongs to another body, a rigid body that is not on a Movable frame
  /// or a joint, a kinematic body not on a Movable frame, a rigid body whose mass is not > 0 or
  /// whose inertia is not symmetric positive definite, or an undeclared material or object type.
  BodyId addBody(Body body);
  /// Adds a rigid device and returns its id; sets Body::device of its base (unless the base
  /// already belongs to another device) and of its links.
  /// @throws std::invalid_argument unless the device is one of workcell().devices() and not yet
  /// added, forceLimits and linkBodies have one entry per device->joints() (limits finite and
  /// >= 0), the base is a valid body and each link is none or an unused rigid body on its
  /// joint's frame.
  DeviceId addDevice(RigidDevice device);
  /// Adds a controller.
  /// @throws std::invalid_argument on an empty or duplicate name, an invalid device, gains
  /// whose sizes differ from the device's DOF or that are not finite, an unknown type, or a time
  /// step that is not > 0.
  void addController(PDController controller);
  /// Adds a constraint.
  /// @throws std::invalid_argument on an empty or duplicate name, an invalid body, parent ==
  /// child, two bodies neither of which is rigid, a transform that is not finite or not a
  /// rotation, limits that are not one per free DOF, a limit with low > high (or NaN), limits
  /// on a Spherical or Free constraint (RobWorkSim has none there), angular limits outside
  /// [-pi, pi], or spring matrices that are not DOF x DOF and finite.
  void addConstraint(Constraint constraint);
  /// Materials, for building.
  MaterialMap& materials() { return materials_; }
  /// Sets gravity.
  void setGravity(const rw::math::Vector3D& g) { gravity_ = g; }
  /// Sets an engine property.
  void setEngineProperty(const std::string& name, const std::string& value) {
    engineProperties_[name] = value;
  }
  /// Sets the file name.
  void setFileName(std::string fileName) { fileName_ = std::move(fileName); }

 private:
  std::unique_ptr<rw::models::WorkCell> workcell_;
  std::vector<Body> bodies_;
  std::vector<BodyId> bodyOfFrame_;
  std::vector<RigidDevice> devices_;
  std::vector<PDController> controllers_;
  std::vector<Constraint> constraints_;
  MaterialMap materials_;
  rw::math::Vector3D gravity_ = rw::math::Vector3D::Zero();
  std::map<std::string, std::string> engineProperties_;
  std::string fileName_;
};

/// Frames whose geometry a body on `frame` carries: `frame` and the frames below it reached
/// through Fixed frames only (stopping at joints, movable frames, dynamically attachable frames
/// and `stopAt` frames), in depth-first order with `frame` first.
std::vector<rw::kinematics::FrameId> rigidlyAttachedFrames(
    const rw::kinematics::FrameTree& tree, rw::kinematics::FrameId frame,
    const std::vector<rw::kinematics::FrameId>& stopAt);

/// The body pairs a device joint connects: each joint's link body with the body nearest above
/// the joint; also the bodies of each loop closure and of each constraint but Free ones. Each
/// pair once as (smaller, larger) id, sorted. Their model geometry usually
/// overlaps at the joint, so contact detection skips them (as MuJoCo skips parent-child pairs).
std::vector<std::pair<BodyId, BodyId>> jointConnectedBodyPairs(const DynamicWorkCell& dwc);

}  // namespace rwsim::dynamics
