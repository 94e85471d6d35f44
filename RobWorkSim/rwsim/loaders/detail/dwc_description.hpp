#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/kinematics/property_map.hpp"
#include "rw/math/types.hpp"
#include "rwsim/dynamics/constraint.hpp"
#include "rwsim/dynamics/material_map.hpp"

namespace rwsim::loaders::detail {

using rw::common::SourceLocation;

/// A name or value together with where it was written.
struct LocatedText {
  /// The text, trimmed.
  std::string text;
  /// Where it was written.
  SourceLocation location;
};

/// What a body element says (RigidBody, FixedBody, KinematicBody, a device base or link).
struct BodyDesc {
  /// Element name: RigidBody, FixedBody, KinematicBody, KinematicBase, FixedBase, RigidBase,
  /// RefBase, RigidJoint or Link.
  std::string tag;
  /// How messages name the element, e.g. `<RigidBody frame="object">`.
  std::string element;
  /// Where the element starts.
  SourceLocation location;
  /// The frame (joint for RigidJoint, object for Link, body for RefBase) as written; device
  /// parts are relative to the device.
  std::string frame;
  /// Mass in kg (checked > 0 where it matters).
  std::optional<double> mass;
  /// Where <Mass> was written.
  SourceLocation massLocation;
  /// Given centre of mass.
  std::optional<rw::math::Vector3D> cog;
  /// Given inertia (symmetric positive definite).
  std::optional<Eigen::Matrix3d> inertia;
  /// <EstimateInertia/> was present.
  bool estimateInertia = false;
  /// Integrator name (RigidBody).
  std::optional<LocatedText> integrator;
  /// Material id.
  std::optional<LocatedText> material;
  /// Object type id.
  std::optional<LocatedText> objectType;
  /// Associated frames.
  std::vector<LocatedText> associates;
  /// Properties.
  rw::kinematics::PropertyMap properties;
};

/// A <ForceLimit joint="...">.
struct ForceLimitDesc {
  /// Joint name relative to the device.
  std::string joint;
  /// Limit, N m or N.
  double value = 0.0;
  /// Where it was written.
  SourceLocation location;
};

/// A <RigidDevice device="...">.
struct DeviceDesc {
  /// Device name.
  std::string name;
  /// How messages name the element.
  std::string element;
  /// Where the element starts.
  SourceLocation location;
  /// Force limits in file order.
  std::vector<ForceLimitDesc> forceLimits;
  /// The base (tag tells which kind), if any.
  std::optional<BodyDesc> base;
  /// RigidJoint and Link elements in file order.
  std::vector<BodyDesc> links;
};

/// A <PDDeviceController>.
struct ControllerDesc {
  /// Controller name.
  std::string name;
  /// Device name.
  std::string device;
  /// Controller type.
  std::string type;
  /// How messages name the element.
  std::string element;
  /// Where the element starts.
  SourceLocation location;
  /// The PDParams numbers (P D pairs), if given.
  std::optional<std::vector<double>> gains;
  /// Where <PDParams> was written.
  SourceLocation gainsLocation;
  /// Controller period.
  double timeStep = 0.01;
};

/// A <Constraint name type parent child>.
struct ConstraintDesc {
  /// Constraint name.
  std::string name;
  /// How messages name the element.
  std::string element;
  /// Where the element starts.
  SourceLocation location;
  /// The type (none if the type was bad; reported by the parser).
  std::optional<rwsim::dynamics::ConstraintType> type;
  /// Parent body name as written.
  std::string parent;
  /// Child body name as written.
  std::string child;
  /// The <Transform3D>, identity if none.
  rw::math::Transform3D X_parent_constraint = rw::math::Transform3D::Identity();
  /// One entry per <Limit> (checked against the type's DOF by the parser).
  std::vector<rwsim::dynamics::ConstraintLimit> limits;
  /// The <Spring>, if given.
  std::optional<rwsim::dynamics::ConstraintSpring> spring;
};

/// Everything a dynamic workcell file and its includes say, before the workcell is consulted.
struct DynamicWorkCellDesc {
  /// The workcell attribute as written.
  std::string workcellFile;
  /// Where the root element starts.
  SourceLocation rootLocation;
  /// Gravity.
  rw::math::Vector3D gravity = rw::math::Vector3D::Zero();
  /// PhysicsEngine properties (name -> value text).
  std::map<std::string, std::string> engineProperties;
  /// Materials, object types, friction and restitution, filled in document order.
  rwsim::dynamics::MaterialMap materials;
  /// Where the default material was named (to report an undeclared one).
  std::optional<LocatedText> defaultMaterial;
  /// Where the default object type was named.
  std::optional<LocatedText> defaultObjectType;
  /// RigidBody, FixedBody and KinematicBody elements in document order.
  std::vector<BodyDesc> bodies;
  /// RigidDevice elements in document order.
  std::vector<DeviceDesc> devices;
  /// PDDeviceController elements in document order.
  std::vector<ControllerDesc> controllers;
  /// Constraint elements in document order.
  std::vector<ConstraintDesc> constraints;
};

}  // namespace rwsim::loaders::detail
