// Self-collision of the project's hands: free at home and in VisGraB's open pre-shapes with their
// collision setups, and the setups exclude only pairs that touch by construction.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

#include "rw/proximity/collision_detector.hpp"
#include "scene_test_helpers.hpp"

namespace {

using rw::math::Q;
using rw::models::WorkCell;
using visgrab::test::scenes::deviceOf;
using visgrab::test::scenes::load;

std::string describe(const WorkCell& wc, const std::vector<rw::proximity::FramePair>& pairs) {
  std::string text;
  for (const auto& p : pairs) {
    text += wc.frames().frame(p.first).name() + " - " + wc.frames().frame(p.second).name() + "\n";
  }
  return text;
}

std::vector<rw::proximity::FramePair> collidingAt(const WorkCell& wc,
                                                  const rw::proximity::CollisionDetector& detector,
                                                  const std::string& device, const Q& q) {
  auto state = wc.defaultState();
  deviceOf(wc, device).setQ(q, state);
  return detector.collidingPairs(state);
}

Q handQ(std::initializer_list<double> values) {
  Q q(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double v : values) q[i++] = v;
  return q;
}

// Home and the open configurations of VisGraB's SDH pre-shapes (reference §7.1).
std::vector<Q> sdhOpenConfigurations() {
  return {Q::Zero(7),
          handQ({-1.571, -1.571, 1.571, -1.048, 0.174, -1.048, 0.174}),  // SDH_PAR
          handQ({-1.571, -1.571, 1.571, -0.296, 0.240, -0.296, 0.240}),  // SDH_PAR1
          handQ({-1.571, -1.571, 1.571, -0.1, 0.1, -0.1, 0.1}),          // SDH_PAR2
          handQ({-1.048, 0.174, 1.047, -1.048, 0.174, -1.048, 0.174}),   // SDH_BALL
          handQ({-1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174})};    // SDH_CYL
}

TEST(HandCollision, SdhIsFreeAtHomeAndInTheOpenPreShapes) {
  const auto wc = load(visgrab::test::scenes::projectSdhFile());
  const rw::proximity::CollisionDetector detector(*wc);
  for (const Q& q : sdhOpenConfigurations()) {
    EXPECT_EQ(describe(*wc, collidingAt(*wc, detector, "SchunkHand", q)), "")
        << "q = " << q.transpose();
  }
}

TEST(HandCollision, Pg70IsFreeOverItsWholeStroke) {
  const auto wc = load(visgrab::test::scenes::projectPg70File());
  const rw::proximity::CollisionDetector detector(*wc);
  for (const double q : {0.0, 0.01, 0.035}) {
    EXPECT_EQ(describe(*wc, collidingAt(*wc, detector, "PG70", Q::Constant(1, q))), "")
        << "q = " << q;
  }
}

// Every pair that touches at home (checked without any exclusion) is excluded by the hand's
// collision setup, and every excluded pair names two frames that carry geometry.
TEST(HandCollision, SetupsExcludeOnlyPairsThatTouch) {
  for (const auto& [file, device, dof] :
       {std::tuple{visgrab::test::scenes::projectSdhFile(), "SchunkHand", 7},
        std::tuple{visgrab::test::scenes::projectPg70File(), "PG70", 1}}) {
    SCOPED_TRACE(file.string());
    const auto wc = load(file);
    rw::models::ProximitySetup none;
    none.useIncludeAll = true;
    none.useExcludeStaticPairs = false;
    const rw::proximity::CollisionDetector all(*wc, none);
    const auto touching = collidingAt(*wc, all, device, Q::Zero(dof));
    for (const auto& [a, b] : wc->collisionSetup().excludePairs) {
      const auto fa = wc->findFrame(a);
      const auto fb = wc->findFrame(b);
      ASSERT_TRUE(fa.valid() && fb.valid()) << a << " - " << b;
      EXPECT_NE(wc->findObject(fa), nullptr) << a;
      EXPECT_NE(wc->findObject(fb), nullptr) << b;
    }
    if (dof == 7) {
      // The proximal and distal links overlap at their joint: the check does see contact.
      const auto j2 = wc->findFrame("SchunkHand.f1.Joint2");
      const auto j3 = wc->findFrame("SchunkHand.f1.Joint3");
      EXPECT_NE(std::find(touching.begin(), touching.end(), rw::proximity::makeFramePair(j2, j3)),
                touching.end());
    }
    const rw::proximity::CollisionDetector withSetup(*wc);
    for (const auto& pair : touching) {
      const auto& checked = withSetup.checkedPairs();
      EXPECT_EQ(std::find(checked.begin(), checked.end(), pair), checked.end())
          << describe(*wc, {pair}) << "touches at home but is checked";
    }
  }
}

}  // namespace
