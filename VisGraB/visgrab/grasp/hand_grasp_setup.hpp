#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/kinematics/state.hpp"
#include "rw/models/workcell.hpp"
#include "visgrab/grasp/grasp_description.hpp"

namespace visgrab::grasp {

/// A pre-shape ready for use: all vectors have one value per DOF.
struct PreShape {
  /// Name.
  std::string name;
  /// Further names.
  std::vector<std::string> aliases;
  /// Configuration when placed.
  rw::math::Q qOpen;
  /// Configuration the fingers close towards.
  rw::math::Q qClosed;
  /// Torque limits (given or by the rule).
  rw::math::Q tauMax;
  /// Pose of the hand's tcp in the frame the pre-shape's X_hand refers to (identity if same).
  rw::math::Transform3D X_shapeTcp_tcp = rw::math::Transform3D::Identity();
};

/// One torque adjustment with joints as DOF indices and angles in radians.
struct TauAdjust {
  /// DOF index of the angle joint.
  int angleIndex = 0;
  /// Lower bound (inclusive), rad.
  double atLeast = -1e300;
  /// Upper bound (exclusive), rad.
  double below = 1e300;
  /// DOF indices set.
  std::vector<int> joints;
  /// DOF index whose base value is scaled.
  int source = 0;
  /// Gain.
  double gain = 1.0;
  /// f(angle).
  TauFunction function = TauFunction::kOne;
  /// Lowest result.
  double floor = 0.0;
};

/// The torque-limit rule: base limits, then adjustments driven by a joint's angle in qOpen.
struct TauRule {
  /// Base limits, one per DOF.
  rw::math::Q base;
  /// Adjustments, applied in order; each reads `base` and writes the result.
  std::vector<TauAdjust> adjust;

  /// tau_max for a grasp that starts at qOpen. Precondition: qOpen.size() == base.size().
  rw::math::Q evaluate(const rw::math::Q& qOpen) const;
};

/// A fingertip of the contact IK, resolved.
struct Fingertip {
  /// Name.
  std::string name;
  /// Frame.
  rw::kinematics::FrameId frame;
  /// Pad point in the frame, m.
  rw::math::Vector3D point = rw::math::Vector3D::Zero();
  /// Unit push direction in the frame.
  rw::math::Vector3D normal = rw::math::Vector3D::UnitZ();
};

/// One way of solving a contact grasp, resolved.
struct IkGrasp {
  /// Number of contacts.
  int contacts = 0;
  /// Indices into ContactIkSettings::fingertips, one per contact.
  std::vector<int> fingers;
  /// DOF indices the solver may move, ascending.
  std::vector<int> joints;
  /// Seed configurations (one value per DOF).
  std::vector<rw::math::Q> seeds;
  /// Closing offsets (one per DOF, rad or m).
  rw::math::Q closeOffset;
};

/// Contact IK settings, resolved (angles in radians, approach axis unit, in the base frame).
struct ContactIkSettings {
  /// See ContactIkSpec.
  double backoff = 0.01;
  /// See ContactIkSpec.
  double maxPositionError = 0.01;
  /// Radians.
  double maxDirectionError = 0.5;
  /// Radians.
  double maxApproachError = 0.8;
  /// See ContactIkSpec.
  double directionWeight = 0.01;
  /// See ContactIkSpec.
  double approachWeight = 0.02;
  /// Unit approach axis in the hand's base frame.
  rw::math::Vector3D approachAxisInBase = rw::math::Vector3D::UnitZ();
  /// Fingertips.
  std::vector<Fingertip> fingertips;
  /// Ways of solving, in file order.
  std::vector<IkGrasp> grasps;
};

/// A hand's parallel-jaw frame (GraspDescription::jawFrame checked against the model): how a
/// hand-independent jaw grasp (GraspKind::kJaw) places this hand.
struct JawFrame {
  /// The jaw frame in the hand's TCP frame: origin at the centre between the finger pads (with
  /// the jaws open at `preshape`), z the approach axis, x the closing axis, y = z x x.
  rw::math::Transform3D X_tcp_jaw = rw::math::Transform3D::Identity();
  /// Largest opening between the pads (at `preshape`), m.
  double stroke = 0.0;
  /// Distance from the pad centre to the fingertips' front along the approach axis, m (where a
  /// GraspNet grasp's depth is measured to).
  double tipDepth = 0.0;
  /// Index in HandGraspSetup::preshapes() of the pre-shape that opens the jaws (q_open, q_closed,
  /// tau_max of a jaw grasp).
  std::size_t preshape = 0;
};

/// A hand's grasp description checked against its kinematic model, prepared once and then used
/// const (from any number of threads): what resolve() and the contact IK need.
class HandGraspSetup {
 public:
  /// Checks `description` against `workcell` and prepares it. Errors are reported to `sink`
  /// at the lines of the description; returns nullptr if there was one.
  static std::unique_ptr<HandGraspSetup> build(GraspDescription description,
                                               std::shared_ptr<const rw::models::WorkCell> workcell,
                                               rw::common::DiagnosticSink& sink);

