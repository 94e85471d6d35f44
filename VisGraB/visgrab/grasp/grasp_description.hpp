#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"
#include "rw/math/types.hpp"

namespace visgrab::grasp {

/// Where an element of a grasp description was written.
using SourceLocation = rw::common::SourceLocation;

/// A named pre-shape as written (paper §2.3.2).
struct PreShapeSpec {
  /// Name ("SDH_CYL").
  std::string name;
  /// Further names ("cyl").
  std::vector<std::string> aliases;
  /// Configuration when placed.
  std::vector<double> qOpen;
  /// Configuration the fingers close towards.
  std::vector<double> qClosed;
  /// Torque limits; nullopt: the torque rule applied to qOpen.
  std::optional<std::vector<double>> tauMax;
  /// Frame X_hand refers to; empty: the description's tcp.
  std::string tcp;
  /// Where it was written.
  SourceLocation where;
};

/// One closing offset as written: degrees for revolute joints, metres for prismatic ones.
struct CloseOffsetSpec {
  /// Joint name.
  std::string joint;
  /// Offset in the file's units.
  double value = 0.0;
  /// Where it was written.
  SourceLocation where;
};

/// f(angle) of a torque adjustment.
enum class TauFunction {
  kOne,     ///< 1
  kCos,     ///< cos(angle)
  kSecant,  ///< 1 / cos(angle)
};

/// One torque adjustment as written (see xml/grasp-description.xsd, element Adjust).
struct TauAdjustSpec {
  /// Joint whose qOpen value is the angle.
  std::string angleJoint;
  /// Lower bound of the angle (inclusive), degrees; nullopt: open.
  std::optional<double> atLeastDeg;
  /// Upper bound of the angle (exclusive), degrees; nullopt: open.
  std::optional<double> belowDeg;
  /// Joints whose limit is set.
  std::vector<std::string> joints;
  /// Joint whose base limit is scaled.
  std::string source;
  /// Gain.
  double gain = 1.0;
  /// f(angle).
  TauFunction function = TauFunction::kOne;
  /// Lowest result.
  double floor = 0.0;
  /// Where it was written.
  SourceLocation where;
};

/// The torque-limit rule as written.
struct TauRuleSpec {
  /// Base limits, one per DOF.
  std::vector<double> base;
  /// Adjustments in order.
  std::vector<TauAdjustSpec> adjust;
  /// Where it was written.
  SourceLocation where;
};

/// A fingertip of the contact IK as written.
struct FingertipSpec {
  /// Name used by Grasp elements ("thumb").
  std::string name;
  /// Frame name.
  std::string frame;
  /// Pad point in the frame, m.
  rw::math::Vector3D point = rw::math::Vector3D::Zero();
  /// Push direction in the frame.
  rw::math::Vector3D normal = rw::math::Vector3D::UnitZ();
  /// Where it was written.
  SourceLocation where;
};

/// One way of solving a contact grasp, as written.
struct IkGraspSpec {
  /// Number of contacts it solves.
  int contacts = 0;
  /// Fingertip names, one per contact.
  std::vector<std::string> fingers;
  /// Joints the solver may move; empty: all.
  std::vector<std::string> joints;
  /// Seed configurations.
  std::vector<std::vector<double>> seeds;
  /// Own closing offsets; nullopt: the description's Closing.
  std::optional<std::vector<CloseOffsetSpec>> closing;
  /// Where it was written.
  SourceLocation where;
};

/// Contact IK settings as written.
struct ContactIkSpec {
  /// Fingertips start this far short of their contacts, m.
  double backoff = 0.01;
  /// Largest accepted fingertip position deviation, m.
  double maxPositionError = 0.01;
  /// Largest accepted push-direction deviation, degrees.
  double maxDirectionErrorDeg = 30.0;
  /// Largest accepted approach-axis deviation, degrees.
  double maxApproachErrorDeg = 45.0;
  /// Weight of the direction residuals, m.
  double directionWeight = 0.01;
  /// Weight of the approach residual, m.
  double approachWeight = 0.02;
  /// The approach axis in the tcp frame.
  rw::math::Vector3D approachAxis = rw::math::Vector3D::UnitZ();
  /// Fingertips.
  std::vector<FingertipSpec> fingertips;
  /// Ways of solving.
  std::vector<IkGraspSpec> grasps;
  /// Where it was written.
  SourceLocation where;
};

/// A parallel-jaw frame as written (<JawFrame>): where a hand's pads are, so that a
/// hand-independent jaw grasp can place it (docs/grasp-format.md, "Parallel-jaw grasps").
struct JawFrameSpec {
  /// Name or alias of the pre-shape that opens the jaws.
  std::string preshape;
  /// Frame that position and the axes are written in; empty: the description's tcp.
  std::string frame;
  /// The centre between the pads with the jaws open at the pre-shape, m, in `frame`.
  rw::math::Vector3D position = rw::math::Vector3D::Zero();
  /// Direction of travel towards the object (the jaw frame's z), in `frame`; need not be unit.
  rw::math::Vector3D approach = rw::math::Vector3D::UnitZ();
  /// The axis the pads close along (the jaw frame's x), in `frame`; need not be unit.
  rw::math::Vector3D closing = rw::math::Vector3D::UnitX();
  /// Opening between the pads at the pre-shape, m.
  double stroke = 0.0;
  /// Distance from the pad centre along the approach to the fingertips' front, m.
  double tipDepth = 0.0;
  /// Where it was written.
  SourceLocation where;
};

/// A hand's grasp description file (`<hand>.grasp.xml`) as written: the first pass of the
/// loader, names not yet checked against the hand's model.
struct GraspDescription {
  /// The file, as given to the loader.
  std::string file;
  /// The hand's workcell file, as written (relative to the description's folder).
  std::string workcell;
  /// The hand's dynamics (a RobWorkSim IncludeData file with its RigidDevice and controller,
  /// included by scenes), as written; empty: beside the workcell, the workcell's file name up to
  /// its first dot + "_dynamics.dwc.xml".
  std::string dynamics;
  /// Device name.
  std::string device;
  /// Controller name.
  std::string controller;
  /// TCP frame name.
  std::string tcp;
  /// Pre-shapes in file order.
  std::vector<PreShapeSpec> preshapes;
  /// Closing rule of pose + q grasps (and of contact grasps without their own); nullopt: the
  /// description has no <Closing> (a hand that runs only pre-shape and raw grasps).
  std::optional<std::vector<CloseOffsetSpec>> closing;
  /// Torque-limit rule.
  TauRuleSpec tauRule;
  /// Contact IK settings (nullopt: the hand cannot solve contact grasps).
  std::optional<ContactIkSpec> contactIk;
  /// The parallel-jaw frame (nullopt: the hand runs no jaw grasps).
  std::optional<JawFrameSpec> jawFrame;
  /// Where the root element was written.
  SourceLocation where;
};

/// Reads and validates (xml/grasp-description.xsd, compiled in) a grasp description.
/// Errors go to `sink`, each at file:line:column; returns nullopt if there was one.
std::optional<GraspDescription> parseGraspDescription(std::string_view xml,
                                                      const std::filesystem::path& file,
                                                      rw::common::DiagnosticSink& sink);

}  // namespace visgrab::grasp
