// RobWorkSim's <Constraint> in the simulator: each type becomes its ODE joint. Checked against
// analytic truth: a compound pendulum's period and energy (Revolute), free fall along a slider
// and a stop (Prismatic), a weld under gravity (Fixed), and the anchor of a ball and a universal
// joint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::BodyId;
using rwsim::simulator::Simulator;
using rwsim::simulator::SimulatorOptions;
using rwsim::simulator::StepStatus;

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;

// The bob: a 1 kg box 0.05 x 0.05 x 0.2 m (centre of mass at its frame origin), hung d = 0.3 m
// below the support's origin at (0, 0, 1). Its inertia about y through the centre is
// m (a^2 + c^2) / 12 with a = 0.05, c = 0.2.
constexpr double kMass = 1.0;
constexpr double kD = 0.3;
constexpr double kIyy = kMass * (0.05 * 0.05 + 0.2 * 0.2) / 12.0;
constexpr double kIxx = kIyy;
constexpr double kIzz = kMass * (0.05 * 0.05 + 0.05 * 0.05) / 12.0;
const Vector3D kPivot(0, 0, 1);

// The support overlaps the bob in the "Overlap" variant (to show that a constrained pair makes
// no contacts).
std::string workCell(double bobZ, double supportSize, bool kinematicSupport) {
  const std::string s = std::to_string(supportSize);
  return std::string(R"(<WorkCell name="Constraints">
  <Frame name="Support" refframe="WORLD")") +
         (kinematicSupport ? " type=\"Movable\"" : "") + R"(>
    <RPY>0 0 0</RPY><Pos>0 0 1</Pos>
    <Drawable name="S"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x=")" +
         s + "\" y=\"" + s + "\" z=\"" + s + R"("/></Drawable>
  </Frame>
  <Frame name="Bob" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 )" +
         std::to_string(bobZ) + R"(</Pos>
    <Drawable name="B"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.05" y="0.05" z="0.2"/></Drawable>
  </Frame>
</WorkCell>
)";
}

// A dynamic workcell with the bob and one constraint (`constraint` is the whole element).
std::string dynamics(const std::string& constraint, bool kinematicSupport) {
  const std::string materials =
      (visgrab::test::sourceDir() / "scenes/materials.xml").generic_string();
  return R"(<DynamicWorkcell workcell="scene.wc.xml">
  <Gravity>0 0 -9.81</Gravity>
  <Include file=")" +
         materials + R"("/>
  )" +
         std::string(kinematicSupport
                         ? "<KinematicBody "
                           "frame=\"Support\"><MaterialID>Object</MaterialID></KinematicBody>"
                         : "<FixedBody frame=\"Support\"/>") +
         R"(
  <RigidBody frame="Bob">
    <Integrator>Euler</Integrator>
    <Mass>1</Mass><COG>0 0 0</COG>
    <Inertia>)" +
         std::to_string(kIxx) + " " + std::to_string(kIyy) + " " + std::to_string(kIzz) +
         R"(</Inertia>
  </RigidBody>
)" + constraint +
         "</DynamicWorkcell>\n";
}

class Constraints : public ::testing::Test {
 protected:
  void load(const std::string& constraint, double bobZ = 1.0 - kD, double supportSize = 0.02,
            bool kinematicSupport = false) {
    visgrab::test::writeFile(tmp_.path() / "scene.wc.xml",
                             workCell(bobZ, supportSize, kinematicSupport));
    visgrab::test::writeFile(tmp_.path() / "scene.dwc.xml", dynamics(constraint, kinematicSupport));
    dwc_ = rwsim::loaders::loadDynamicWorkCell(tmp_.path() / "scene.dwc.xml");
    bob_ = dwc_->findBody("Bob");
  }

  // A simulator with the bob placed at X_W_bob.
  std::unique_ptr<Simulator> start(const Transform3D& X_W_bob, double dt) {
    SimulatorOptions options;
    options.timeStep = dt;
    auto sim = std::make_unique<Simulator>(*dwc_, options);
    rw::kinematics::State state = dwc_->workcell().defaultState();
    dwc_->workcell().frames().frame(dwc_->body(bob_).frame).setMovableTransform(state, X_W_bob);
    sim->reset(state);
    return sim;
  }

