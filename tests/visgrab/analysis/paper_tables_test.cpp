#include "visgrab/analysis/paper_tables.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

#include "visgrab/analysis/analysis.hpp"

namespace visgrab::analysis {
namespace {

/// The paper value pair, failing the test where there is none.
std::array<double, 2> values(PaperTable table, const std::string& group,
                             const std::string& method) {
  const auto v = paperValues(table, group, method);
  EXPECT_TRUE(v.has_value()) << group << " " << method;
  return v.value_or(std::array<double, 2>{std::nan(""), std::nan("")});
}

/// Expects `text` to be rejected with a message containing `what`.
void expectRejected(const std::string& text, const std::string& what) {
  try {
    parsePaperTables(text, "t.csv");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(what), std::string::npos) << error.what();
  }
}

constexpr const char* kHeader = "table,texture,group,method,q_lift,q_gws,p,ga\n";

// A malformed compiled-in table is a programming error: this test fails, not the user's report.
TEST(PaperTablesTest, CompiledInTableIsCompleteAndWellFormed) {
  const std::vector<PaperEntry>& entries = paperTables();
  // 2 tables x 2 textures x 6 rows x 3 grasp types.
  ASSERT_EQ(entries.size(), 2u * 2u * 6u * 3u);
  std::set<std::tuple<PaperTable, std::string, std::string>> seen;
  for (const PaperEntry& e : entries) seen.emplace(e.table, e.group, e.method);
  for (const PaperTable table : {PaperTable::kQuality, PaperTable::kFirstSuccess}) {
    for (const ConditionGroup& g : conditionGroups()) {
      for (const char* method : {"s2EGA1", "s2EGA3", "s3EGA1"}) {
        // The paper's rows: every group of a texture and a scene kind.
        EXPECT_EQ(seen.count({table, g.key, method}), g.kind.has_value() ? 1u : 0u)
            << g.key << " " << method;
      }
    }
  }
  EXPECT_FALSE(paperComparisonNote().heading.empty());
  EXPECT_FALSE(paperComparisonNote().paragraphs.empty());
}

// Spot checks against the paper's Tables 1 and 2 (section 4.1).
TEST(PaperTablesTest, ValuesAreThePapers) {
  using T = PaperTable;
  EXPECT_EQ(values(T::kFirstSuccess, "textured-single-all", "s3EGA1"),
            (std::array<double, 2>{0.84, 2.60}));
  EXPECT_EQ(values(T::kFirstSuccess, "plain-single-all", "s2EGA1")[0], 0.77);
  EXPECT_EQ(values(T::kFirstSuccess, "plain-single-lying", "s3EGA1"),
            (std::array<double, 2>{0.81, 5.04}));
  EXPECT_EQ(values(T::kFirstSuccess, "textured-double-apart", "s2EGA3"),
            (std::array<double, 2>{0.69, 4.12}));
  EXPECT_EQ(values(T::kFirstSuccess, "plain-double-close", "s2EGA3"),
            (std::array<double, 2>{0.58, 4.94}));
  EXPECT_EQ(values(T::kQuality, "textured-single-standing", "s2EGA1"),
            (std::array<double, 2>{0.58, 0.46}));
  EXPECT_EQ(values(T::kQuality, "plain-single-lying", "s2EGA3"),
            (std::array<double, 2>{0.01, 0.03}));
  EXPECT_EQ(values(T::kQuality, "plain-double-all", "s3EGA1"), (std::array<double, 2>{0.68, 0.53}));
  EXPECT_EQ(values(T::kQuality, "textured-double-close", "s2EGA1"),
            (std::array<double, 2>{0.68, 0.46}));
  // No values for other methods, a table's "all" row, "overall".
  EXPECT_FALSE(paperValues(T::kFirstSuccess, "textured-single-all", "mine"));
  EXPECT_FALSE(paperValues(T::kFirstSuccess, "textured-single-all", "s3ega1"));
  EXPECT_FALSE(paperValues(T::kFirstSuccess, "textured-all", "s3EGA1"));
  EXPECT_FALSE(paperValues(T::kQuality, "overall", "s3EGA1"));
  EXPECT_TRUE(isPaperMethod("s2EGA3"));
  EXPECT_FALSE(isPaperMethod("mine"));
}

// A typo guard independent of the spot checks: the paper's "all" rows follow from its other
// rows. Single and double groups have as many standing as lying (apart as close) scenes, so p(all)
// is the mean of the two p (up to the paper's rounding to 0.01) and ga(all) their mean weighted
// by p; Q(all) lies between the two Q (its weights, the successful trials, are not printed).
TEST(PaperTablesTest, AllRowsAgreeWithTheirParts) {
  for (const std::string texture : {"textured", "plain"}) {
    for (const char* method : {"s2EGA1", "s2EGA3", "s3EGA1"}) {
      for (const auto& [kind, a, b] :
           {std::tuple<std::string, std::string, std::string>{"single", "standing", "lying"},
            {"double", "apart", "close"}}) {
        const std::string prefix = texture + "-" + kind + "-";
        SCOPED_TRACE(prefix + " " + method);
        const auto p1 = values(PaperTable::kFirstSuccess, prefix + a, method);
        const auto p2 = values(PaperTable::kFirstSuccess, prefix + b, method);
        const auto pAll = values(PaperTable::kFirstSuccess, prefix + "all", method);
        EXPECT_NEAR(pAll[0], (p1[0] + p2[0]) / 2, 0.0051);
        EXPECT_NEAR(pAll[1], (p1[0] * p1[1] + p2[0] * p2[1]) / (p1[0] + p2[0]), 0.01);
        const auto q1 = values(PaperTable::kQuality, prefix + a, method);
        const auto q2 = values(PaperTable::kQuality, prefix + b, method);
        const auto qAll = values(PaperTable::kQuality, prefix + "all", method);
        for (std::size_t k = 0; k < 2; ++k) {
          EXPECT_GE(qAll[k], std::min(q1[k], q2[k]) - 0.005);
          EXPECT_LE(qAll[k], std::max(q1[k], q2[k]) + 0.005);
        }
      }
    }
  }
}

TEST(PaperTablesTest, ParsesCommentsHeaderAndEntries) {
  const auto entries = parsePaperTables(
      "# comment\n\ntable,texture,group,method,q_lift,q_gws,p,ga\n"
      "1,plain,plain-double-close,s3EGA1,0.5,0.25,,\r\n"
      "2,textured,textured-single-lying,s2EGA3,,,0.06,2.38\n");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].table, PaperTable::kQuality);
  EXPECT_EQ(entries[0].texture, database::Texture::kPlain);
  EXPECT_EQ(entries[0].group, "plain-double-close");
  EXPECT_EQ(entries[0].method, "s3EGA1");
  EXPECT_EQ(entries[0].values, (std::array<double, 2>{0.5, 0.25}));
  EXPECT_EQ(entries[1].table, PaperTable::kFirstSuccess);
  EXPECT_EQ(entries[1].values, (std::array<double, 2>{0.06, 2.38}));
}

