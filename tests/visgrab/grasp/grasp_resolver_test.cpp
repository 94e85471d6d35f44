// resolve(): raw, pre-shape and pose + q requests, and input errors naming file:line and id.
#include "visgrab/grasp/grasp_resolver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "grasp_test_support.hpp"
#include "rw/math/rpy.hpp"

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::grasp::GraspKind;
using visgrab::grasp::GraspRequest;
using visgrab::grasp::resolve;
using visgrab::grasp::ResolveStatus;
using visgrab::test::grasp::kDeg;
using visgrab::test::grasp::makeQ;
using visgrab::test::grasp::pg70;
using visgrab::test::grasp::sdh;

GraspRequest request(GraspKind kind) {
  GraspRequest r;
  r.sceneId = "s1";
  r.id = "g7";
  r.kind = kind;
  r.X_W_tcp = rw::math::rpyTransform(Vector3D(0.1, std::numbers::pi, 0), Vector3D(0, 0, 0.05));
  r.sourceFile = "grasps/s1.txt";
  r.sourceLine = 12;
  return r;
}

TEST(Resolve, RawGivesItsValues) {
  GraspRequest r = request(GraspKind::kRaw);
  r.qOpen = makeQ({0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7});
  r.qClosed = makeQ({0.2, 0.3, 0.3, 0.5, 0.6, 0.7, 0.8});
  r.tauMax = makeQ({1, 1, 1, 1, 1, 1, 1});
  const auto g = resolve(r, sdh());
  ASSERT_TRUE(g.ok()) << g.message;
  EXPECT_TRUE(g.parameters.X_W_tcp.isApprox(r.X_W_tcp));
  EXPECT_EQ(g.parameters.qOpen, r.qOpen);
  EXPECT_EQ(g.parameters.qClosed, r.qClosed);
  EXPECT_EQ(g.parameters.tauMax, r.tauMax);
}

TEST(Resolve, RawWithoutTauUsesTheRule) {
  GraspRequest r = request(GraspKind::kRaw);
  r.qOpen = makeQ({0, 0, 30 * kDeg, 0, 0, 0, 0});
  r.qClosed = r.qOpen;
  const auto g = resolve(r, sdh());
  ASSERT_TRUE(g.ok()) << g.message;
  const double t = 2.0 / (2.0 * std::cos(30 * kDeg));
  EXPECT_VECTOR_NEAR(g.parameters.tauMax, makeQ({2, 2, 10, t, 2, t, 2}), 1e-12);
}

TEST(Resolve, PreshapeByNameAndAlias) {
  GraspRequest r = request(GraspKind::kPreshape);
  r.preshape = "SDH_CYL";
  const auto a = resolve(r, sdh());
  r.preshape = "cyl";
  const auto b = resolve(r, sdh());
  ASSERT_TRUE(a.ok() && b.ok()) << a.message << b.message;
  EXPECT_EQ(a.parameters.qOpen, makeQ({-1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174}));
  EXPECT_EQ(a.parameters.qClosed, makeQ({0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349}));
  EXPECT_VECTOR_NEAR(a.parameters.tauMax, makeQ({2, 2, 10, 1, 2, 1, 2}), 1e-12);
  EXPECT_TRUE(a.parameters.X_W_tcp.isApprox(r.X_W_tcp));
  EXPECT_EQ(a.parameters.qOpen, b.parameters.qOpen);
}

TEST(Resolve, PoseAndQAppliesTheClosingAndTauRules) {
  GraspRequest r = request(GraspKind::kPoseAndQ);
  r.qOpen = makeQ({0.1, 0.2, 60 * kDeg, 0.3, 0.4, 0.5, 0.6});
  const auto g = resolve(r, sdh());
  ASSERT_TRUE(g.ok()) << g.message;
  EXPECT_EQ(g.parameters.qOpen, r.qOpen);
  const double c = 30 * kDeg;  // VisGraB: +30 deg on joints 0, 3 and 5
  EXPECT_VECTOR_NEAR(g.parameters.qClosed,
                     makeQ({0.1 + c, 0.2, 60 * kDeg, 0.3 + c, 0.4, 0.5 + c, 0.6}), 1e-12);
  EXPECT_VECTOR_NEAR(g.parameters.tauMax,
                     makeQ({std::max(2 * std::cos(60 * kDeg) * 2, 0.2), 2, 10, 2, 2, 2, 2}), 1e-12);
  EXPECT_TRUE(g.parameters.X_W_tcp.isApprox(r.X_W_tcp));
}

TEST(Resolve, Pg70PoseAndQ) {
  GraspRequest r = request(GraspKind::kPoseAndQ);
  r.qOpen = makeQ({0.03});
  const auto g = resolve(r, pg70());
  ASSERT_TRUE(g.ok()) << g.message;
  EXPECT_VECTOR_NEAR(g.parameters.qClosed, makeQ({0.01}), 1e-15);
  EXPECT_EQ(g.parameters.tauMax, makeQ({40}));
}