  visgrab::test::TempDir tmp_;
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc_;
  BodyId bob_;
};

// The bob turned by theta about the pivot's y axis (the pendulum's hinge).
Transform3D pendulumPose(double theta) {
  Transform3D X = Transform3D::Identity();
  X.linear() = Eigen::AngleAxisd(theta, Vector3D::UnitY()).toRotationMatrix();
  X.translation() = kPivot + X.linear() * Vector3D(0, 0, -kD);
  return X;
}

// The pendulum's angle about y from the bob's pose (0 hanging straight down).
double pendulumAngle(const Transform3D& X) {
  const Vector3D r = X.translation() - kPivot;
  return std::atan2(-r.x(), -r.z());
}

// A hinge about world y through the pivot: the constraint frame's z axis is the hinge axis, and
// RPY (radians in a .dwc.xml) 0 0 -pi/2 turns z onto y.
std::string revolute(const std::string& parent, const std::string& child, const char* pos) {
  return "<Constraint name=\"Hinge\" type=\"Revolute\" parent=\"" + parent + "\" child=\"" + child +
         "\">\n  <Transform3D><Pos>" + pos +
         "</Pos><RPY>0 0 -1.5707963267948966</RPY></Transform3D>\n</Constraint>\n";
}

// The times at which the angle crosses zero going up, linearly interpolated between steps.
std::vector<double> upwardCrossings(Simulator& sim, BodyId bob, double duration) {
  std::vector<double> crossings;
  double last = pendulumAngle(sim.bodyPose(bob));
  while (sim.time() < duration) {
    const double t0 = sim.time();
    EXPECT_EQ(sim.step(), StepStatus::kOk) << sim.failureDetail();
    const double now = pendulumAngle(sim.bodyPose(bob));
    if (last < 0.0 && now >= 0.0) crossings.push_back(t0 + (sim.time() - t0) * last / (last - now));
    last = now;
  }
  return crossings;
}

// The small-angle period of the compound pendulum: T0 = 2 pi sqrt(I_pivot / (m g d)),
// I_pivot = I_cog + m d^2 (parallel axes). At amplitude theta0 the true period is
// T0 (1 + theta0^2 / 16 + ...): 1.6e-4 relative at 0.05 rad. The step (dt = 1 ms, omega dt =
// 0.0056) changes the period of the semi-implicit Euler step by (omega dt)^2 / 24 ~ 1e-6; the
// zero crossings are interpolated linearly, an error of order omega^2 theta0 dt^2 per crossing,
// ~1e-7 s. Allowed: 0.1 % of T0 (0.0011 s), six times the amplitude term, for the joint's
// constraint softness (world CFM 1e-7).
constexpr double kPeriodTolerance = 1e-3;

double expectedPeriod() {
  const double iPivot = kIyy + kMass * kD * kD;
  return 2.0 * kPi * std::sqrt(iPivot / (kMass * kG * kD));
}

double measuredPeriod(Simulator& sim, BodyId bob) {
  const double t0 = expectedPeriod();
  const std::vector<double> c = upwardCrossings(sim, bob, 5.5 * t0);
  EXPECT_GE(c.size(), 5u);
  if (c.size() < 2) return 0.0;
  return (c.back() - c.front()) / static_cast<double>(c.size() - 1);
}

TEST_F(Constraints, ARevolutePendulumSwingsWithTheCompoundPendulumPeriod) {
  load(revolute("Support", "Bob", "0 0 0"));
  auto sim = start(pendulumPose(0.05), 0.001);
  const double period = measuredPeriod(*sim, bob_);
  const double expected = expectedPeriod();
  RecordProperty("period_s", std::to_string(period));
  RecordProperty("expected_s", std::to_string(expected));
  std::printf("pendulum period %.6f s, expected %.6f s, relative error %.2e\n", period, expected,
              std::abs(period - expected) / expected);
  EXPECT_NEAR(period, expected, kPeriodTolerance * expected);
}

