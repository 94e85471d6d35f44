#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rw/math/types.hpp"

/// Trial protocols as data (docs/protocols.md): what a grasp trial does after it placed the hand
/// and how it judges the grasp. The paper's lift is the default (TrialProtocol::lift(),
/// scenes/protocols/lift.xml); ACRONYM's shake without gravity is scenes/protocols/shake.xml.
namespace rwsim::trial {

/// When the closing phase ends.
enum class ClosingRule {
  /// The fingers are static (or at qClosed, or the closing time cap): the paper's rule.
  kRest,
  /// Also when the hand's total normal force on one object exceeds TrialProtocol::gripForce.
  kForceThreshold,
};

/// What a motion phase after closing does.
enum class PhaseKind {
  /// The hand's base moves `distance` straight up (world z) on a ramp (speed, acceleration).
  kLift,
  /// The hand oscillates along or about `axis`: offset A (1 - cos(2 pi f t)) for `cycles`
  /// periods (it starts and ends at rest where it started; peak acceleration A (2 pi f)^2).
  kShake,
  /// The hand's base moves `distance` along `axis` on a ramp (speed, acceleration).
  kPull,
};

/// The frame a phase's axis is given in.
enum class AxisFrame {
  /// The world frame.
  kWorld,
  /// The hand's TCP frame at the start of the phase (z: approach for every project hand).
  kTcp,
  /// The hand's parallel-jaw frame at the start of the phase (GraspTrialSetup::X_tcp_jaw: z the
  /// approach, x the closing axis, whatever the TCP's axes; a rotation turns about its origin,
  /// the centre between the pads).
  kJaw,
};

/// How a trial judges the grasp after the phases.
enum class SuccessRule {
  /// Held when some hand body touches the object (the paper's rule); stable or slipped by the
  /// object's drift in the hand.
  kHandContact,
  /// Held when the object touches at least two distinct finger links (hand bodies other than the
  /// base; ACRONYM's "object between the fingers"); stable or slipped by drift.
  kTwoFingers,
};

/// One motion phase after closing. Lengths in m, angles in rad, times in s.
struct ProtocolPhase {
  /// What the phase does.
  PhaseKind kind = PhaseKind::kLift;
  /// kPull, kShake: the frame of `axis`.
  AxisFrame frame = AxisFrame::kWorld;
  /// kPull: the direction; kShake: the axis of the motion (unit length; kLift: world z).
  rw::math::Vector3D axis = rw::math::Vector3D::UnitZ();
  /// kLift, kPull: how far, m.
  double distance = 0.10;
  /// kLift, kPull: ramp top speed, m/s.
  double speed = 0.5;
  /// kLift, kPull: ramp acceleration, m/s^2.
  double acceleration = 1.0;
  /// kShake: true to turn about `axis` through the TCP origin (amplitude in rad), false to move
  /// along it (amplitude in m).
  bool rotation = false;
  /// kShake: amplitude A (half the stroke), m or rad.
  double amplitude = 0.0;
  /// kShake: frequency f, Hz.
  double frequency = 1.0;
  /// kShake: periods, a whole or half number (after a half the hand stops at the far end, 2 A
  /// away).
  double cycles = 1.0;
  /// Time the hand stands still after the phase, s.
  double settle = 0.2;

  /// Field-wise equality.
  friend bool operator==(const ProtocolPhase&, const ProtocolPhase&) = default;
};

/// A trial protocol: gravity, the closing rule, the motion phases after closing and the success
/// rule. Default-constructed it is the paper's lift (TrialProtocol::lift()).
struct TrialProtocol {
  /// The protocol's name (run.csv records it; "lift" for the default).
  std::string name = "lift";
  /// False: the world has no gravity for the whole trial (the object floats where it is).
  bool gravity = true;
  /// When closing ends.
  ClosingRule closing = ClosingRule::kRest;
  /// kForceThreshold: the total normal force of the hand on one object that ends closing, N.
  double gripForce = 0.0;
  /// The fastest a prismatic finger joint closes, m/s (the controller's command is clamped to
  /// it for the whole trial); 0: no cap (the paper's PD closing at the hand's force limit).
  double closingSpeed = 0.0;
  /// The same for revolute finger joints, rad/s; 0: no cap.
  double closingAngularSpeed = 0.0;
  /// The motion after closing, in order (the paper: one lift of 10 cm at 0.5 m/s, 1 m/s^2, then
  /// 0.2 s standing still).
  std::vector<ProtocolPhase> phases = {ProtocolPhase{}};
  /// How the grasp is judged.
  SuccessRule success = SuccessRule::kHandContact;

  /// The paper's protocol: gravity, closing until rest, one lift, held by hand contact.
  static TrialProtocol lift() { return TrialProtocol{}; }
  /// True when this is the paper's protocol in every field but the name (a run records nothing
  /// for it: its files stay as before protocols existed).
  bool isLift() const;
  /// True when a phase gives its axis in the hand's jaw frame (AxisFrame::kJaw): the hand must
  /// declare one (GraspTrialSetup::X_tcp_jaw).
  bool usesJawFrame() const;
  /// @throws std::invalid_argument when the protocol uses the jaw frame and the hand has none:
  /// "the protocol "P" gives an axis in the jaw frame, but `hand` declares no jaw frame (...):
  /// give ...", `hand` naming it ("hand 'Gripper'", "the hand of FILE", "device D"), the rest
  /// saying what to give instead.
  void requireJawFrame(bool handHasJawFrame, const std::string& hand) const;
  /// Field-wise equality.
  friend bool operator==(const TrialProtocol&, const TrialProtocol&) = default;
};

/// @throws std::invalid_argument naming the field unless every number is finite and in range
/// (distances, speeds, accelerations, frequencies, amplitudes > 0; settle, gripForce and the
/// closing speeds >= 0; cycles a positive multiple of 0.5; a non-zero axis).
void checkProtocol(const TrialProtocol& protocol);

/// One line that tells protocols apart (every value in shortest exact form, SI units), e.g.
/// "gravity on; close until rest; lift 0.1 m at 0.5 m/s 1 m/s^2, settle 0.2 s; held by hand
/// contact". The name is not part of it.
std::string describe(const TrialProtocol& protocol);

/// Simulated time the phases after closing take, s: each phase's motion (a ramp's time, a
/// shake's cycles / frequency) and its settle.
double phasesDuration(const TrialProtocol& protocol);

/// 16 hex digits: FNV-1a of describe(protocol) (run.csv's protocol_hash).
std::string protocolHash(const TrialProtocol& protocol);

/// Reads a protocol from XML text (schema xml/protocol.xsd); `file` names it in messages.
/// @throws rw::common::LoadError with every problem as `file:line:column: error: ...`
/// (malformed XML, wrong root, unknown element or attribute, a value out of range).
TrialProtocol parseTrialProtocol(std::string_view xml, const std::filesystem::path& file);

/// Reads a protocol file. @throws rw::common::LoadError as parseTrialProtocol, or naming the
/// file when it cannot be read.
TrialProtocol loadTrialProtocol(const std::filesystem::path& file);

/// The text of xml/protocol.xsd, which parseTrialProtocol validates against.
std::string_view trialProtocolSchema();

}  // namespace rwsim::trial
