#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/xml_tree.hpp"
#include "rw/math/types.hpp"
#include "rwsim/trial/grasp_outcome.hpp"
#include "visgrab/request/grasp_request.hpp"

/// Grasp and task file formats: RobWork's GraspTask XML, the original VisGraB experiment XML
/// and the project's plain grasp list (docs/grasp-format.md).
namespace visgrab::taskio {

/// A PropertyMap entry this model has no field for, kept verbatim so that it is written back.
struct Property {
  /// The property's <Name>.
  std::string name;
  /// The property's <Description> (usually empty).
  std::string description;
  /// The typed element inside <Value>, e.g. <String>text</String> or <Q>1 2</Q>.
  rw::common::XmlElement value;
};

/// The value of the <String> property `name` in `properties`, if there is one.
std::optional<std::string> stringProperty(const std::vector<Property>& properties,
                                          std::string_view name);
/// Sets (replaces or appends) the <String> property `name`.
void setStringProperty(std::vector<Property>& properties, std::string_view name,
                       std::string_view value);

/// RobWork's Contact3D as stored in task files: 9 values p(3) n(3) f(3), object frame.
struct TaskContact {
  /// Contact point.
  rw::math::Vector3D position = rw::math::Vector3D::Zero();
  /// Contact normal.
  rw::math::Vector3D normal = rw::math::Vector3D::Zero();
  /// Contact force.
  rw::math::Vector3D force = rw::math::Vector3D::Zero();
};

/// RobWork's GraspResult (reference §3.1); property names in comments.
struct GraspResult {
  /// TestStatus: RobWork's status code (reference §3.2), 0 = UnInitialized.
  int testStatus = 0;
  /// LiftResult.
  double liftResult = 0.0;
  /// GripperConfiguration: q at grasp.
  rw::math::Q gripperConfigurationGrasp;
  /// GripperConfigurationPost: q after lifting.
  rw::math::Q gripperConfigurationLift;
  /// QualityBeforeLifting.
  rw::math::Q qualityBeforeLifting;
  /// QualityAfterLifting.
  rw::math::Q qualityAfterLifting;
  /// ObjectTtcptTarget (RobWork's spelling, with the extra "t").
  rw::math::Transform3D objectTtcpTarget = rw::math::Transform3D::Identity();
  /// ObjectTtcpApproach.
  rw::math::Transform3D objectTtcpApproach = rw::math::Transform3D::Identity();
  /// ObjectTtcpGrasp.
  rw::math::Transform3D objectTtcpGrasp = rw::math::Transform3D::Identity();
  /// ObjectTtcpLift.
  rw::math::Transform3D objectTtcpLift = rw::math::Transform3D::Identity();
  /// ContactsGrasp.
  std::vector<TaskContact> contactsGrasp;
  /// ContactsLift.
  std::vector<TaskContact> contactsLift;
  /// InterferenceTs.
  std::vector<rw::math::Transform3D> interferenceTs;
  /// InterferenceDistances.
  std::vector<double> interferenceDistances;
  /// InterferenceAngles.
  std::vector<double> interferenceAngles;
  /// Interferences.
  std::vector<double> interferences;
  /// Interference.
  double interference = 0.0;
  /// Other properties of the target, kept verbatim (LiftStatus is derived, not kept).
  std::vector<Property> otherProperties;
};

/// One grasp target: the TCP pose in refframe·offset coordinates and an optional result.
struct GraspTarget {
  /// Pose of the TCP relative to the sub-task's refframe·offset.
  rw::math::Transform3D pose = rw::math::Transform3D::Identity();
  /// The result; absent when the file's <PropertyMap> was empty.
  std::optional<GraspResult> result;
  /// Line of the <CartesianTarget> it was read from (0 if not read from a file).
  int sourceLine = 0;
};

/// RobWork's GraspSubTask (reference §3.1).
struct GraspSubTask {
  /// refframe: the frame the offset is relative to ("WORLD" by default).
  std::string refframe = "WORLD";
  /// ObjectID (written only if not empty).
  std::string objectId;
  /// The sub-task's <Id>.
  std::string taskId;
  /// Offset: refframe -> nominal frame.
  rw::math::Transform3D offset = rw::math::Transform3D::Identity();
  /// Approach displacement.
  rw::math::Transform3D approach = rw::math::Transform3D::Identity();
  /// Retract (lift) displacement.
  rw::math::Transform3D retract = rw::math::Transform3D::Identity();
  /// OpenQ: pre-shape.
  rw::math::Q openQ;
  /// CloseQ: closing target.
  rw::math::Q closeQ;
  /// TauMax: joint force limits (may be empty).
  rw::math::Q tauMax;
  /// The targets.
  std::vector<GraspTarget> targets;
  /// Other sub-task properties (e.g. VisGraB's VisGraBID), kept verbatim.
  std::vector<Property> otherProperties;
  /// Line of the sub-task's <CartesianTask> (0 if not read from a file).
  int sourceLine = 0;
};

/// RobWork's GraspTask: gripper, TCP, controller and sub-tasks (reference §3.1).
struct GraspTask {
  /// Gripper: dynamic device name.
  std::string gripperId;
  /// TCP: full name of the TCP frame.
  std::string tcpId;
  /// GraspController: controller name in the dynamic workcell.
  std::string graspControllerId;
  /// The sub-tasks.
  std::vector<GraspSubTask> subTasks;
  /// Other root properties (e.g. VisGraB's SceneID), kept verbatim.
  std::vector<Property> otherProperties;

  /// Number of targets over all sub-tasks.
  std::size_t targetCount() const;
};

/// Pose of a frame in the world, by name; nullopt if the frame is unknown.
using FrameResolver = std::function<std::optional<rw::math::Transform3D>(const std::string&)>;

/// One GraspRequest (kRaw) per target, in order (sub-tasks, then targets): pose =
/// X_W_refframe · offset · target pose, as RobWork's simulator composes it; qOpen/qClosed/tauMax
/// from the sub-task. refframe "WORLD" (or empty) is the identity; other frames go to `resolve`.
/// Ids: the sub-task's VisGraBID property for a one-target sub-task, else "<taskId or sub-task
/// index>.<target index>". @throws std::invalid_argument for a refframe that cannot be resolved.
std::vector<grasp::GraspRequest> toGraspRequests(const GraspTask& task, std::string_view sceneId,
                                                 std::string_view method,
                                                 const FrameResolver& resolve = {});

/// A task with one sub-task (refframe WORLD, VisGraBID = request id, Retract 0.1 m up as VisGraB
/// wrote) and one target per request, and root property SceneID from the first request.
/// @throws std::invalid_argument if a request is not kRaw.
GraspTask fromGraspRequests(const std::vector<grasp::GraspRequest>& requests,
                            std::string_view gripperId, std::string_view tcpId,
                            std::string_view graspControllerId = "GraspController");

/// The `index`-th target over all sub-tasks (the order of toGraspRequests).
/// @throws std::out_of_range if there is no such target.
GraspTarget& targetAt(GraspTask& task, std::size_t index);

/// Writes a trial's result into `target`: TestStatus = RobWork code of `outcome`,
/// QualityAfterLifting = {qLift}, LiftResult = qLift, QualityBeforeLifting = {qGws, qGwsUnit}
/// (the VisGraB-era plugin's q0, GWS with the measured forces, and q1, with unit forces),
/// GripperConfiguration = qGrasp. Other result fields are kept.
void setResult(GraspTarget& target, rwsim::trial::GraspOutcome outcome, double qLift, double qGws,
               double qGwsUnit, const rw::math::Q& qGrasp);

}  // namespace visgrab::taskio
