#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/models/device.hpp"
#include "rw/models/setups.hpp"

namespace rw::models {

/// One geometry placed in a frame.
struct GeometryInstance {
  /// Plain (unscoped) name from the XML.
  std::string name;
  /// Pose of the geometry in its frame.
  rw::math::Transform3D X_frame_geometry = rw::math::Transform3D::Identity();
  /// The shape (shared, immutable).
  std::shared_ptr<const rw::geometry::Geometry> geometry;
  /// RGB colour in [0, 1] for drawing.
  std::array<float, 3> color{0.8f, 0.8f, 0.8f};
};

/// The geometry attached to one frame: what collides and what is drawn.
struct Object {
  /// The frame carrying the geometry.
  rw::kinematics::FrameId frame;
  /// Collision geometry (Drawables unless colmodel="Disabled", and CollisionModels).
  std::vector<GeometryInstance> collision;
  /// Visual geometry (Drawables).
  std::vector<GeometryInstance> visual;
};

/// A loaded workcell: frames, devices, geometry, setups and properties. Built once by a loader
/// (or by code through the mutable accessors before it is shared) and then used const.
class WorkCell {
 public:
  /// An empty workcell named `name`.
  explicit WorkCell(std::string name);

  /// Workcell name.
  const std::string& name() const { return name_; }
  /// The frames.
  const rw::kinematics::FrameTree& frames() const { return frames_; }
  /// The frames, for building.
  rw::kinematics::FrameTree& frames() { return frames_; }
  /// Looks a frame up by full name; invalid id if absent.
  rw::kinematics::FrameId findFrame(std::string_view name) const { return frames_.find(name); }

  /// Adds a device over frames already in the tree. @throws std::invalid_argument on a
  /// duplicate name.
  const Device& addDevice(Device::Spec spec);
  /// Adds a parallel device (spec.kind == kParallel). @throws std::invalid_argument on a
  /// duplicate name or a bad structure (see Device).
  const Device& addDevice(Device::Spec spec, ParallelStructure structure);
  /// All devices in document order.
  const std::vector<std::unique_ptr<Device>>& devices() const { return devices_; }
  /// The device with this name, or nullptr.
  const Device* findDevice(std::string_view name) const;

  /// The object of a frame, created on first use.
  Object& objectOf(rw::kinematics::FrameId frame);
  /// Objects (one per frame with geometry), in order of creation.
  const std::vector<Object>& objects() const { return objects_; }
  /// The object of a frame, or nullptr.
  const Object* findObject(rw::kinematics::FrameId frame) const;

  /// Workcell properties.
  const rw::kinematics::PropertyMap& properties() const { return properties_; }
  /// Workcell properties, for building.
  rw::kinematics::PropertyMap& properties() { return properties_; }
  /// Collision setup (merged, scoped names). Empty when the file had none.
  const CollisionSetup& collisionSetup() const { return collisionSetup_; }
  /// Collision setup, for building.
  CollisionSetup& collisionSetup() { return collisionSetup_; }
  /// Proximity setup (merged).
  const ProximitySetup& proximitySetup() const { return proximitySetup_; }
  /// Proximity setup, for building.
  ProximitySetup& proximitySetup() { return proximitySetup_; }

  /// The default state: movable frames at their initial transforms, devices at "Home" (as set by
  /// setDefaultState), or frames().makeState() when none was set for the current frames.
  rw::kinematics::State defaultState() const;
  /// Sets the default state. @throws std::invalid_argument unless it fits the current frames.
  void setDefaultState(rw::kinematics::State state);
  /// Absolute path of the file the workcell was loaded from (empty if built in code).
  const std::string& fileName() const { return fileName_; }
  /// Sets the file name.
  void setFileName(std::string fileName) { fileName_ = std::move(fileName); }

 private:
  void checkNewDeviceName(const std::string& name) const;

  std::string name_;
  rw::kinematics::FrameTree frames_;
  std::vector<std::unique_ptr<Device>> devices_;
  std::vector<Object> objects_;
  rw::kinematics::PropertyMap properties_;
  CollisionSetup collisionSetup_;
  ProximitySetup proximitySetup_;
  std::optional<rw::kinematics::State> defaultState_;
  std::string fileName_;
};

}  // namespace rw::models
