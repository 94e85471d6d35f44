#pragma once

#include <limits>
#include <memory>
#include <string>

#include "rw/math/types.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"

/// Dynamic workcells built in code for the simulator tests: a table, boxes, a two-jaw gripper
/// and a one-joint finger. Materials: "Table", "Object", "Finger" with mu Object-Table
/// `tableMu`, Finger-Object 0.6, Finger-Finger 0.8, Finger-Table 0.4.
namespace visgrab::test::sim {

/// Standard gravity used by the scenes, m/s^2.
inline constexpr double kG = 9.81;

/// Incremental builder: add frames and geometry, then build() the DynamicWorkCell and add bodies.
class SceneBuilder {
 public:
  /// An empty workcell named `name`, materials declared, friction Object-Table `tableMu`.
  explicit SceneBuilder(std::string name, double tableMu = 0.4);

  /// A fixed frame with a box (full sizes) centred on it; becomes a FixedBody "name".
  void addTable(const std::string& name, const rw::math::Transform3D& X_W,
                const rw::math::Vector3D& size);
  /// A Movable frame at X_W with a box centred on it; becomes a RigidBody of `mass` (uniform
  /// box inertia) with material "Object".
  void addBox(const std::string& name, const rw::math::Transform3D& X_W,
              const rw::math::Vector3D& size, double mass);
  /// A Movable frame at X_W with `geometry` centred on it; becomes a RigidBody of `mass`, its
  /// centre of mass at `cog` (in the frame) and `inertia` (about it), with material "Object".
  void addBody(const std::string& name, const rw::math::Transform3D& X_W,
               std::shared_ptr<const rw::geometry::Geometry> geometry, double mass,
               const Eigen::Matrix3d& inertia,
               const rw::math::Vector3D& cog = rw::math::Vector3D::Zero());
  /// A two-jaw gripper "Gripper": kinematic base at `X_W`, prismatic jaws "Gripper.Left" at
  /// y = -gap and "Gripper.Right" at y = +gap moving towards y = 0 (q > 0 closes), jaw plates of
  /// thickness 0.02 (faces at |y| = gap - 0.01), 0.1 x 0.1, each 0.1 kg; two independent DOF,
  /// force limit `force` each, velocity limit `velocity` each (m/s; default none); PD controller
  /// "GraspController" (P 10, D 0.003 as RobWork's).
  void addGripper(const rw::math::Transform3D& X_W, double gap, double force,
                  double velocity = std::numeric_limits<double>::infinity());
  /// A one-joint finger "Finger": fixed base at X_W, revolute joint "Finger.Joint" about world
  /// +y through X_W's origin, a rod along +x ending in a sphere (r 0.01) whose lowest point is
  /// at (lever, 0, 0), level with the axis; positive q turns the tip down. Link mass 0.1 kg,
  /// torque limit `torque`; joint limits +-1 rad, or none when `limited` is false.
  void addFinger(const rw::math::Transform3D& X_W, double lever, double torque,
                 bool limited = true);

  /// Builds the DynamicWorkCell with gravity (0, 0, -gravity) and all the bodies and devices.
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> build(double gravity = kG);

 private:
  struct Pending;
  std::unique_ptr<rw::models::WorkCell> wc_;
  std::shared_ptr<Pending> pending_;
  double tableMu_;
};

/// Inertia of a solid box about its centre.
Eigen::Matrix3d boxInertia(double mass, const rw::math::Vector3D& size);

/// A slope without a tilted table: a box "Block" (0.1 x 0.1 x 0.05 m, 0.5 kg) resting at
/// x = -0.5 on a level table "Table" (2 x 1 m, top at z = 0, mu Object-Table `mu`) under
/// gravity kG turned by `angle` about world +y, so that downhill is world +x. Every engine then
/// meets a face-up table (MuJoCo's export uses its top plane; see mjcf_export.hpp).
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> boxUnderTiltedGravity(double angle, double mu);

/// Weighing scene: a box "Box" (0.1 m cube, `boxMass`, a rigid body of no device) resting on a
/// table "Table" (top at z = 0), and, clear of both, the two-jaw gripper (addGripper: jaws of
/// 0.1 kg, gap 0.05) at (0.5, 0, 0.5) with force limit `jawForce`: driven at their limit the
/// jaws accelerate at a rate set by their mass. (No other fixed box: MuJoCo's export gives a
/// fixed face-up box an unbounded top plane.)
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> weighingScene(double boxMass, double jawForce);

}  // namespace visgrab::test::sim
