// The contact IK: contacts made by forward kinematics from a known hand pose and q (through
// rw::kinematics), shuffled, solved; unreachable contacts; determinism across threads.
#include "visgrab/grasp/contact_ik.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <future>
#include <numbers>
#include <random>

#include "grasp_test_support.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
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
  wc.frames().frame(s.device().base()).setMovableTransform(state, X_W_base);  // parent: WORLD
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