  /// The description as read.
  const GraspDescription& description() const { return description_; }
  /// The hand's kinematic model.
  const rw::models::WorkCell& workcell() const { return *workcell_; }
  /// The hand's workcell file (absolute, normalised; empty when built from a workcell in code).
  const std::filesystem::path& workcellFile() const { return workcellFile_; }
  /// The hand's dynamics file (GraspDescription::dynamics resolved; absolute, normalised;
  /// empty when built in code).
  const std::filesystem::path& dynamicsFile() const { return dynamicsFile_; }
  /// The hand's device.
  const rw::models::Device& device() const { return *device_; }
  /// Degrees of freedom of the hand.
  int dof() const { return device_->dof(); }
  /// Full name of the TCP frame (as GraspTrialSetup::tcpFrame wants it).
  const std::string& tcpFrameName() const { return tcpName_; }
  /// The TCP frame.
  rw::kinematics::FrameId tcpFrame() const { return tcp_; }
  /// The frame the grasp utilities move to place the hand: the device's base when it is
  /// Movable (the project's hands), otherwise the Movable frame that holds the base rigidly
  /// (a device file that cannot be edited, such as RobWork's Robotiq, put after a Movable mount
  /// frame). "base" in X_base_tcp and in the contact IK means this frame.
  rw::kinematics::FrameId placementFrame() const { return placement_; }
  /// X_base_tcp (rigid; base = placementFrame()).
  const rw::math::Transform3D& X_base_tcp() const { return X_base_tcp_; }
  /// Device name.
  const std::string& deviceName() const { return description_.device; }
  /// Controller name.
  const std::string& controllerName() const { return description_.controller; }
  /// Pre-shapes in file order.
  const std::vector<PreShape>& preshapes() const { return preshapes_; }
  /// The pre-shape with this name or alias (exact match), or nullptr.
  const PreShape* findPreshape(std::string_view name) const;
  /// Closing offsets of pose + q grasps, one per DOF (rad or m); zero when there is no rule.
  const rw::math::Q& closeOffset() const { return closeOffset_; }
  /// False when the grasp description has no <Closing>: pose + q grasps cannot run.
  bool hasClosingRule() const { return hasClosingRule_; }
  /// The torque rule.
  const TauRule& tauRule() const { return tauRule_; }
  /// Contact IK settings, or nullptr if the hand has none.
  const ContactIkSettings* contactIk() const { return contactIk_ ? &*contactIk_ : nullptr; }
  /// The hand's jaw frame, or nullptr if its description declares none (not a parallel-jaw
  /// hand: jaw grasps cannot run on it).
  const JawFrame* jawFrame() const { return jawFrame_ ? &*jawFrame_ : nullptr; }
  /// The workcell's default state (a copy is the starting point of every computation).
  const rw::kinematics::State& defaultState() const { return defaultState_; }

 private:
  HandGraspSetup() = default;
  friend class SetupBuilder;
  friend std::unique_ptr<HandGraspSetup> loadHandGraspSetupFromString(
      std::string_view xml, const std::filesystem::path& virtualFile);

  GraspDescription description_;
  std::shared_ptr<const rw::models::WorkCell> workcell_;
  const rw::models::Device* device_ = nullptr;
  std::string tcpName_;
  rw::kinematics::FrameId tcp_;
  rw::kinematics::FrameId placement_;
  rw::math::Transform3D X_base_tcp_ = rw::math::Transform3D::Identity();
  std::vector<PreShape> preshapes_;
  rw::math::Q closeOffset_;
  bool hasClosingRule_ = true;
  TauRule tauRule_;
  std::optional<ContactIkSettings> contactIk_;
  std::optional<JawFrame> jawFrame_;
  rw::kinematics::State defaultState_;
  std::filesystem::path workcellFile_;
  std::filesystem::path dynamicsFile_;
};

/// Loads a grasp description file and the hand's workcell it names (rw::loaders::loadWorkCell),
/// and prepares them. `file` may also be a hand's folder (e.g. scenes/hands/pg70): the one
/// `*.grasp.xml` in it. @throws rw::common::LoadError listing every error, each at the
/// file:line:column of the description (or of the workcell, if that fails to load); for a
/// folder without exactly one grasp description, naming the folder and what it holds.
std::unique_ptr<HandGraspSetup> loadHandGraspSetup(const std::filesystem::path& file);

/// The grasp description of a hand given as a file or as its folder (see loadHandGraspSetup).
/// @throws rw::common::LoadError as loadHandGraspSetup for a folder.
std::filesystem::path graspDescriptionFile(const std::filesystem::path& fileOrFolder);

/// Same as loadHandGraspSetup, reading the description from `xml`; its workcell attribute
/// resolves against the folder of `virtualFile`, and messages name `virtualFile`.
/// @throws rw::common::LoadError listing every error.
std::unique_ptr<HandGraspSetup> loadHandGraspSetupFromString(
    std::string_view xml, const std::filesystem::path& virtualFile);

}  // namespace visgrab::grasp
