#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/geometry/geometry.hpp"
#include "rw/kinematics/frame.hpp"
#include "rw/kinematics/property_map.hpp"
#include "rw/math/types.hpp"

/// The plain description of a workcell file (first pass): what the XML says, with scoped names
/// and the location of every element, before any model object is built.
namespace rw::loaders::detail {

/// Where an element is and how messages name it.
struct Origin {
  /// Position of the element's start tag.
  common::SourceLocation location;
  /// `<Joint name="j1">`: the element as messages show it.
  std::string element;
};

/// One geometry element (a primitive or a Polytope).
struct GeometryDesc {
  /// The element.
  Origin origin;
  /// Shape kind (kMesh for a Polytope).
  rw::geometry::GeometryType type = rw::geometry::GeometryType::kBox;
  /// Primitive parameters in XML attribute order.
  std::vector<double> parameters;
  /// Polytope: the file attribute as written.
  std::string meshName;
  /// Polytope: folder of the file the element is written in (relative names start there).
  std::string baseDir;
};

/// A Drawable or CollisionModel.
struct ModelDesc {
  /// The element.
  Origin origin;
  /// Plain name from the XML.
  std::string name;
  /// Full name of the frame it belongs to.
  std::string frame;
  /// Creates visual geometry (Drawable).
  bool visual = true;
  /// Creates collision geometry (CollisionModel, or Drawable without colmodel="Disabled").
  bool collision = true;
  /// Pose of the geometry in the frame.
  rw::math::Transform3D transform = rw::math::Transform3D::Identity();
  /// Colour from <RGB> (Drawable only); nullopt: the default grey.
  std::optional<std::array<float, 3>> color;
  /// The shapes.
  std::vector<GeometryDesc> geometries;
};

/// A Property element with its value already converted.
struct PropertyDesc {
  /// The element.
  Origin origin;
  /// Property name.
  std::string name;
  /// Value and description.
  rw::kinematics::Property property;
};

/// Which limit an element sets.
enum class LimitKind { kPosition, kVelocity, kAcceleration };

/// A PosLimit, VelLimit or AccLimit, values as written (degrees for revolute joints).
struct LimitDesc {
  /// The element.
  Origin origin;
  /// Kind of limit.
  LimitKind kind = LimitKind::kPosition;
  /// Full name of the joint (device-level limits), empty inside a joint.
  std::string joint;
  /// Lower position limit (kPosition only).
  double min = 0.0;
  /// Upper limit.
  double max = 0.0;
};

/// A Depend element: the enclosing joint follows `on`.
struct DependDesc {
  /// The element.
  Origin origin;
  /// Owner name as written.
  std::string on;
  /// Scope at the element, outermost first (for the lookup in shorter scopes).
  std::vector<std::string> scope;
  /// Gain.
  double gain = 1.0;
  /// Offset (raw).
  double offset = 0.0;
};

/// A Frame, Joint or DHJoint.
struct FrameDesc {
  /// The element.
  Origin origin;
  /// Full (scoped) name.
  std::string name;
  /// Full name of the parent frame, decided by RobWork's attachment rules.
  std::string parent;
  /// True when `parent` comes from a refframe attribute (so an unknown name is the user's).
  bool parentFromRefframe = false;
  /// Frame kind.
  rw::kinematics::FrameType type = rw::kinematics::FrameType::kFixed;
  /// Marks an end of a TreeDevice.
  bool endEffector = false;
  /// Dynamically attachable.
  bool daf = false;
  /// state="Passive".
  bool passive = false;
  /// Transform relative to the parent (placement at q = 0 for joints).
  rw::math::Transform3D transform = rw::math::Transform3D::Identity();
  /// Coupling to another joint.
  std::optional<DependDesc> depend;
  /// Limits written inside the element.
  std::vector<LimitDesc> limits;
  /// Properties written inside the element.
  std::vector<PropertyDesc> properties;
  /// Index of the device it belongs to, -1 at workcell level.
  int device = -1;
  /// Name of the innermost SerialChain around it; empty outside every chain.
  std::string chain;
};

/// A named configuration.
struct QDesc {
  /// The element.
  Origin origin;
  /// Name ("Home" sets the default state).
  std::string name;
  /// Values (raw).
  std::vector<double> values;
};

/// A CollisionSetup or ProximitySetup element.
struct SetupRef {
  /// The element.
  Origin origin;
  /// The file as written.
  std::string file;
  /// The file to read (relative to the folder of the file holding the element).
  std::string path;
  /// Scope prefix for the names inside ("Dev." or "Dev.Chain."; empty at workcell level).
  std::string prefix;
};

/// A `<Chains>` element of a Junction: SerialChain names joined into one leg.
struct ChainsDesc {
  /// The element.
  Origin origin;
  /// The names, in order (unscoped, as written).
  std::vector<std::string> names;
};

/// A `<Junction>` of a ParallelDevice.
struct JunctionDesc {
  /// The element.
  Origin origin;
  /// One entry per leg.
  std::vector<ChainsDesc> legs;
};

/// A SerialDevice, TreeDevice or ParallelDevice.
struct DeviceDesc {
  /// The element.
  Origin origin;
  /// Device name.
  std::string name;
  /// True for a TreeDevice.
  bool tree = false;
  /// True for a ParallelDevice (frames attach as in a TreeDevice).
  bool parallel = false;
  /// Junctions of a ParallelDevice.
  std::vector<JunctionDesc> junctions;
  /// Indices into WorkCellDesc::frames, document order (first = base).
  std::vector<int> frames;
  /// Device-level limits.
  std::vector<LimitDesc> limits;
  /// Device-level properties.
  std::vector<PropertyDesc> properties;
  /// Named configurations.
  std::vector<QDesc> configurations;
};

/// The whole file after Include/Define/Use expansion.
struct WorkCellDesc {
  /// Workcell name (empty for a bare device file).
  std::string name;
  /// Every frame, in document order.
  std::vector<FrameDesc> frames;
  /// Devices in document order.
  std::vector<DeviceDesc> devices;
  /// Every Drawable/CollisionModel in document order, with its frame's full name.
  std::vector<ModelDesc> models;
  /// Workcell properties.
  std::vector<PropertyDesc> properties;
  /// CollisionSetup elements in document order.
  std::vector<SetupRef> collisionSetups;
  /// ProximitySetup elements in document order.
  std::vector<SetupRef> proximitySetups;
};

}  // namespace rw::loaders::detail