void expectInputError(const GraspRequest& r, const std::string& what) {
  const auto g = resolve(r, sdh());
  EXPECT_EQ(g.status, ResolveStatus::kInputError);
  EXPECT_EQ(g.message.rfind("grasps/s1.txt:12: grasp \"g7\": ", 0), 0u) << g.message;
  EXPECT_NE(g.message.find(what), std::string::npos) << g.message;
}

TEST(Resolve, InputErrorsNameFileLineAndId) {
  GraspRequest r = request(GraspKind::kPreshape);
  r.preshape = "SDH_FIST";
  expectInputError(r, "unknown pre-shape \"SDH_FIST\"");

  r = request(GraspKind::kPoseAndQ);
  r.qOpen = makeQ({0, 0, 0});
  expectInputError(r, "q has 3 values, but hand \"SchunkHand\" has 7 DOF");

  r = request(GraspKind::kRaw);
  r.qOpen = Q::Zero(7);
  r.qClosed = Q::Zero(6);
  expectInputError(r, "q_closed has 6 values");

  r.qClosed = Q::Zero(7);
  r.tauMax = Q::Zero(2);
  expectInputError(r, "tau_max has 2 values");

  r.tauMax = Q::Constant(7, -1.0);
  expectInputError(r, "tau_max has a negative value");

  r = request(GraspKind::kContacts);
  r.contacts.resize(1);
  expectInputError(r, "cannot solve a grasp with 1 contacts");

  r.contacts.resize(2);
  r.contacts[1].direction = Vector3D::Zero();
  expectInputError(r, "contact 2 has a zero");
}

TEST(Resolve, MessageWithoutSourceStillNamesTheGrasp) {
  GraspRequest r = request(GraspKind::kPreshape);
  r.sourceFile.clear();
  r.preshape = "nope";
  const auto g = resolve(r, sdh());
  EXPECT_EQ(g.message.rfind("grasp \"g7\": unknown pre-shape", 0), 0u) << g.message;
}

}  // namespace

namespace {

// Two contacts 6 cm apart along y at z 0.1, approach straight down: the TCP midway, z down,
// x from the first contact to the second, y = z x x (worked by hand: (0,0,-1) x (0,1,0) =
// (1,0,0)).
TEST(PreshapeFromContacts, TcpBetweenTheContactsClosingAlongX) {
  visgrab::grasp::GraspRequest c;
  c.sceneId = "s";
  c.method = "m";
  c.id = "g";
  c.kind = visgrab::grasp::GraspKind::kContacts;
  c.contacts = {{{0.1, -0.03, 0.1}, {0, 1, 0}}, {{0.1, 0.03, 0.1}, {0, -1, 0}}};
  c.approach = {0, 0, -2};
  const auto p = visgrab::grasp::preshapeFromContacts(c, "wide");
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->kind, visgrab::grasp::GraspKind::kPreshape);
  EXPECT_EQ(p->preshape, "wide");
  EXPECT_EQ(p->id, "g");
  EXPECT_TRUE(p->contacts.empty());
  EXPECT_LT((p->X_W_tcp.translation() - rw::math::Vector3D(0.1, 0, 0.1)).norm(), 1e-15);
  EXPECT_LT((p->X_W_tcp.linear().col(0) - rw::math::Vector3D(0, 1, 0)).norm(), 1e-15);
  EXPECT_LT((p->X_W_tcp.linear().col(1) - rw::math::Vector3D(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((p->X_W_tcp.linear().col(2) - rw::math::Vector3D(0, 0, -1)).norm(), 1e-15);
  // A tilted line between the contacts: x is its part across the approach.
  c.contacts[1].position = {0.1, 0.03, 0.16};
  const auto tilted = visgrab::grasp::preshapeFromContacts(c, "wide");
  ASSERT_TRUE(tilted.has_value());
  EXPECT_LT((tilted->X_W_tcp.linear().col(0) - rw::math::Vector3D(0, 1, 0)).norm(), 1e-15);
  // Not two contacts, no approach, or contacts along the approach: none.
  auto three = c;
  three.contacts.push_back(c.contacts[0]);
  EXPECT_FALSE(visgrab::grasp::preshapeFromContacts(three, "wide").has_value());
  auto noApproach = c;
  noApproach.approach = rw::math::Vector3D::Zero();
  EXPECT_FALSE(visgrab::grasp::preshapeFromContacts(noApproach, "wide").has_value());
  auto along = c;
  along.contacts[1].position = {0.1, -0.03, 0.2};
  EXPECT_FALSE(visgrab::grasp::preshapeFromContacts(along, "wide").has_value());
  auto pose = c;
  pose.kind = visgrab::grasp::GraspKind::kPreshape;
  EXPECT_FALSE(visgrab::grasp::preshapeFromContacts(pose, "wide").has_value());
}

}  // namespace