TEST_F(Constraints, ARevoluteWithTheFixedBodyAsChildSwingsTheSame) {
  // The hinge hangs on the bob (parent) and holds the support (child): ODE's second body is then
  // the static world. The constraint frame is given in the bob's frame: the pivot is d above it.
  load(revolute("Bob", "Support", "0 0 0.3"));
  auto sim = start(pendulumPose(0.05), 0.001);
  const double period = measuredPeriod(*sim, bob_);
  std::printf("reversed pendulum period %.6f s\n", period);
  EXPECT_NEAR(period, expectedPeriod(), kPeriodTolerance * expectedPeriod());
}

TEST_F(Constraints, ALargeSwingConservesEnergy) {
  // Released at 1.2 rad from rest: E = m g d (1 - cos 1.2) = 1.9 J above the lowest point.
  // The semi-implicit Euler step conserves a nearby energy (its error oscillates with amplitude
  // of order omega dt E ~ 0.6 % at dt = 1 ms) and the constraint rows damp it slightly; allowed
  // 2 % over 3 s (about 2.7 periods), and the pivot may open by 1 mm.
  load(revolute("Support", "Bob", "0 0 0"));
  const double theta0 = 1.2;
  auto sim = start(pendulumPose(theta0), 0.001);
  const double iPivot = kIyy + kMass * kD * kD;
  const double e0 = kMass * kG * kD * (1.0 - std::cos(theta0));
  double worst = 0.0;
  double pivotGap = 0.0;
  while (sim->time() < 3.0) {
    ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
    const Transform3D X = sim->bodyPose(bob_);
    const double omega = sim->bodyAngularVelocity(bob_).y();
    const double height = X.translation().z() - (kPivot.z() - kD);
    const double e = 0.5 * iPivot * omega * omega + kMass * kG * height;
    worst = std::max(worst, std::abs(e - e0) / e0);
    pivotGap = std::max(pivotGap, (X * Vector3D(0, 0, kD) - kPivot).norm());
  }
  std::printf("energy error at most %.3f %%, pivot opened at most %.2e m\n", 100.0 * worst,
              pivotGap);
  EXPECT_LT(worst, 0.02);
  EXPECT_LT(pivotGap, 1e-3);
}

TEST_F(Constraints, APrismaticBodyFallsWithGAndStopsAtItsLimit) {
  // A vertical slider (the constraint frame's z axis is world z); the limit lets the bob sink
  // 0.1 m below where it starts. Semi-implicit Euler gives z_n = z0 - g dt^2 n (n + 1) / 2 =
  // z0 - g t^2 / 2 - g t dt / 2: within g t dt / 2 of the free fall.
  load(R"(<Constraint name="Slide" type="prismatic" parent="Support" child="Bob">
  <Limits><Limit low="-0.1" high="0.5"/></Limits>
</Constraint>
)");
  const double dt = 0.001;
  const Transform3D X0 = pendulumPose(0.0);
  auto sim = start(X0, dt);
  const double z0 = X0.translation().z();
  double worstFall = 0.0;
  while (sim->time() < 0.13) {  // the stop is reached at sqrt(2 * 0.1 / g) = 0.143 s
    ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
    const double t = sim->time();
    const double fall = z0 - sim->bodyPose(bob_).translation().z();
    const double error = std::abs(fall - 0.5 * kG * t * t);
    worstFall = std::max(worstFall, error);
    EXPECT_LE(error, 0.5 * kG * t * dt + 1e-6) << "at t = " << t;
  }
  std::printf("free fall: worst deviation from g t^2 / 2 is %.2e m\n", worstFall);
  double lowest = z0;
  double sideways = 0.0;
  while (sim->time() < 1.0) {
    ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
    const Vector3D p = sim->bodyPose(bob_).translation();
    lowest = std::min(lowest, p.z());
    sideways = std::max(sideways, std::hypot(p.x(), p.y()));
  }
  const double rest = sim->bodyPose(bob_).translation().z();
  std::printf("stop: rests at %.6f m (limit %.6f m), lowest %.6f m\n", rest, z0 - 0.1, lowest);
  // The stop is a constraint row with ERP 0.2 and CFM 1e-7 (the world's): the 1 kg bob hits it
  // at 1.4 m/s, overshoots by about v dt (1.4 mm) and is pushed back within a few steps.
  EXPECT_NEAR(rest, z0 - 0.1, 1e-4);
  EXPECT_GT(lowest, z0 - 0.1 - 3e-3);
  EXPECT_LT(sideways, 1e-9);
}

