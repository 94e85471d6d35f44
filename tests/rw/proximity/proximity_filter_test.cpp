// Pair selection: include-all, static groups, wildcard and REGEX rules in order.
#include "rw/proximity/proximity_filter.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "chain_scene.hpp"

namespace rw::proximity {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

using rw::geometry::Geometry;
using rw::models::ProximitySetup;
using test::addFrame;
using test::addGeometry;
using test::exclude;
using test::FrameId;
using test::FrameType;
using test::include;
using test::pose;

// WORLD -> Base (fixed) -> Link1 (revolute) -> Link1Pad (fixed), Link1 -> Link2 (revolute, no
// geometry) -> Tool.Tip (fixed); WORLD -> Table (fixed) -> Obj (fixed DAF);
// WORLD -> ToolxTip (movable). Seven frames carry geometry.
class FilterTest : public ::testing::Test {
 protected:
  FilterTest() : wc_("FilterScene") {
    const FrameId world = rw::kinematics::FrameTree::kWorld;
    base = addFrame(wc_, "Base", world, FrameType::kFixed);
    link1 = addFrame(wc_, "Link1", base, FrameType::kRevolute, pose({0, 0, 0.1}));
    pad = addFrame(wc_, "Link1Pad", link1, FrameType::kFixed, pose({0.1, 0, 0}));
    link2 = addFrame(wc_, "Link2", link1, FrameType::kRevolute, pose({0, 0, 0.5}));
    tip = addFrame(wc_, "Tool.Tip", link2, FrameType::kFixed, pose({0, 0, 0.2}));
    table = addFrame(wc_, "Table", world, FrameType::kFixed, pose({1, 0, 0}));
    obj = addFrame(wc_, "Obj", table, FrameType::kFixed, pose({0, 0, 0.1}), true);
    toolx = addFrame(wc_, "ToolxTip", world, FrameType::kMovable, pose({0, 1, 0}));
    for (const FrameId f : {base, link1, pad, tip, table, obj, toolx}) {
      addGeometry(wc_, f, Geometry::box(0.1, 0.1, 0.1));
    }
  }

  ProximityFilter filterWith(bool includeAll, bool excludeStatic,
                             std::vector<rw::models::ProximityRule> rules) const {
    ProximitySetup setup;
    setup.useIncludeAll = includeAll;
    setup.useExcludeStaticPairs = excludeStatic;
    setup.rules = std::move(rules);
    return ProximityFilter(wc_, setup);
  }

  rw::models::WorkCell wc_;
  FrameId base, link1, pad, link2, tip, table, obj, toolx;
};

TEST_F(FilterTest, IncludeAllTakesEveryPairOfFramesWithGeometryInIdOrder) {
  const ProximityFilter filter(wc_);      // built in code: include all, no rules
  EXPECT_EQ(filter.pairs().size(), 21U);  // 7 choose 2
  EXPECT_FALSE(filter.contains(link2, base));
  EXPECT_TRUE(filter.contains(tip, base));
  EXPECT_TRUE(filter.contains(base, tip));
  EXPECT_FALSE(filter.contains(base, base));
  EXPECT_TRUE(std::is_sorted(filter.pairs().begin(), filter.pairs().end()));
  for (const FramePair& p : filter.pairs()) EXPECT_LT(p.first, p.second);
}

TEST_F(FilterTest, StaticGroupsFollowFixedFramesOnly) {
  const std::vector<int> g = staticFrameGroups(wc_.frames());
  const auto group = [&](FrameId f) { return g[static_cast<std::size_t>(f.index)]; };
  EXPECT_EQ(group(base), group(rw::kinematics::FrameTree::kWorld));
  EXPECT_EQ(group(table), group(base));
  EXPECT_EQ(group(pad), group(link1));
  EXPECT_NE(group(link1), group(base));
  EXPECT_EQ(group(tip), group(link2));
  EXPECT_NE(group(link2), group(link1));
  EXPECT_NE(group(obj), group(table));  // a DAF starts its own group
  EXPECT_NE(group(toolx), group(base));
}

TEST_F(FilterTest, ExcludeStaticPairsDropsRigidlyConnectedPairs) {
  const ProximityFilter filter = filterWith(true, true, {});
  EXPECT_EQ(filter.pairs().size(), 19U);
  EXPECT_FALSE(filter.contains(base, table));
  EXPECT_FALSE(filter.contains(link1, pad));
  EXPECT_TRUE(filter.contains(table, obj));
  EXPECT_TRUE(filter.contains(base, link1));
}

TEST_F(FilterTest, WildcardsAndLiteralDots) {
  // "Link*" matches Link1, Link1Pad and Link2: 2 frames with geometry x 6 others + their pair.
  EXPECT_EQ(filterWith(true, false, {exclude("Link*", "*")}).pairs().size(), 21U - 11U);
  // "." is literal: Tool.Tip matches itself only, not ToolxTip.
  const ProximityFilter dot = filterWith(true, false, {exclude("Tool.Tip", "*")});
  EXPECT_EQ(dot.pairs().size(), 15U);
  EXPECT_FALSE(dot.contains(tip, base));
  EXPECT_TRUE(dot.contains(toolx, base));
  // "?" is exactly one character: Link? matches Link1 but not Link1Pad.
  const ProximityFilter one = filterWith(true, false, {exclude("Link?", "Base")});
  EXPECT_FALSE(one.contains(link1, base));
  EXPECT_TRUE(one.contains(pad, base));
  // A rule matches either order of the pair.
  const ProximityFilter either = filterWith(true, false, {exclude("Obj", "Table")});
  EXPECT_FALSE(either.contains(table, obj));
  EXPECT_EQ(either.pairs().size(), 20U);
}

TEST_F(FilterTest, RegexRules) {
  const ProximityFilter filter =
      filterWith(true, false, {exclude("REGEX(Base|Table)", "REGEXLink[0-9]+")});
  EXPECT_FALSE(filter.contains(base, link1));
  EXPECT_FALSE(filter.contains(table, link1));
  EXPECT_TRUE(filter.contains(base, pad));
  EXPECT_EQ(filter.pairs().size(), 19U);
  EXPECT_THROW(filterWith(true, false, {exclude("REGEX(", "*")}), std::invalid_argument);
}

TEST_F(FilterTest, IncludeAfterExcludeAddsPairsEvenWithoutGeometry) {
  const ProximityFilter filter = filterWith(
      true, false, {exclude("*", "*"), include("Base", "Obj"), include("Link2", "Base")});
  ASSERT_EQ(filter.pairs().size(), 2U);
  EXPECT_TRUE(filter.contains(base, obj));
  EXPECT_TRUE(filter.contains(base, link2));
  // Exclude after include removes again; rules apply in order.
  const ProximityFilter later =
      filterWith(false, false, {include("*", "Obj"), exclude("Base", "*")});
  EXPECT_EQ(later.pairs().size(), 7U);  // every other frame (8 of 9, WORLD included) minus Base
  EXPECT_FALSE(later.contains(base, obj));
  EXPECT_TRUE(later.contains(rw::kinematics::FrameTree::kWorld, obj));
}

}  // namespace
}  // namespace rw::proximity