TEST(PaperTablesTest, RejectsMalformedTablesNamingTheLine) {
  std::string h = "# c\n";
  h += kHeader;
  expectRejected("# only a comment\n", "t.csv: no header line");
  expectRejected("table,texture\n", "t.csv:1: expected the header");
  expectRejected(h + "1,plain,plain-single-all,s2EGA1,0.5,0.5,\n", "t.csv:3: expected 8 fields");
  expectRejected(h + "3,plain,plain-single-all,s2EGA1,0.5,0.5,,\n", "t.csv:3: table '3'");
  expectRejected(h + "1,wood,plain-single-all,s2EGA1,0.5,0.5,,\n", "unknown texture 'wood'");
  expectRejected(h + "1,plain,textured-single-all,s2EGA1,0.5,0.5,,\n",
                 "group 'textured-single-all' is not a row of the paper's plain table");
  expectRejected(h + "1,plain,plain-all,s2EGA1,0.5,0.5,,\n", "group 'plain-all'");
  expectRejected(h + "1,plain,overall,s2EGA1,0.5,0.5,,\n", "group 'overall'");
  expectRejected(h + "1,plain,plain-single-all,s2EGAl,0.5,0.5,,\n", "unknown grasp type 's2EGAl'");
  expectRejected(h + "1,plain,plain-single-all,s2EGA1,0.5,0.5,0.5,\n", "table 1 has no p, ga");
  expectRejected(h + "2,plain,plain-single-all,s2EGA1,0.5,,0.5,2\n",
                 "table 2 has no q_lift, q_gws");
  expectRejected(h + "1,plain,plain-single-all,s2EGA1,0.5,O.5,,\n", "q_gws 'O.5' is not a number");
  expectRejected(h + "1,plain,plain-single-all,s2EGA1,,0.5,,\n", "q_lift '' is not a number");
  expectRejected(h + "1,plain,plain-single-all,s2EGA1,nan,0.5,,\n", "q_lift is not finite");
  expectRejected(h + "1,plain,plain-single-all,s2EGA1,1.5,0.5,,\n", "must be in [0, 1]");
  expectRejected(h + "2,plain,plain-single-all,s2EGA1,,,0.5,0.9\n", "ga >= 1");
  expectRejected(h + "2,plain,plain-single-all,s2EGA1,,,0.5,2\n2,plain,plain-single-all,s2EGA1,,,"
                     "0.6,2\n",
                 "t.csv:4: repeats");
  expectRejected(h + "2,plain,plain-single-all,\"s2EGA1,,,0.5,2\n", "t.csv:3: ");
}

TEST(PaperTablesTest, ParsesTheComparisonNote) {
  const PaperComparisonNote note =
      parsePaperComparisonNote("# Heading\n\nFirst line\nsecond line.\n\n\nOther.\n");
  EXPECT_EQ(note.heading, "Heading");
  EXPECT_EQ(note.paragraphs, (std::vector<std::string>{"First line second line.", "Other."}));
  EXPECT_THROW(parsePaperComparisonNote("Heading\n\nText.\n"), std::invalid_argument);
  EXPECT_THROW(parsePaperComparisonNote("# \n\nText.\n"), std::invalid_argument);
  EXPECT_THROW(parsePaperComparisonNote("# Heading\n\n"), std::invalid_argument);
}

// The note is shown as plain text in both reports: no Markdown markup that the HTML page would
// show literally.
TEST(PaperTablesTest, ComparisonNoteIsPlainText) {
  const PaperComparisonNote& note = paperComparisonNote();
  EXPECT_EQ(note.heading, "Comparing with the paper");
  for (const std::string& paragraph : note.paragraphs) {
    EXPECT_EQ(paragraph.find_first_of("*`<>#"), std::string::npos) << paragraph;
    EXPECT_EQ(paragraph.find("]("), std::string::npos) << paragraph;
  }
}

}  // namespace
}  // namespace visgrab::analysis