TEST_F(Constraints, AWeldedBodyStaysPutUnderGravity) {
  // The support (0.25 m cube) overlaps the bob: a constrained pair makes no contacts, or the
  // overlap would push them apart. With CFM and ERP a constraint row is a spring of stiffness
  // ERP / (dt CFM) (ODE's manual): under the bob's weight the weld sags m g dt CFM / ERP =
  // 9.81 * 0.005 * 1e-7 / 0.2 = 2.5e-8 m. Allowed drift over 2 s: 1e-6 m.
  load(R"(<Constraint name="Weld" type="Fixed" parent="Support" child="Bob"/>
)",
       1.0 - kD, 0.25);
  const Transform3D X0 = pendulumPose(0.0);
  auto sim = start(X0, 0.005);
  double drift = 0.0;
  double turn = 0.0;
  while (sim->time() < 2.0) {
    ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
    const Transform3D X = sim->bodyPose(bob_);
    drift = std::max(drift, (X.translation() - X0.translation()).norm());
    turn = std::max(turn, Eigen::AngleAxisd(X.linear() * X0.linear().transpose()).angle());
  }
  std::printf("weld: drift %.2e m, rotation %.2e rad over 2 s\n", drift, turn);
  EXPECT_LT(drift, 1e-6);
  EXPECT_LT(turn, 1e-6);
  EXPECT_TRUE(sim->contacts().empty());
  EXPECT_EQ(sim->lastStepRows(), 6u);
}

TEST_F(Constraints, ABodyWeldedToAKinematicBodyFollowsIt) {
  // The support is kinematic, moved at 0.2 m/s along x; the weld carries the bob along (ODE
  // treats the kinematic body as infinitely heavy). After 1 s both moved 0.2 m; the bob keeps
  // its offset to within the weld's sag (2.5e-8 m, see the test above) and the step's
  // position error.
  load(R"(<Constraint name="Weld" type="Fixed" parent="Support" child="Bob"/>
)",
       1.0 - kD, 0.02, true);
  const BodyId support = dwc_->findBody("Support");
  const Transform3D X0 = pendulumPose(0.0);
  auto sim = start(X0, 0.005);
  sim->setKinematicVelocity(support, Vector3D(0.2, 0, 0), Vector3D::Zero());
  double offsetError = 0.0;
  while (sim->time() < 1.0 - 1e-9) {
    ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
    const Vector3D offset =
        sim->bodyPose(bob_).translation() - sim->bodyPose(support).translation();
    offsetError = std::max(offsetError, (offset - Vector3D(0, 0, -kD)).norm());
  }
  const double moved = sim->bodyPose(bob_).translation().x() - X0.translation().x();
  std::printf("weld to a kinematic body: bob moved %.6f m, offset error at most %.2e m\n", moved,
              offsetError);
  EXPECT_NEAR(sim->bodyPose(support).translation().x(), 0.2, 1e-9);
  EXPECT_NEAR(moved, 0.2, 1e-5);
  EXPECT_LT(offsetError, 1e-5);
}

// Let go from X0: the anchor (the pivot, d above the bob's centre) must stay at the pivot. For a
// universal joint, axis 1 (the constraint frame's x: world x, on the support) and axis 2 (its y
// at the start, carried by the bob) must stay perpendicular.
struct Swing {
  double anchorError = 0.0;
  double axisError = 0.0;  // |cos| of the angle between the two axes
};

Swing swing(Simulator& sim, BodyId bob, const Transform3D& X0) {
  Swing s;
  while (sim.time() < 2.0) {
    EXPECT_EQ(sim.step(), StepStatus::kOk) << sim.failureDetail();
    const Transform3D X = sim.bodyPose(bob);
    s.anchorError = std::max(s.anchorError, (X * Vector3D(0, 0, kD) - kPivot).norm());
    const Vector3D axis2 = X.linear() * X0.linear().transpose() * Vector3D::UnitY();
    s.axisError = std::max(s.axisError, std::abs(Vector3D::UnitX().dot(axis2)));
  }
  return s;
}

// The bob turned about the pivot by `R`.
Transform3D turned(const Eigen::Matrix3d& R) {
  Transform3D X = Transform3D::Identity();
  X.linear() = R;
  X.translation() = kPivot + R * Vector3D(0, 0, -kD);
  return X;
}

