// The closing-tag repair that reproduces RobWork's lenient dwc parsing (reference §2.1).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rwsim/loaders/detail/tag_repair.hpp"

namespace {

using rwsim::loaders::detail::repairClosingTags;

TEST(TagRepair, MatchingTagsAreLeftAlone) {
  const std::string text = "<a x=\"1\">\n  <b/>\n  <c>text</c>\n</a>\n";
  const auto r = repairClosingTags(text);
  EXPECT_EQ(r.text, text);
  EXPECT_TRUE(r.repairs.empty());
  EXPECT_FALSE(r.unclosed);
}

TEST(TagRepair, AMismatchedClosingTagClosesTheInnermostElement) {
  const auto r = repairClosingTags(
      "<IncludeData>\n <RigidJoint joint=\"j\">\n  <Mass>0.1</Mass>\n"
      " </RigidBody>\n <PDParams>1 2</PDParam>\n</IncludeData>");
  EXPECT_EQ(r.text,
            "<IncludeData>\n <RigidJoint joint=\"j\">\n  <Mass>0.1</Mass>\n"
            " </RigidJoint>\n <PDParams>1 2</PDParams>\n</IncludeData>");
  ASSERT_EQ(r.repairs.size(), 2u);
  EXPECT_EQ(r.repairs[0].written, "RigidBody");
  EXPECT_EQ(r.repairs[0].closes, "RigidJoint");
  EXPECT_EQ(r.repairs[0].where.line, 4);
  EXPECT_EQ(r.repairs[0].where.column, 2);
  EXPECT_EQ(r.repairs[1].written, "PDParam");
  EXPECT_EQ(r.repairs[1].where.line, 5);
  EXPECT_EQ(r.repairs[1].where.column, 15);
  EXPECT_FALSE(r.unclosed);
}

TEST(TagRepair, CommentsCdataInstructionsAndQuotedValuesAreSkipped) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n<!-- <a> </b> -->\n<a v='x>y' w=\"</q>\"><![CDATA[</z><y>]]>"
      "<?pi </p> ?></a >";
  const auto r = repairClosingTags(text);
  EXPECT_EQ(r.text, text);
  EXPECT_TRUE(r.repairs.empty());
  EXPECT_FALSE(r.unclosed);
}

TEST(TagRepair, LinesStayWhereTheyWere) {
  const std::string text = "<a>\n<b>\n</c>\n<d>\n</e>\n</a>";
  const auto r = repairClosingTags(text);
  EXPECT_EQ(r.text, "<a>\n<b>\n</b>\n<d>\n</d>\n</a>");
  EXPECT_EQ(std::count(r.text.begin(), r.text.end(), '\n'), 5);
}

TEST(TagRepair, ColumnsCountCharactersNotBytes) {
  const auto r = repairClosingTags("<a>\n<b>\xC3\xA4\xC3\xB6</c></a>");
  ASSERT_EQ(r.repairs.size(), 1u);
  EXPECT_EQ(r.repairs[0].where.line, 2);
  EXPECT_EQ(r.repairs[0].where.column, 6);
}

TEST(TagRepair, AnElementOpenAtTheEndIsReported) {
  const auto r = repairClosingTags("<a>\n  <b x=\"1\">\n  <c/>\n");
  ASSERT_TRUE(r.unclosed);
  EXPECT_EQ(r.unclosed->first, "b");
  EXPECT_EQ(r.unclosed->second.line, 2);
  EXPECT_EQ(r.unclosed->second.column, 3);
}

TEST(TagRepair, AClosingTagWithNothingOpenIsLeftForTheParser) {
  const std::string text = "<a></a></b>";
  const auto r = repairClosingTags(text);
  EXPECT_EQ(r.text, text);
  EXPECT_TRUE(r.repairs.empty());
  EXPECT_FALSE(r.unclosed);
}

TEST(TagRepair, UnknownMarkupStopsTheRepair) {
  constexpr char kBinary[] = "<a\0\xff<</b>";
  const std::vector<std::string> texts = {"<a><!DOCTYPE x></b>", "<a><!-- </b>", "<a>< b></c>",
                                          "<a x=\"></b>", std::string(kBinary, sizeof kBinary - 1)};
  for (const std::string& text : texts) {
    const auto r = repairClosingTags(text);
    EXPECT_EQ(r.text, text);
    EXPECT_TRUE(r.repairs.empty());
    EXPECT_FALSE(r.unclosed);
  }
}

}  // namespace
