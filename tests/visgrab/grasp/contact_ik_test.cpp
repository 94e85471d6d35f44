// The contact IK: contacts made by forward kinematics from a known hand pose and q (through
// rw::kinematics), shuffled, solved; unreachable contacts; determinism across threads.
#include "visgrab/grasp/contact_ik.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <future>
#include <numbers>
#include <random>

#include "grasp_test_support.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rw/models/parallel_kinematics.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::grasp::ContactIkResult;
using visgrab::grasp::DesiredContact;
using visgrab::grasp::HandGraspSetup;
using visgrab::grasp::solveContactIk;
using visgrab::test::grasp::makeQ;
using visgrab::test::grasp::pg70;
using visgrab::test::grasp::sdh;

constexpr double kPi = std::numbers::pi;

// Pad point and push direction of a fingertip frame, as the description defines them.
struct Pad {
  const char* frame;
  Vector3D point;
  Vector3D normal;
};

const Pad kSdhPads[] = {{"SchunkHand.f1.TCP", {0, 0, 0.0049}, {0, 0, 1}},
                        {"SchunkHand.f2.TCP", {0, 0, 0.0049}, {0, 0, 1}},
                        {"SchunkHand.f3.TCP", {0, 0, 0.0049}, {0, 0, 1}}};

// Contacts of the given pads with the hand's base at X_W_base and configuration q.
std::vector<DesiredContact> contactsByFk(const HandGraspSetup& s, const Transform3D& X_W_base,
                                         const Q& q, const std::vector<Pad>& pads) {
  const auto& wc = s.workcell();
  auto state = wc.defaultState();
  wc.frames().frame(s.placementFrame()).setMovableTransform(state, X_W_base);  // parent: WORLD
  s.device().setQ(q, state);
  std::vector<DesiredContact> out;
  for (const Pad& pad : pads) {
    const auto id = wc.findFrame(pad.frame);
    EXPECT_TRUE(id.valid()) << pad.frame;
    const Transform3D X = rw::kinematics::worldTransform(wc.frames(), state, id);
    out.push_back({X * pad.point, X.linear() * pad.normal});
  }
  return out;
}