TEST_F(Constraints, ASphericalJointHoldsItsAnchor) {
  load(R"(<Constraint name="Ball" type="Spherical" parent="Support" child="Bob"/>
)");
  const Transform3D X0 =
      turned(Eigen::AngleAxisd(0.6, Vector3D(1, 1, 0).normalized()).toRotationMatrix());
  auto sim = start(X0, 0.002);
  const Swing s = swing(*sim, bob_, X0);
  std::printf("ball: anchor moved at most %.2e m\n", s.anchorError);
  EXPECT_LT(s.anchorError, 1e-3);
  EXPECT_EQ(sim->lastStepRows(), 3u);
}

TEST_F(Constraints, AUniversalJointHoldsItsAnchorAndKeepsItsAxesPerpendicular) {
  load(R"(<Constraint name="Cross" type="Universal" parent="Support" child="Bob"/>
)");
  // Turned about both joint axes, so that gravity swings it about both.
  const Transform3D X0 =
      turned((Eigen::AngleAxisd(0.4, Vector3D::UnitX()) * Eigen::AngleAxisd(0.3, Vector3D::UnitY()))
                 .toRotationMatrix());
  auto sim = start(X0, 0.002);
  const Swing s = swing(*sim, bob_, X0);
  std::printf("universal: anchor moved at most %.2e m, axes off perpendicular by %.2e\n",
              s.anchorError, s.axisError);
  EXPECT_LT(s.anchorError, 1e-3);
  EXPECT_LT(s.axisError, 1e-3);
  EXPECT_EQ(sim->lastStepRows(), 4u);
}

TEST_F(Constraints, ARevoluteLimitStopsTheSwing) {
  // The limit is on the child's turn relative to the parent about the constraint frame's z
  // (world y), measured from the start: released at -0.3 rad, the pendulum would swing to +0.3;
  // the stop 0.1 rad past the start holds it at -0.2.
  load(R"(<Constraint name="Hinge" type="Revolute" parent="Support" child="Bob">
  <Transform3D><RPY>0 0 -1.5707963267948966</RPY></Transform3D>
  <Limits><Limit high="0.1"/></Limits>
</Constraint>
)");
  auto sim = start(pendulumPose(-0.3), 0.001);
  double highest = -1.0;
  while (sim->time() < 1.0) {
    ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
    highest = std::max(highest, pendulumAngle(sim->bodyPose(bob_)));
  }
  std::printf("hinge stop at -0.2 rad: highest angle %.5f rad\n", highest);
  // Reached at about 0.9 rad/s: overshoot about omega dt, corrected within a few steps.
  EXPECT_GT(highest, -0.2 - 1e-3);
  EXPECT_LT(highest, -0.2 + 3e-3);
}

// Every type builds its ODE joint and runs from a tilted start; the rows of the first step are
// the joint's (no stop is reached).
struct TypeCase {
  const char* type;
  std::size_t rows;
};

class ConstraintTypes : public Constraints, public ::testing::WithParamInterface<TypeCase> {};

TEST_P(ConstraintTypes, RunsWithItsRows) {
  load(std::string("<Constraint name=\"C\" type=\"") + GetParam().type +
       "\" parent=\"Support\" child=\"Bob\"/>\n");
  auto sim = start(pendulumPose(0.2), 0.002);
  ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
  EXPECT_EQ(sim->lastStepRows(), GetParam().rows);
  while (sim->time() < 0.5) ASSERT_EQ(sim->step(), StepStatus::kOk) << sim->failureDetail();
  const Vector3D p = sim->bodyPose(bob_).translation();
  EXPECT_TRUE(p.allFinite());
}

INSTANTIATE_TEST_SUITE_P(All, ConstraintTypes,
                         ::testing::Values(TypeCase{"Fixed", 6}, TypeCase{"Prismatic", 5},
                                           TypeCase{"Revolute", 5}, TypeCase{"Universal", 4},
                                           TypeCase{"Spherical", 3}, TypeCase{"Piston", 4},
                                           TypeCase{"PrismaticRotoid", 4},
                                           TypeCase{"PrismaticUniversal", 3}, TypeCase{"Free", 0}),
                         [](const auto& c) { return std::string(c.param.type); });

}  // namespace
