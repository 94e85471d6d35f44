#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_tree.hpp"
#include "rw/loaders/detail/wc_description.hpp"

/// Readers of single workcell elements (values, units and per-element checks), used by the
/// description parser. Each reports its own problems at the element and returns nullopt then.
namespace rw::loaders::detail {

/// Origin (location and label) of an element.
Origin originOf(const common::XmlElement& element);

/// Collects the RPY/Pos/Transform children of one element and makes the transform.
class TransformReader {
 public:
  /// Takes `child` if it is RPY, Pos or Transform (returns true); reports duplicates.
  bool take(const common::XmlElement& owner, const common::XmlElement& child,
            common::DiagnosticSink& sink);
  /// True if any transform element was seen.
  bool any() const { return rpy_ != nullptr || pos_ != nullptr || matrix_ != nullptr; }
  /// The transform (identity if none was given); nullopt after reporting a lone RPY or Pos,
  /// a bad number list or a Transform whose rotation part is not a rotation.
  std::optional<rw::math::Transform3D> finish(const common::XmlElement& owner,
                                              common::DiagnosticSink& sink) const;

 private:
  const common::XmlElement* rpy_ = nullptr;
  const common::XmlElement* pos_ = nullptr;
  const common::XmlElement* matrix_ = nullptr;
};

/// True for Box, Sphere, Cylinder, Tube, Cone, Plane, Custom and Polytope.
bool isGeometryElement(std::string_view name);

/// Reads one geometry element (sizes checked: Custom is reported as not supported).
std::optional<GeometryDesc> readGeometry(const common::XmlElement& element,
                                         common::DiagnosticSink& sink);

/// Reads a Property; a type other than string, double or Q is a warning and gives nullopt.
std::optional<PropertyDesc> readProperty(const common::XmlElement& element,
                                         common::DiagnosticSink& sink);

/// Reads a PosLimit/VelLimit/AccLimit; `owner` names the enclosing joint in messages (may be
/// empty). min > max and negative velocity/acceleration limits are errors.
std::optional<LimitDesc> readLimit(const common::XmlElement& element, const std::string& owner,
                                   common::DiagnosticSink& sink);

/// Reads a Depend (scope filled in by the caller).
std::optional<DependDesc> readDepend(const common::XmlElement& element,
                                     common::DiagnosticSink& sink);

/// Reads a Q element.
std::optional<QDesc> readQ(const common::XmlElement& element, common::DiagnosticSink& sink);

/// Frame kind given by a `type` attribute.
struct FrameKind {
  /// Kind of frame.
  rw::kinematics::FrameType type = rw::kinematics::FrameType::kFixed;
  /// EndEffector.
  bool endEffector = false;
};

/// Interprets a Frame/Joint `type` value; reports unknown and unsupported types.
std::optional<FrameKind> readFrameType(const common::XmlElement& element, const std::string& value,
                                       common::DiagnosticSink& sink);

/// Placement and joint type of a DHJoint.
struct DhPlacement {
  /// Fixed transform (joint at q = 0).
  rw::math::Transform3D transform = rw::math::Transform3D::Identity();
  /// kRevolute or kPrismatic.
  rw::kinematics::FrameType type = rw::kinematics::FrameType::kRevolute;
};

/// Reads the DH attributes of a DHJoint (reference §1.3).
std::optional<DhPlacement> readDhJoint(const common::XmlElement& element,
                                       common::DiagnosticSink& sink);

/// For the XML reader: names the attribute or text of `element` that is not a valid value
/// (number, number count, boolean), or returns an empty string.
std::string explainWorkCellValueError(const common::XmlElement& element);

}  // namespace rw::loaders::detail
