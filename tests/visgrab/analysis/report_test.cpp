#include "visgrab/analysis/report.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.hpp"
#include "test_runs.hpp"
#include "visgrab/analysis/detail/report_tables.hpp"

namespace visgrab::analysis {
namespace {

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A small well-formedness checker for the report's HTML: every tag closed in order (void
/// elements self-closed with "/>"), attribute values quoted, no raw '<' or '>' in text, every
/// '&' starts an entity. Returns "" or what is wrong.
std::string checkWellFormed(const std::string& html) {
  const std::set<std::string> entities = {"&amp;", "&lt;", "&gt;", "&quot;", "&#39;"};
  std::vector<std::string> stack;
  std::size_t i = 0;
  if (html.rfind("<!DOCTYPE html>", 0) != 0) return "no doctype";
  i = html.find('>') + 1;
  while (i < html.size()) {
    const char c = html[i];
    if (c == '&') {
      const std::size_t end = html.find(';', i);
      if (end == std::string::npos || entities.count(html.substr(i, end - i + 1)) == 0) {
        return "bare '&' at " + std::to_string(i);
      }
      i = end + 1;
      continue;
    }
    if (c == '>') return "bare '>' at " + std::to_string(i);
    if (c != '<') {
      ++i;
      continue;
    }
    // A tag: scan to its '>' outside quoted attribute values.
    std::size_t j = i + 1;
    bool quoted = false;
    while (j < html.size() && (quoted || html[j] != '>')) {
      if (html[j] == '"') quoted = !quoted;
      if (!quoted && html[j] == '<') return "'<' inside a tag at " + std::to_string(j);
      ++j;
    }
    if (j >= html.size()) return "unterminated tag at " + std::to_string(i);
    std::string tag = html.substr(i + 1, j - i - 1);
    i = j + 1;
    const bool closing = !tag.empty() && tag[0] == '/';
    const bool selfClosing = !tag.empty() && tag.back() == '/';
    std::size_t n = closing ? 1 : 0;
    std::string name;
    while (n < tag.size() && (std::isalnum(static_cast<unsigned char>(tag[n])) != 0)) {
      name += tag[n++];
    }
    if (name.empty()) return "tag without a name: <" + tag + ">";
    if (closing) {
      if (stack.empty() || stack.back() != name) {
        return "</" + name + "> closes <" + (stack.empty() ? "" : stack.back()) + ">";
      }
      stack.pop_back();
    } else if (!selfClosing) {
      if (name == "meta" || name == "br" || name == "line") {
        return "void element <" + name + "> not self-closed";
      }
      stack.push_back(name);
    }
    if (name == "style" && !closing) {
      const std::size_t end = html.find("</style>", i);
      if (end == std::string::npos) return "unclosed style";
      i = end;
    }
  }
  if (!stack.empty()) return "unclosed <" + stack.back() + ">";
  return "";
}

TEST(ReportTest, CheckerCatchesMistakes) {
  EXPECT_EQ(checkWellFormed("<!DOCTYPE html>\n<p>a &amp; b<br/></p>"), "");
  EXPECT_NE(checkWellFormed("<!DOCTYPE html>\n<p>a & b</p>"), "");
  EXPECT_NE(checkWellFormed("<!DOCTYPE html>\n<p><b>x</p></b>"), "");
  EXPECT_NE(checkWellFormed("<!DOCTYPE html>\n<p>x"), "");
  EXPECT_NE(checkWellFormed("<!DOCTYPE html>\n<p>1 < 2</p>"), "");
}

TEST(ReportTest, EscapesHtml) {
  EXPECT_EQ(escapeHtml("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
}

/// The options of the report as it was before intervals: no resamples.
AnalysisOptions withoutIntervals() {
  AnalysisOptions options;
  options.bootstrapResamples = 0;
  return options;
}

/// The paper's numbers of the shared test runs, without intervals (ReportIntervalsTest has them).
class ReportFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    writeReport({test_runs::runA(), test_runs::runB()}, dir.path(), withoutIntervals());
  }
  test::TempDir dir;
};

TEST_F(ReportFilesTest, HtmlIsWellFormedSelfContainedAndHasTheNumbers) {
  const std::string html = readText(dir.path() / "report.html");
  EXPECT_EQ(checkWellFormed(html), "");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_NE(html.find("<rect"), std::string::npos);
  EXPECT_NE(html.find("<polyline"), std::string::npos);
  for (const char* external : {"<script", "<link", "src=", "href=", "url(", "@import"}) {
    EXPECT_EQ(html.find(external), std::string::npos) << external;
  }
  // The method name with markup characters is escaped, never raw.
  EXPECT_NE(html.find("x&lt;&amp;&gt;&quot;"), std::string::npos);
  EXPECT_EQ(html.find("x<&>"), std::string::npos);
  // Table 2, textured single standing, runA: p = 0.50, ga = 5/3 = 1.67 (analysis_test.cpp).
  EXPECT_NE(html.find("<tr><td class=\"text\">textured, single, standing</td>"
                      "<td class=\"text\">runA: A</td><td>0.50</td><td>1.67</td>"),
            std::string::npos);
  // Table 1, textured single standing, runA: Q_lift 0.70, Q_GWS 0.30, Q_GWS,unit 0.03.
  EXPECT_NE(html.find("<td class=\"text\">runA: A</td><td>2</td><td>0.70</td><td>0.30</td>"
                      "<td>0.03</td></tr>"),
            std::string::npos);
  EXPECT_NE(html.find("<th>Q<sub>lift</sub></th><th>Q<sub>GWS</sub></th>"
                      "<th>Q<sub>GWS,unit</sub></th>"),
            std::string::npos);
  EXPECT_NE(html.find("as VisGraB&#39;s original simulator computed its tables"),
            std::string::npos);
  // Figure 6: the grey share of textured single standing for runA is 0.500.
  EXPECT_NE(html.find("runA: A, no grasp suggested: 0.500"), std::string::npos);
  EXPECT_NE(html.find("fill=\"#a6a6a6\""), std::string::npos);
  // Table 3: cocacola standing 50 %; pair e far 33 %, held object 14: 33 %.
  EXPECT_NE(html.find("title=\"2 of 4\">50 %</td>"), std::string::npos);
  EXPECT_NE(html.find("<th>pair</th>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"text\">e: 5-14</td>"), std::string::npos);
  EXPECT_NE(html.find("title=\"1 of 3\">33 % <small>(0 % / 33 %)</small></td>"), std::string::npos);
  // No intervals: no band, no interval, no statistics section.
  EXPECT_EQ(html.find("<polygon"), std::string::npos);
  EXPECT_EQ(html.find(" ["), std::string::npos);
  EXPECT_EQ(html.find("Overall success rate"), std::string::npos);
}

TEST_F(ReportFilesTest, MarkdownAndCsvHaveTheNumbers) {
  const std::string md = readText(dir.path() / "report.md");
  EXPECT_NE(md.find("| textured, single, standing | runA: A | 0.50 | 1.67 |"), std::string::npos);
  EXPECT_NE(md.find("| textured, all | runA: A | 0.60 | 1.72 |"), std::string::npos);
  EXPECT_NE(md.find("x<&>\""), std::string::npos);
  // The runs' table: rejected grasps and closings that hit the cap per method.
  EXPECT_NE(md.find("| run | method | rejected grasps | closings at the cap |"), std::string::npos);
  EXPECT_NE(md.find("| runA | runA: A | 2 | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| runB | runB: A | 0 | 0 |"), std::string::npos) << md;

  const std::string first = readText(dir.path() / "first_success.csv");
  EXPECT_EQ(first.rfind("group,method,scenes,scenes_with_success,p,ga,", 0), 0u);
  // p = 3/5, ga = 31/18 for textured all.
  EXPECT_NE(first.find("textured-all,runA: A,5,3,0.6,1.7222222222222223,"), std::string::npos)
      << first;
  const std::string attempts = readText(dir.path() / "attempts.csv");
  EXPECT_NE(attempts.find("textured-single-standing,runA: A,2,0.4166666666666667,"),
            std::string::npos);
  const std::string distribution = readText(dir.path() / "distribution.csv");
  EXPECT_NE(distribution.find("textured-single-standing,runA: A,2,1,4,"), std::string::npos);
  const std::string objects = readText(dir.path() / "objects.csv");
  EXPECT_NE(objects.find("textured,runA: A,double,e,cocacola+saltcylinder,apart,3,1,"),
            std::string::npos);
  // Table 1 with both Q_GWS columns and the note defining them.
  EXPECT_NE(md.find("| group | method | successes | Q_lift | Q_GWS | Q_GWS,unit |"),
            std::string::npos);
  EXPECT_NE(md.find("| textured, single, standing | runA: A | 2 | 0.70 | 0.30 | 0.03 |"),
            std::string::npos);
  EXPECT_NE(md.find("Q_GWS,unit: unit normal forces"), std::string::npos);
  const std::string quality = readText(dir.path() / "quality.csv");
  EXPECT_NE(quality.find("\ntextured-single-standing,runA: A,2,0.7,0.30000000000000004,,,0.03\n"),
            std::string::npos)
      << quality;
}

TEST_F(ReportFilesTest, NoPaperColumnsWithoutThePapersMethods) {
  const std::string md = readText(dir.path() / "report.md");
  const std::string html = readText(dir.path() / "report.html");
  EXPECT_EQ(md.find("paper"), std::string::npos);
  EXPECT_EQ(html.find("class=\"paper\""), std::string::npos);
  EXPECT_EQ(html.find("Comparing with the paper"), std::string::npos);
  // The CSV columns are always there, empty.
  const std::string first = readText(dir.path() / "first_success.csv");
  EXPECT_NE(first.find(",ga_given_order,paper_p,paper_ga\n"), std::string::npos);
  EXPECT_NE(first.find("\ntextured-single-all,runA: A,3,2,"), std::string::npos);
  const std::string quality = readText(dir.path() / "quality.csv");
  EXPECT_EQ(quality.rfind("group,method,successes,mean_q_lift,mean_q_gws,paper_q_lift,paper_q_gws,"
                          "mean_q_gws_unit\n",
                          0),
            0u);
}

/// One textured single standing scene where "s3EGA1" (named like the paper's grasp type) and
/// "mine" (not) each have one stable grasp: s3EGA1 (0.9, 0.4, unit 0.04), mine (0.5, 0.2, 0.02).
results::RunResults paperNamedRun() {
  results::RunResults run;
  run.label = "run";
  const auto s1 =
      test_runs::scene(database::SceneConditions::single(database::Texture::kTextured, 5, 1));
  run.scenes = {s1};
  run.methods = {"s3EGA1", "mine"};
  run.trials = {
      test_runs::trial(s1, "s3EGA1", 0, rwsim::trial::GraspOutcome::kStable, 0.9, 0.4, 5, 0.04),
      test_runs::trial(s1, "mine", 0, rwsim::trial::GraspOutcome::kStable, 0.5, 0.2, 5, 0.02)};
  return run;
}

TEST(ReportPaperColumnsTest, PaperValuesBesideOursOnlyForThePapersMethods) {
  test::TempDir dir;
  writeReport({paperNamedRun()}, dir.path(), withoutIntervals());

  // Markdown: Table 2 and Table 1 with the paper's columns; s3EGA1 textured single has p = 0.84,
  // ga = 2.60 in the paper (single all), 0.88, 2.18 (single standing); Q 0.72, 0.59 (standing).
  const std::string md = readText(dir.path() / "report.md");
  EXPECT_NE(md.find("| group | method | p | ga | paper p | paper ga | ga (randomized) | ga (given "
                    "order) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| textured, single, all | s3EGA1 | 1.00 | 1.00 | 0.84 | 2.60 | 1.00 | 1.00 |"),
            std::string::npos);
  EXPECT_NE(md.find("| textured, single, standing | s3EGA1 | 1.00 | 1.00 | 0.88 | 2.18 |"),
            std::string::npos);
  EXPECT_NE(md.find("| textured, single, all | mine | 1.00 | 1.00 |  |  | 1.00 | 1.00 |"),
            std::string::npos);
  // Rows the paper does not have: none.
  EXPECT_NE(md.find("| textured, all | s3EGA1 | 1.00 | 1.00 |  |  |"), std::string::npos);
  EXPECT_NE(md.find("| overall | s3EGA1 | 1.00 | 1.00 |  |  |"), std::string::npos);
  // Table 1: the paper's Q_GWS right after ours (q_gws, the paper's definition), then
  // Q_GWS,unit.
  EXPECT_NE(md.find("| group | method | successes | Q_lift | Q_GWS | paper Q_lift | paper Q_GWS | "
                    "Q_GWS,unit |"),
            std::string::npos);
  EXPECT_NE(
      md.find("| textured, single, standing | s3EGA1 | 1 | 0.90 | 0.40 | 0.72 | 0.59 | 0.04 |"),
      std::string::npos);
  EXPECT_NE(md.find("| textured, single, standing | mine | 1 | 0.50 | 0.20 |  |  | 0.02 |"),
            std::string::npos);
  EXPECT_NE(md.find("compare with Q_GWS, not Q_GWS,unit"), std::string::npos);
  EXPECT_NE(md.find("\n### Comparing with the paper\n"), std::string::npos);
  EXPECT_NE(md.find("not the paper's real camera images"), std::string::npos);

  // HTML: the same tables, the paper's columns grey and italic.
  const std::string html = readText(dir.path() / "report.html");
  EXPECT_EQ(checkWellFormed(html), "");
  EXPECT_NE(html.find("<th>p</th><th>ga</th><th class=\"paper\">paper p</th>"
                      "<th class=\"paper\">paper ga</th><th>ga (randomized)</th>"
                      "<th>ga (given order)</th></tr>"),
            std::string::npos);
  // Table 2, textured single all; Table 1, textured single standing.
  EXPECT_NE(html.find("<td class=\"text\">textured, single, all</td><td class=\"text\">s3EGA1"
                      "</td><td>1.00</td><td>1.00</td><td class=\"paper\">0.84</td>"
                      "<td class=\"paper\">2.60</td><td>1.00</td><td>1.00</td></tr>"),
            std::string::npos);
  EXPECT_NE(html.find("<td class=\"text\">s3EGA1</td><td>1</td><td>0.90</td><td>0.40</td>"
                      "<td class=\"paper\">0.72</td><td class=\"paper\">0.59</td>"
                      "<td>0.04</td></tr>"),
            std::string::npos);
  EXPECT_NE(html.find("<th>Q<sub>GWS</sub></th><th class=\"paper\">paper Q<sub>lift</sub></th>"),
            std::string::npos);
  // Rows the paper does not have get empty paper cells.
  EXPECT_NE(html.find("<td class=\"text\">overall</td><td class=\"text\">s3EGA1</td>"
                      "<td>1.00</td><td>1.00</td><td class=\"paper\"></td>"
                      "<td class=\"paper\"></td>"),
            std::string::npos);
  EXPECT_NE(html.find("<h3>Comparing with the paper</h3>"), std::string::npos);
  EXPECT_NE(html.find("not the paper&#39;s real camera images"), std::string::npos);

  // CSV: the paper's values where it has them, empty fields elsewhere.
  const std::string first = readText(dir.path() / "first_success.csv");
  EXPECT_NE(first.find("\ntextured-single-all,s3EGA1,1,1,1,1,1,1,0.84,2.6\n"), std::string::npos)
      << first;
  EXPECT_NE(first.find("\ntextured-single-all,mine,1,1,1,1,1,1,,\n"), std::string::npos);
  EXPECT_NE(first.find("\ntextured-all,s3EGA1,1,1,1,1,1,1,,\n"), std::string::npos);
  // The paper's plain rows even where this run has no scene (our values undefined).
  EXPECT_NE(first.find("\nplain-single-all,s3EGA1,0,0,,,,,0.88,3.15\n"), std::string::npos);
  const std::string quality = readText(dir.path() / "quality.csv");
  EXPECT_NE(quality.find("\ntextured-single-standing,s3EGA1,1,0.9,0.4,0.72,0.59,0.04\n"),
            std::string::npos)
      << quality;
  EXPECT_NE(quality.find("\ntextured-single-standing,mine,1,0.5,0.2,,,0.02\n"), std::string::npos);
}

TEST_F(ReportFilesTest, ReportIsDeterministic) {
  test::TempDir other;
  writeReport({test_runs::runA(), test_runs::runB()}, other.path(), withoutIntervals());
  for (const char* file : {"report.html", "report.md", "attempts.csv", "distribution.csv"}) {
    EXPECT_EQ(readText(dir.path() / file), readText(other.path() / file)) << file;
  }
}

/// Without resamples the report's files are byte for byte those of the writer before intervals
/// and the table model existed: data/before_intervals holds them, written by the code of commit
/// 4fb8abf (writeReport with its default options) for runA + runB ("ab") and paperNamedRun()
/// ("paper"). report.html is not compared: its tables now share the Markdown layout.
TEST(ReportWithoutIntervalsTest, FilesAreThoseOfTheWriterBeforeIntervals) {
  const std::filesystem::path before =
      test::sourceDir() / "tests/visgrab/analysis/data/before_intervals";
  const std::vector<std::pair<std::string, std::vector<results::RunResults>>> cases = {
      {"ab", {test_runs::runA(), test_runs::runB()}}, {"paper", {paperNamedRun()}}};
  for (const auto& [name, runs] : cases) {
    test::TempDir dir;
    writeReport(runs, dir.path(), withoutIntervals());
    for (const char* file : {"distribution.csv", "quality.csv", "attempts.csv", "first_success.csv",
                             "objects.csv", "report.md"}) {
      const std::string expected = readText(before / name / file);
      ASSERT_FALSE(expected.empty()) << before / name / file;
      EXPECT_EQ(readText(dir.path() / file), expected) << name << "/" << file;
    }
    for (const char* file : {"success.csv", "comparisons.csv", "robust.csv"}) {
      EXPECT_FALSE(std::filesystem::exists(dir.path() / file)) << file;
    }
  }
}

/// The two hand-worked scenes of intervals_test.cpp with the default options: every estimate
/// shows its interval, which is [S2 alone, S1 alone] (or the reverse) there.
class ReportIntervalsTest : public ::testing::Test {
 protected:
  void SetUp() override { writeReport({test_runs::twoSceneRun()}, dir.path()); }
  test::TempDir dir;
};

TEST_F(ReportIntervalsTest, CsvHasEachIntervalAfterItsEstimate) {
  const std::string first = readText(dir.path() / "first_success.csv");
  EXPECT_EQ(first.substr(0, first.find('\n')),
            "group,method,scenes,scenes_with_success,p,p_ci_low,p_ci_high,ga,ga_ci_low,ga_ci_high,"
            "ga_randomized,ga_given_order,ga_given_order_ci_low,ga_given_order_ci_high,paper_p,"
            "paper_ga");
  // ga = (5/3 + 2) / 2, interval [5/3, 2]; given order 1.5 in [1, 2].
  EXPECT_NE(first.find("\noverall,M,2,2,1,1,1,1.8333333333333335,1.6666666666666667,2,"),
            std::string::npos)
      << first;
  const std::string quality = readText(dir.path() / "quality.csv");
  EXPECT_EQ(quality.substr(0, quality.find('\n')),
            "group,method,successes,mean_q_lift,mean_q_lift_ci_low,mean_q_lift_ci_high,"
            "mean_q_gws,mean_q_gws_ci_low,mean_q_gws_ci_high,paper_q_lift,paper_q_gws,"
            "mean_q_gws_unit,mean_q_gws_unit_ci_low,mean_q_gws_unit_ci_high");
  const std::string distribution = readText(dir.path() / "distribution.csv");
  EXPECT_NE(distribution.find(",share_stable,share_stable_ci_low,share_stable_ci_high,"),
            std::string::npos);
  EXPECT_NE(distribution.find(",share_no_grasp,share_no_grasp_ci_low,share_no_grasp_ci_high\n"),
            std::string::npos);
  const std::string attempts = readText(dir.path() / "attempts.csv");
  EXPECT_EQ(attempts.substr(0, attempts.find('\n')),
            "group,method,attempts,exact,exact_ci_low,exact_ci_high,randomized");
  // n = 2: (5/6 + 2/3) / 2 = 0.75 in [2/3, 5/6] (1 - 1/3 and 1 - 1/6 in doubles).
  EXPECT_NE(attempts.find("\noverall,M,2,0.75,0.6666666666666667,0.8333333333333334,"),
            std::string::npos)
      << attempts;
  const std::string objects = readText(dir.path() / "objects.csv");
  EXPECT_NE(objects.find(",grasps,successes,percent,percent_ci_low,percent_ci_high,"
                         "successes_first,successes_second\n"),
            std::string::npos);
  EXPECT_NE(objects.find("\ntextured,M,single,5,cocacola,standing,4,2,50,50,50,,\n"),
            std::string::npos)
      << objects;
  const std::string success = readText(dir.path() / "success.csv");
  EXPECT_NE(success.find("\noverall,M,2,7,3,0.42857142857142855,0.3333333333333333,0.5\n"),
            std::string::npos)
      << success;
}

TEST_F(ReportIntervalsTest, MarkdownAndHtmlShowTheIntervalBesideTheNumber) {
  const std::string md = readText(dir.path() / "report.md");
  EXPECT_NE(md.find("Intervals: 95 % percentile intervals of a scene bootstrap (2000 resamples, "
                    "seed 20120601)"),
            std::string::npos);
  EXPECT_NE(md.find("\n## Overall success rate\n"), std::string::npos);
  EXPECT_NE(md.find("| overall | M | 2 | 7 | 3 | 0.429 [0.333, 0.500] |"), std::string::npos) << md;
  EXPECT_NE(md.find("| overall | M | 1.00 [1.00, 1.00] | 1.83 [1.67, 2.00] | 1."),
            std::string::npos);
  EXPECT_NE(md.find("| overall | M | 3 | 0.60 [0.40, 0.70] | 0.40 [0.30, 0.60] |"),
            std::string::npos);
  EXPECT_NE(md.find("| 5 cocacola | 50 % [50, 50] | – |"), std::string::npos);
  // One column: nothing to compare.
  EXPECT_EQ(md.find("Method against method"), std::string::npos);
  const std::string html = readText(dir.path() / "report.html");
  EXPECT_EQ(checkWellFormed(html), "");
  EXPECT_NE(html.find("<td>0.429 [0.333, 0.500]</td>"), std::string::npos);
  // Figure 7's band: n = 1..4 along the upper ends, back along the lower ones.
  EXPECT_NE(html.find("<polygon points=\""), std::string::npos);
  EXPECT_NE(html.find("class=\"band\"><title>M (95 % interval)</title></polygon>"),
            std::string::npos);
}

/// Runs read from folders that had not finished (analysed on request) are named at the top of
/// both reports; finished runs add nothing.
TEST(ReportUnfinishedTest, TheReportsNameTheRunsThatHadNotFinished) {
  results::RunResults a = test_runs::runA();
  results::RunResults b = test_runs::runB();
  const auto reportOf = [](const std::vector<results::RunResults>& runs) {
    test::TempDir dir;
    writeReport(runs, dir.path(), withoutIntervals());
    return std::make_pair(readText(dir.path() / "report.md"), readText(dir.path() / "report.html"));
  };
  EXPECT_EQ(reportOf({a, b}).first.find("Unfinished"), std::string::npos);
  b.finished = false;
  const auto [md, html] = reportOf({a, b});
  EXPECT_EQ(md.find("# VisGraB results\n\n**Unfinished: run \"runB\" has not finished (stopped, "
                    "killed or failed, or still running; analysed with --allow-unfinished): its "
                    "figures cover only the trials finished so far.**\n"),
            0u);
  EXPECT_NE(html.find("<h1>VisGraB results</h1>\n<p><strong>Unfinished: run &quot;runB&quot; has "
                      "not finished"),
            std::string::npos);
  a.finished = false;
  EXPECT_NE(reportOf({a, b}).first.find(
                "**Unfinished: runs \"runA\" and \"runB\" have not finished (stopped, killed or "
                "failed, or still running; analysed with --allow-unfinished): their figures"),
            std::string::npos);
}

TEST(ReportLevelTest, TheLevelIsWrittenAsPercent) {
  EXPECT_EQ(detail::levelText(0.95), "95");
  EXPECT_EQ(detail::levelText(0.9), "90");
  EXPECT_EQ(detail::levelText(0.995), "99.5");
}

}  // namespace
}  // namespace visgrab::analysis