// Largest distance from each contact to the nearest pad of the solution.
double deviation(const HandGraspSetup& s, const ContactIkResult& r,
                 const std::vector<DesiredContact>& contacts, const std::vector<Pad>& pads) {
  const auto tips = contactsByFk(s, r.X_W_base, r.qContact, pads);
  double worst = 0.0;
  for (const auto& c : contacts) {
    double nearest = 1e9;
    for (const auto& t : tips) nearest = std::min(nearest, (t.position - c.position).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

Transform3D pose(double r, double p, double y, double px, double py, double pz) {
  return rw::math::rpyTransform(Vector3D(r, p, y), Vector3D(px, py, pz));
}

struct Case {
  Transform3D X_W_base;
  Q q;
};

TEST(ContactIk, SdhThreeFingersShuffled) {
  const Case cases[] = {
      {pose(0, kPi, 0, 0.0, 0.0, 0.3), makeQ({0.3, 0.4, 0.0, 0.3, 0.4, 0.3, 0.4})},
      {pose(0.4, kPi - 0.2, 0.1, 0.05, -0.02, 0.25), makeQ({0.1, 0.6, 0.5, 0.2, 0.3, 0.4, 0.2})},
      {pose(-0.3, 0.2, 1.0, -0.1, 0.1, 0.1), makeQ({0.5, 0.2, 1.0, 0.4, 0.1, 0.3, 0.5})},
      {pose(1.2, 0.5, -2.0, 0.2, 0.0, 0.4), makeQ({-0.2, 0.8, 0.2, 0.0, 0.7, -0.1, 0.6})},
  };
  const std::vector<Pad> pads(std::begin(kSdhPads), std::end(kSdhPads));
  std::mt19937 rng(7);
  for (const Case& c : cases) {
    auto contacts = contactsByFk(sdh(), c.X_W_base, c.q, pads);
    std::shuffle(contacts.begin(), contacts.end(), rng);
    const Vector3D approach = c.X_W_base.linear().col(2);
    const auto r = solveContactIk(sdh(), contacts, approach);
    EXPECT_TRUE(r.valid) << r.reason;
    EXPECT_LT(deviation(sdh(), r, contacts, pads), 0.01);
    EXPECT_LT(r.positionError, 0.002);
    EXPECT_TRUE(r.X_W_tcp.isApprox(r.X_W_base * sdh().X_base_tcp()));
    // Back-off: fingertips short of the contacts, fingers closing past them.
    ContactIkResult opened = r;
    opened.qContact = r.qOpen;
    EXPECT_GT(deviation(sdh(), opened, contacts, pads), 0.003);
    EXPECT_VECTOR_NEAR(r.qClosed - r.qOpen, sdh().closeOffset(), 1e-12);
    EXPECT_VECTOR_NEAR(r.tauMax, sdh().tauRule().evaluate(r.qOpen), 1e-15);
  }
}

TEST(ContactIk, SdhTwoFingers) {
  const Case cases[] = {
      {pose(0, kPi, 0, 0.0, 0.0, 0.25), makeQ({-1.571, -1.571, 1.571, 0.3, 0.4, 0.3, 0.4})},
      {pose(0.3, kPi - 0.3, 0.7, 0.1, 0.05, 0.2),
       makeQ({-1.571, -1.571, 1.571, 0.1, 0.6, 0.4, 0.2})},
      {pose(-1.0, 0.4, 2.0, -0.1, 0.0, 0.1), makeQ({-1.571, -1.571, 1.571, -0.2, 0.9, 0.0, 0.5})},
  };
  const std::vector<Pad> pads{kSdhPads[1], kSdhPads[2]};
  for (const Case& c : cases) {
    for (const bool swap : {false, true}) {
      auto contacts = contactsByFk(sdh(), c.X_W_base, c.q, pads);
      if (swap) std::swap(contacts[0], contacts[1]);
      const auto r = solveContactIk(sdh(), contacts, c.X_W_base.linear().col(2));
      EXPECT_TRUE(r.valid) << r.reason;
      EXPECT_LT(deviation(sdh(), r, contacts, pads), 0.01);
      EXPECT_LT(r.positionError, 0.002);
      EXPECT_EQ(r.fingerOfContact.size(), 2u);
      EXPECT_EQ(r.qOpen.head<3>(), makeQ({-1.571, -1.571, 1.571}));  // thumb and spread kept
    }
  }
}

TEST(ContactIk, Pg70TwoJaws) {
  const Transform3D X = pose(0.2, kPi - 0.1, 0.5, 0.02, 0.03, 0.3);
  const std::vector<Pad> pads{{"PG70.TCPRight", {0, 0.035, -0.0095}, {0, 0, -1}},
                              {"PG70.TCPLeft", {0, 0.035, 0.0095}, {0, 0, 1}}};
  auto contacts = contactsByFk(pg70(), X, makeQ({0.02}), pads);
  std::swap(contacts[0], contacts[1]);
  const auto r = solveContactIk(pg70(), contacts, X.linear().col(2));
  EXPECT_TRUE(r.valid) << r.reason;
  EXPECT_LT(deviation(pg70(), r, contacts, pads), 0.002);
  EXPECT_NEAR(r.qOpen[0], r.qContact[0] + 0.01, 1e-4);  // each jaw backed off by 1 cm
}

// Every junction of a parallel hand closes at q (residual at rounding level).
void expectLoopsClosed(const HandGraspSetup& hand, const Q& q) {
  auto state = hand.workcell().defaultState();
  hand.device().setQ(q, state);
  for (std::size_t j = 0; j < hand.device().parallel()->junctions().size(); ++j) {
    EXPECT_LT(hand.device().parallel()->residual(j, state).position, 1e-9) << "junction " << j;
  }
}

// The project's 2F-85 is a parallel device: each finger a closed four-bar linkage, so its joint
// moves the pads through the closure solver. Two contacts 50 mm apart along the TCP's x axis,
// pushing towards each other: the solution puts the pads on them at the knuckle angle where the
// hand-worked opening gap(q) = 2 (0.004925 + 0.0376 cos q - 0.0430 sin q) m
// (robotiq2f85.wc.xml's header) is 50 mm. Backed off by 1 cm each with the base kept, the pads
// cannot reach both targets (they move on arcs: their height along the approach is
// 0.0376 sin q + 0.0430 cos q + const): qOpen is the least-squares compromise between the
// opening's error and the height's, worked here from the same hand-worked expressions.
TEST(ContactIk, Robotiq2F85ClosedLinkages) {
  const auto hand =
      visgrab::grasp::loadHandGraspSetup(visgrab::test::sourceDir() / "scenes/hands/robotiq2f85");
  ASSERT_NE(hand->device().parallel(), nullptr);
  // gap(q) = 2 (0.004925 + R cos(q + phi)), R cos phi = 0.0376, R sin phi = 0.0430.
  const double R = std::hypot(0.0376, 0.0430);
  const double phi = std::atan2(0.0430, 0.0376);
  const auto qForGap = [&](double gap) { return std::acos((gap / 2 - 0.004925) / R) - phi; };
  const Transform3D X_W_tcp = pose(0.3, kPi - 0.2, -0.4, 0.1, -0.05, 0.25);
  const Vector3D x = X_W_tcp.linear().col(0);
  const std::vector<DesiredContact> contacts{{X_W_tcp * Vector3D(0.025, 0, 0), -x},
                                             {X_W_tcp * Vector3D(-0.025, 0, 0), x}};
  const auto r = solveContactIk(*hand, contacts, X_W_tcp.linear().col(2));
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_NEAR(r.qContact[0], qForGap(0.050), 2e-3);
  const auto halfGap = [](double q) {
    return 0.004925 + 0.0376 * std::cos(q) - 0.0430 * std::sin(q);
  };
  const auto height = [](double q) { return 0.0376 * std::sin(q) + 0.0430 * std::cos(q); };
  const double q50 = qForGap(0.050);
  double bestOpen = 0.0;
  double bestCost = 1e9;
  for (double q = 0.0; q <= 0.8; q += 1e-5) {
    const double cost = std::pow(halfGap(q) - 0.035, 2) + std::pow(height(q) - height(q50), 2);
    if (cost < bestCost) {
      bestCost = cost;
      bestOpen = q;
    }
  }
  EXPECT_NEAR(r.qOpen[0], bestOpen, 1e-3);
  EXPECT_GT(r.qOpen[0], qForGap(0.070));  // opening less than 70 mm: the arc's price
  EXPECT_LT(r.positionError, 0.001);
  // The pads where the contacts are, whichever finger took which.
  const std::vector<Pad> pads{{"Robotiq2F85.RightPad", {0, 0, 0}, {0, 0, 1}},
                              {"Robotiq2F85.LeftPad", {0, 0, 0}, {0, 0, 1}}};
  EXPECT_LT(deviation(*hand, r, contacts, pads), 0.001);
  // The linkage closed at the solution: every junction's residual at rounding level.
  expectLoopsClosed(*hand, r.qContact);
}

// RobWork's own Robotiq model (RW_COMPAT_DATA, scenes/hands/robwork-robotiq): three DOF, the
// motor and each finger's inner link, two closed loops. Contacts 40 mm apart, their directions
// tilted 5 deg the same way about the TCP's y axis (a slightly slanted object): the pads reach
// them within 1 mm and the fingers turn with the directions (within 2 deg, where parallel pads
// would miss by 5: the solver weighs a direction 0.01 m per unit against the positions), and
// the loops stay closed.
TEST(ContactIk, RobWorksRobotiqThreeDofClosedLoops) {
  REQUIRE_COMPAT_DATA(data);  // the hand's workcell reads ${RW_COMPAT_DATA} itself
  static_cast<void>(data);
  const auto hand = visgrab::grasp::loadHandGraspSetup(visgrab::test::sourceDir() /
                                                       "scenes/hands/robwork-robotiq");
  ASSERT_EQ(hand->dof(), 3);
  const Transform3D X_W_tcp = pose(-0.2, kPi - 0.1, 0.7, -0.1, 0.05, 0.2);
  const rw::math::Rotation3D tilt(Eigen::AngleAxisd(5.0 * kPi / 180.0, Vector3D::UnitY()));
  const Vector3D x = X_W_tcp.linear() * (tilt * Vector3D::UnitX());
  const std::vector<DesiredContact> contacts{{X_W_tcp * Vector3D(0.020, 0, 0), -x},
                                             {X_W_tcp * Vector3D(-0.020, 0, 0), x}};
  const auto r = solveContactIk(*hand, contacts, X_W_tcp.linear().col(2));
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_LT(r.positionError, 0.001);
  EXPECT_LT(r.directionError, 2.0 * kPi / 180.0);
  const std::vector<Pad> pads{{"RobotiqFingerControl.RightMotorEnd", {0, 0, 0}, {0, 0, 1}},
                              {"RobotiqFingerControl.LeftMotorEnd", {0, 0, 0}, {0, 0, 1}}};
  EXPECT_LT(deviation(*hand, r, contacts, pads), 0.001);
  expectLoopsClosed(*hand, r.qContact);
}

TEST(ContactIk, ContactsTooFarApartAreInvalid) {
  std::vector<DesiredContact> three{
      {{0.2, 0, 0.05}, {-1, 0, 0}}, {{-0.2, 0.0, 0.05}, {1, 0, 0}}, {{0.0, 0.2, 0.05}, {0, -1, 0}}};
  const auto r3 = solveContactIk(sdh(), three, -Vector3D::UnitZ());
  EXPECT_FALSE(r3.valid);
  EXPECT_GT(r3.positionError, 0.01);
  EXPECT_NE(r3.reason.find("fingertip deviation"), std::string::npos) << r3.reason;

  std::vector<DesiredContact> two{{{0.2, 0, 0.05}, {-1, 0, 0}}, {{-0.2, 0, 0.05}, {1, 0, 0}}};
  visgrab::grasp::GraspRequest req;
  req.kind = visgrab::grasp::GraspKind::kContacts;
  req.contacts = two;
  req.id = "far";
  const auto g = visgrab::grasp::resolve(req, sdh());
  EXPECT_EQ(g.status, visgrab::grasp::ResolveStatus::kInvalidContacts) << g.message;
  EXPECT_NE(g.message.find("grasp \"far\""), std::string::npos) << g.message;
}

bool sameBytes(const ContactIkResult& a, const ContactIkResult& b) {
  const auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           std::memcmp(x.data(), y.data(), sizeof(double) * static_cast<std::size_t>(x.size())) ==
               0;
  };
  return same(a.X_W_tcp.matrix(), b.X_W_tcp.matrix()) && same(a.qOpen, b.qOpen) &&
         same(a.qClosed, b.qClosed) && same(a.tauMax, b.tauMax) && a.valid == b.valid &&
         a.fingerOfContact == b.fingerOfContact;
}

TEST(ContactIk, DeterministicAcrossThreads) {
  const std::vector<Pad> pads(std::begin(kSdhPads), std::end(kSdhPads));
  const Transform3D X = pose(0.4, kPi - 0.2, 0.1, 0.05, -0.02, 0.25);
  const auto contacts = contactsByFk(sdh(), X, makeQ({0.1, 0.6, 0.5, 0.2, 0.3, 0.4, 0.2}), pads);
  const Vector3D a = X.linear().col(2);
  const auto first = solveContactIk(sdh(), contacts, a);
  auto t1 = std::async(std::launch::async, [&] { return solveContactIk(sdh(), contacts, a); });
  auto t2 = std::async(std::launch::async, [&] { return solveContactIk(sdh(), contacts, a); });
  EXPECT_TRUE(sameBytes(t1.get(), first));
  EXPECT_TRUE(sameBytes(t2.get(), first));
}

// reopenContactIk solves only q_open again: for each back-off it gives the very doubles of a
// full refitContactIk from the same solution and base (the placement search relies on it).
TEST(ContactIk, ReopenEqualsRefitWithTheOtherBackoff) {
  const std::vector<Pad> pads(std::begin(kSdhPads), std::end(kSdhPads));
  const Transform3D X = pose(0.4, kPi - 0.2, 0.1, 0.05, -0.02, 0.25);
  const auto contacts = contactsByFk(sdh(), X, makeQ({0.1, 0.6, 0.5, 0.2, 0.3, 0.4, 0.2}), pads);
  const Vector3D a = X.linear().col(2);
  const auto solution = solveContactIk(sdh(), contacts, a);
  ASSERT_TRUE(solution.valid) << solution.reason;
  Transform3D moved = solution.X_W_base;
  moved.translation() -= 0.01 * a;  // the fingers must move to reach again
  const auto first = visgrab::grasp::refitContactIk(sdh(), contacts, a, solution, moved, 0.02);
  EXPECT_FALSE(first.qContact.isApprox(solution.qContact, 1e-6));
  for (const double backoff : {0.03, 0.05, 0.07}) {
    const auto refit = visgrab::grasp::refitContactIk(sdh(), contacts, a, solution, moved, backoff);
    const auto reopened = visgrab::grasp::reopenContactIk(sdh(), contacts, a, first, backoff);
    EXPECT_TRUE(sameBytes(reopened, refit)) << backoff;
    EXPECT_EQ(reopened.qContact, refit.qContact);
    EXPECT_EQ(reopened.positionError, refit.positionError);
    EXPECT_EQ(reopened.reason, refit.reason);
    EXPECT_FALSE(reopened.qOpen.isApprox(first.qOpen, 1e-6)) << backoff;  // opened further
  }
}

}  // namespace
