#include "visgrab/analysis/table.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace visgrab::analysis {
namespace {

/// A table with one column of each kind, and one only in HTML: two rows, one with the undefined
/// values.
Table sampleTable(bool intervals) {
  Table t;
  t.title = "sample";
  t.intervals = intervals;
  TableColumn name;
  name.name = "name";
  name.heading = "name";
  TableColumn count;
  count.name = "count";
  count.heading = "count";
  count.kind = CellKind::kInteger;
  TableColumn rate;
  rate.name = "rate";
  rate.heading = "rate";
  rate.kind = CellKind::kEstimate;
  rate.decimals = 2;
  rate.htmlHeading = "r<sub>1</sub>";
  TableColumn share;
  share.name = "share";
  share.heading = "share";
  share.kind = CellKind::kEstimate;
  share.decimals = 0;
  share.percent = true;
  share.formats = kDisplayFormats;
  TableColumn paper;
  paper.name = "paper";
  paper.heading = "paper";
  paper.kind = CellKind::kPaper;
  TableColumn plain;
  plain.name = "plain";
  plain.heading = "plain";
  plain.kind = CellKind::kNumber;
  plain.decimals = 3;
  plain.formats = kCsvFormat | kHtmlFormat;
  plain.tooltip = "a <plain> number";
  t.columns = {name, count, rate, share, paper, plain};
  TableCell shareCell = estimateCell(33.3, {10.0, 60.4});
  shareCell.note = "0 % / 33 %";
  shareCell.tooltip = "1 of 3";
  t.addRow({textCell("a|b, \"c\""), integerCell(12), estimateCell(0.6375, {0.61, 0.665}), shareCell,
            numberCell(0.84), numberCell(1.0 / 3.0)});
  t.addRow({textCell("x<&>"), integerCell(-3), estimateCell(kUndefinedValue, {0.1, 0.2}),
            estimateCell(50.0, kUndefinedInterval), numberCell(kUndefinedValue),
            numberCell(kUndefinedValue)});
  return t;
}

TEST(TableTest, CsvPutsEachIntervalRightAfterItsEstimate) {
  EXPECT_EQ(csvText(sampleTable(true)),
            "name,count,rate,rate_ci_low,rate_ci_high,paper,plain\n"
            "\"a|b, \"\"c\"\"\",12,0.6375,0.61,0.665,0.84,0.3333333333333333\n"
            // An undefined estimate has no interval; undefined values are empty fields.
            "x<&>,-3,,,,,\n");
}

TEST(TableTest, WithoutIntervalsNoIntervalColumnAppears) {
  EXPECT_EQ(csvText(sampleTable(false)),
            "name,count,rate,paper,plain\n"
            "\"a|b, \"\"c\"\"\",12,0.6375,0.84,0.3333333333333333\n"
            "x<&>,-3,,,\n");
  const std::string md = markdownText(sampleTable(false));
  EXPECT_NE(md.find("| a\\|b, \"c\" | 12 | 0.64 | 33 % (0 % / 33 %) | 0.84 |\n"), std::string::npos)
      << md;
}

TEST(TableTest, MarkdownShowsTheIntervalBesideTheNumber) {
  EXPECT_EQ(markdownText(sampleTable(true)),
            "| name | count | rate | share | paper |\n"
            "| --- | ---: | ---: | ---: | ---: |\n"
            "| a\\|b, \"c\" | 12 | 0.64 [0.61, 0.67] | 33 % [10, 60] (0 % / 33 %) | 0.84 |\n"
            // Undefined: '–' for our numbers, empty for the paper's, no interval without both
            // ends.
            "| x<&> | -3 | – | 50 % |  |\n");
}

TEST(TableTest, HtmlEscapesAndMarksThePapersColumns) {
  EXPECT_EQ(htmlText(sampleTable(true)),
            "<table>\n<thead><tr><th>name</th><th>count</th><th>r<sub>1</sub></th>"
            "<th>share</th><th class=\"paper\">paper</th>"
            "<th title=\"a &lt;plain&gt; number\">plain</th></tr></thead>\n<tbody>\n"
            "<tr><td class=\"text\">a|b, &quot;c&quot;</td><td>12</td>"
            "<td>0.64 [0.61, 0.67]</td>"
            "<td title=\"1 of 3\">33 % [10, 60] <small>(0 % / 33 %)</small></td>"
            "<td class=\"paper\">0.84</td><td>0.333</td></tr>\n"
            "<tr><td class=\"text\">x&lt;&amp;&gt;</td><td>-3</td><td>–</td><td>50 %</td>"
            "<td class=\"paper\"></td><td>–</td></tr>\n"
            "</tbody>\n</table>\n");
}

TEST(TableTest, ARowMustHaveOneCellPerColumn) {
  Table t = sampleTable(true);
  EXPECT_THROW(t.addRow({textCell("short")}), std::logic_error);
}

}  // namespace
}  // namespace visgrab::analysis
