#include "visgrab/analysis/detail/report_tables.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "visgrab/analysis/detail/format.hpp"
#include "visgrab/analysis/paper_tables.hpp"
#include "visgrab/analysis/report.hpp"

namespace visgrab::analysis::detail {

namespace {

using rwsim::trial::kOutcomeTable;

/// A column of `kind` with `decimals` in Markdown and HTML.
TableColumn numberColumn(std::string name, std::string heading, CellKind kind, int decimals,
                         unsigned formats = kAllFormats) {
  TableColumn column;
  column.name = std::move(name);
  column.heading = std::move(heading);
  column.kind = kind;
  column.decimals = decimals;
  column.formats = formats;
  return column;
}

/// A text column.
TableColumn textColumn(std::string name, std::string heading, unsigned formats = kAllFormats) {
  return numberColumn(std::move(name), std::move(heading), CellKind::kText, 0, formats);
}

/// An integer column.
TableColumn integerColumn(std::string name, std::string heading, unsigned formats = kAllFormats) {
  return numberColumn(std::move(name), std::move(heading), CellKind::kInteger, 0, formats);
}

/// The first columns of a per-group table: the group's key (CSV) or name (Markdown, HTML) and
/// the column's label.
void addGroupColumns(Table& t, const std::string& method = "method") {
  t.columns.push_back(textColumn("group", "", kCsvFormat));
  t.columns.push_back(textColumn("", "group", kDisplayFormats));
  t.columns.push_back(textColumn(method, method));
}

std::vector<TableCell> groupCells(const Analysis& a, std::size_t g, std::size_t c) {
  return {textCell(a.groups[g].key), textCell(a.groups[g].name), textCell(a.columns[c].label)};
}

bool hasPaperColumns(const Analysis& a) {
  return std::any_of(a.columns.begin(), a.columns.end(),
                     [](const MethodColumn& c) { return isPaperMethod(c.method); });
}

/// The paper's two values for a group and column (undefined where it has none).
std::array<TableCell, 2> paperCells(PaperTable table, const std::string& group,
                                    const MethodColumn& column) {
  const auto values = paperValues(table, group, column.method);
  if (!values) return {numberCell(kUndefinedValue), numberCell(kUndefinedValue)};
  return {numberCell((*values)[0]), numberCell((*values)[1])};
}

std::string subjectName(bool single, std::size_t index) {
  if (single) return std::string(database::objectName(static_cast<int>(index) + 1));
  const database::ObjectPair& p = database::kObjectPairs[index];
  return std::string(database::objectName(p.first)) + "+" +
         std::string(database::objectName(p.second));
}

/// `interval` scaled by `factor`, its ends swapped when the factor is negative (a zero end stays
/// +0, never "-0.0").
results::Interval scaled(const results::Interval& interval, double factor) {
  const double low = interval.low * factor + 0.0;
  const double high = interval.high * factor + 0.0;
  return factor < 0 ? results::Interval{high, low} : results::Interval{low, high};
}

/// The overall group's comparisons with a defined difference, each oriented so that its first
/// column succeeds at least as often (a tie keeps the column order).
struct Oriented {
  const Comparison* comparison = nullptr;
  std::size_t better = 0;
  std::size_t worse = 0;
  double sign = 1.0;  // +1: better = A
};

std::vector<Oriented> overallComparisons(const Analysis& a) {
  std::vector<Oriented> out;
  for (const Comparison& c : a.comparisons) {
    if (a.groups[c.group].key != "overall" || std::isnan(c.rate.difference)) continue;
    const bool swap = c.rate.difference < 0.0;
    out.push_back(
        {&c, swap ? c.columnB : c.columnA, swap ? c.columnA : c.columnB, swap ? -1.0 : 1.0});
  }
  return out;
}

std::string joined(const std::vector<std::string>& items, const std::string& last) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) text += i + 1 == items.size() ? last : ", ";
    text += items[i];
  }
  return text;
}

}  // namespace

std::string levelText(double level) {
  std::string text = fixed(100.0 * level, 2);
  while (text.back() == '0') text.pop_back();
  if (text.back() == '.') text.pop_back();
  return text;
}

std::string intervalsSentence(const Analysis& a) {
  return "Intervals: " + levelText(a.options.ciLevel) + " % percentile intervals of a scene " +
         "bootstrap (" + std::to_string(a.options.bootstrapResamples) + " resamples, seed " +
         std::to_string(a.options.bootstrapSeed) +
         "), written \"estimate [low, high]\"; comparisons: paired bootstrap and paired "
         "permutation test (" +
         std::to_string(a.options.permutations) + " permutations).";
}

std::string unfinishedSentence(const Analysis& a) {
  const std::vector<std::string>& runs = a.unfinishedRuns;
  if (runs.empty()) return "";
  // "a", "a" and "b", "a", "b" and "c".
  std::string names = "\"" + runs.front() + "\"";
  for (std::size_t i = 1; i < runs.size(); ++i) {
    names += std::string(i + 1 == runs.size() ? " and " : ", ") + "\"" + runs[i] + "\"";
  }
  const bool one = runs.size() == 1;
  return std::string("Unfinished: ") + (one ? "run " : "runs ") + names + (one ? " has" : " have") +
         " not finished (stopped, killed or failed, or still running; analysed with "
         "--allow-unfinished): " +
         (one ? "its" : "their") + " figures cover only the trials finished so far.";
}

Table runsTable(const Analysis& a) {
  Table t;
  t.columns = {integerColumn("", "#", kHtmlFormat), textColumn("", "run", kDisplayFormats),
               textColumn("", "method", kDisplayFormats),
               integerColumn("", "rejected grasps", kDisplayFormats),
               integerColumn("", "closings at the cap", kDisplayFormats)};
  t.columns.back().tooltip =
      "trials whose closing ran into the closing cap before the fingers came to rest";
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    const MethodColumn& m = a.columns[c];
    t.addRow({integerCell(static_cast<long long>(c) + 1), textCell(a.runLabels[m.run]),
              textCell(m.label), integerCell(m.rejected), integerCell(m.closingCapped)});
  }
  return t;
}

Table distributionTable(const Analysis& a) {
  Table t;
  t.title = "Outcome distribution (Figure 6)";
  t.note = "Scene-weighted shares; \"no grasp\" is the share of scenes without a suggested grasp.";
  t.intervals = a.intervals;
  addGroupColumns(t);
  t.columns.push_back(integerColumn("scenes", "scenes"));
  t.columns.push_back(integerColumn("scenes_without_grasps", "", kCsvFormat));
  t.columns.push_back(integerColumn("grasps", "grasps"));
  for (const auto& info : kOutcomeTable) {
    t.columns.push_back(integerColumn("count_" + std::string(info.name), "", kCsvFormat));
  }
  for (const auto& info : kOutcomeTable) {
    t.columns.push_back(numberColumn("share_" + std::string(info.name),
                                     std::string(outcomeLegend(info.outcome)), CellKind::kEstimate,
                                     3));
  }
  t.columns.push_back(numberColumn("share_no_grasp", "no grasp", CellKind::kEstimate, 3));
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const Distribution& d = a.results[g][c].distribution;
      std::vector<TableCell> row = groupCells(a, g, c);
      row.insert(row.end(), {integerCell(d.scenes), integerCell(d.scenesWithoutGrasps),
                             integerCell(d.grasps)});
      for (const int n : d.counts) row.push_back(integerCell(n));
      for (std::size_t o = 0; o < kOutcomeCount; ++o) {
        row.push_back(estimateCell(d.share[o], d.shareCi[o]));
      }
      row.push_back(estimateCell(d.noGraspShare, d.noGraspShareCi));
      t.addRow(std::move(row));
    }
  }
  return t;
}

Table qualityTable(const Analysis& a) {
  const unsigned paper = hasPaperColumns(a) ? kAllFormats : kCsvFormat;
  Table t;
  t.title = "Grasp quality of the successful grasps (Table 1)";
  t.intervals = a.intervals;
  addGroupColumns(t);
  t.columns.push_back(integerColumn("successes", "successes"));
  t.columns.push_back(numberColumn("mean_q_lift", "Q_lift", CellKind::kEstimate, 2));
  t.columns.back().htmlHeading = "Q<sub>lift</sub>";
  t.columns.push_back(numberColumn("mean_q_gws", "Q_GWS", CellKind::kEstimate, 2));
  t.columns.back().htmlHeading = "Q<sub>GWS</sub>";
  t.columns.push_back(numberColumn("paper_q_lift", "paper Q_lift", CellKind::kPaper, 2, paper));
  t.columns.back().htmlHeading = "paper Q<sub>lift</sub>";
  t.columns.push_back(numberColumn("paper_q_gws", "paper Q_GWS", CellKind::kPaper, 2, paper));
  t.columns.back().htmlHeading = "paper Q<sub>GWS</sub>";
  t.columns.push_back(numberColumn("mean_q_gws_unit", "Q_GWS,unit", CellKind::kEstimate, 2));
  t.columns.back().htmlHeading = "Q<sub>GWS,unit</sub>";
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const QualityMeans& q = a.results[g][c].quality;
      const auto p = paperCells(PaperTable::kQuality, a.groups[g].key, a.columns[c]);
      std::vector<TableCell> row = groupCells(a, g, c);
      row.insert(row.end(), {integerCell(q.successes), estimateCell(q.meanQLift, q.meanQLiftCi),
                             estimateCell(q.meanQGws, q.meanQGwsCi), p[0], p[1],
                             estimateCell(q.meanQGwsUnit, q.meanQGwsUnitCi)});
      t.addRow(std::move(row));
    }
  }
  return t;
}

Table firstSuccessTable(const Analysis& a) {
  // The paper's columns come right after p and ga in Markdown and HTML, at the end in CSV (where
  // they were first added): the same cells under two columns each.
  const unsigned paper = hasPaperColumns(a) ? kDisplayFormats : 0U;
  Table t;
  t.title = "Scenes with a success and attempts to the first success (Table 2)";
  t.note =
      "ga: expected attempts under random order, (n+1)/(k+1), averaged over the scenes with a "
      "success.";
  t.intervals = a.intervals;
  addGroupColumns(t);
  t.columns.push_back(integerColumn("scenes", "scenes", kCsvFormat));
  t.columns.push_back(integerColumn("scenes_with_success", "", kCsvFormat));
  t.columns.push_back(numberColumn("p", "p", CellKind::kEstimate, 2));
  t.columns.push_back(numberColumn("ga", "ga", CellKind::kEstimate, 2));
  t.columns.push_back(numberColumn("", "paper p", CellKind::kPaper, 2, paper));
  t.columns.push_back(numberColumn("", "paper ga", CellKind::kPaper, 2, paper));
  t.columns.push_back(numberColumn("ga_randomized", "ga (randomized)", CellKind::kNumber, 2));
  t.columns.push_back(numberColumn("ga_given_order", "ga (given order)", CellKind::kEstimate, 2));
  t.columns.push_back(numberColumn("paper_p", "", CellKind::kPaper, 2, kCsvFormat));
  t.columns.push_back(numberColumn("paper_ga", "", CellKind::kPaper, 2, kCsvFormat));
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const FirstSuccess& f = a.results[g][c].firstSuccess;
      const auto p = paperCells(PaperTable::kFirstSuccess, a.groups[g].key, a.columns[c]);
      std::vector<TableCell> row = groupCells(a, g, c);
      row.insert(row.end(),
                 {integerCell(f.scenes), integerCell(f.scenesWithSuccess), estimateCell(f.p, f.pCi),
                  estimateCell(f.ga, f.gaCi), p[0], p[1], numberCell(f.gaRandomized),
                  estimateCell(f.gaGivenOrder, f.gaGivenOrderCi), p[0], p[1]});
      t.addRow(std::move(row));
    }
  }
  return t;
}

Table attemptsTable(const Analysis& a) {
  Table t;
  t.intervals = a.intervals;
  t.columns = {textColumn("group", "group"), textColumn("method", "method"),
               integerColumn("attempts", "attempts"),
               numberColumn("exact", "exact", CellKind::kEstimate, 2),
               numberColumn("randomized", "randomized", CellKind::kNumber, 2)};
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const AttemptsCurve& curve = a.results[g][c].attempts;
      for (std::size_t n = 0; n < curve.exact.size(); ++n) {
        const results::Interval ci =
            n < curve.exactCi.size() ? curve.exactCi[n] : kUndefinedInterval;
        t.addRow({textCell(a.groups[g].key), textCell(a.columns[c].label),
                  integerCell(static_cast<long long>(n) + 1), estimateCell(curve.exact[n], ci),
                  numberCell(curve.randomized[n])});
      }
    }
  }
  return t;
}

Table attemptsDisplayTable(const Analysis& a) {
  Table t;
  t.title = "Success rate against attempts (Figure 7)";
  t.note = a.intervals ? "Exact expectation with its interval in square brackets (randomized "
                         "estimate in parentheses)."
                       : "Exact expectation (randomized estimate in brackets).";
  t.intervals = a.intervals;
  t.columns = {textColumn("", "group", kDisplayFormats), textColumn("", "method", kDisplayFormats)};
  for (int n = 1; n <= a.maxAttempts; ++n) {
    t.columns.push_back(
        numberColumn("", "n=" + std::to_string(n), CellKind::kEstimate, 2, kDisplayFormats));
  }
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const AttemptsCurve& curve = a.results[g][c].attempts;
      std::vector<TableCell> row = {textCell(a.groups[g].name), textCell(a.columns[c].label)};
      for (std::size_t n = 0; n < static_cast<std::size_t>(a.maxAttempts); ++n) {
        if (n >= curve.exact.size()) {
          row.push_back(textCell(""));
          continue;
        }
        TableCell cell = estimateCell(
            curve.exact[n], n < curve.exactCi.size() ? curve.exactCi[n] : kUndefinedInterval);
        cell.note = fixed(curve.randomized[n], 2);
        row.push_back(std::move(cell));
      }
      t.addRow(std::move(row));
    }
  }
  return t;
}

Table objectsTable(const Analysis& a) {
  Table t;
  t.intervals = a.intervals;
  t.columns = {textColumn("table", "table"),
               textColumn("method", "method"),
               textColumn("kind", "kind"),
               textColumn("subject", "subject"),
               textColumn("name", "name"),
               textColumn("arrangement", "arrangement"),
               integerColumn("grasps", "grasps"),
               integerColumn("successes", "successes"),
               numberColumn("percent", "percent", CellKind::kEstimate, 0),
               integerColumn("successes_first", "successes first"),
               integerColumn("successes_second", "successes second")};
  for (std::size_t table = 0; table < 2; ++table) {
    const std::string name = table == 0 ? "textured" : "plain";
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const ObjectTable& o = a.objectTables[table][c];
      for (std::size_t i = 0; i < o.single.size(); ++i) {
        for (std::size_t k = 0; k < 2; ++k) {
          const SuccessCount& s = o.single[i][k];
          t.addRow({textCell(name), textCell(a.columns[c].label), textCell("single"),
                    textCell(std::to_string(i + 1)), textCell(subjectName(true, i)),
                    textCell(k == 0 ? "standing" : "lying"), integerCell(s.grasps),
                    integerCell(s.successes), estimateCell(s.percent(), s.percentCi), textCell(""),
                    textCell("")});
        }
      }
      for (std::size_t i = 0; i < o.pairs.size(); ++i) {
        for (std::size_t k = 0; k < 2; ++k) {
          const SuccessCount& s = o.pairs[i][k];
          t.addRow({textCell(name), textCell(a.columns[c].label), textCell("double"),
                    textCell(std::string(1, database::kObjectPairs[i].letter)),
                    textCell(subjectName(false, i)), textCell(k == 0 ? "apart" : "close"),
                    integerCell(s.grasps), integerCell(s.successes),
                    estimateCell(s.percent(), s.percentCi), integerCell(s.byObject[0]),
                    integerCell(s.byObject[1])});
        }
      }
    }
  }
  return t;
}

Table objectDisplayTable(const Analysis& a, std::size_t table, bool single) {
  Table t;
  t.intervals = a.intervals;
  t.columns.push_back(textColumn("", single ? "object" : "pair", kDisplayFormats));
  for (const MethodColumn& c : a.columns) {
    for (const char* arrangement : single ? std::array{" s", " l"} : std::array{" f", " c"}) {
      TableColumn column =
          numberColumn("", c.label + arrangement, CellKind::kEstimate, 0, kDisplayFormats);
      column.percent = true;
      t.columns.push_back(std::move(column));
    }
  }
  const std::size_t rows = single ? database::kObjectCount : database::kPairCount;
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<TableCell> row;
    if (single) {
      row.push_back(textCell(std::to_string(i + 1) + " " + subjectName(true, i)));
    } else {
      const database::ObjectPair& p = database::kObjectPairs[i];
      row.push_back(textCell(std::string(1, p.letter) + ": " + std::to_string(p.first) + "-" +
                             std::to_string(p.second)));
    }
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      for (std::size_t k = 0; k < 2; ++k) {
        const ObjectTable& o = a.objectTables[table][c];
        const SuccessCount& s = single ? o.single[i][k] : o.pairs[i][k];
        TableCell cell = estimateCell(s.percent(), s.percentCi);
        cell.tooltip = std::to_string(s.successes) + " of " + std::to_string(s.grasps);
        if (!single) cell.note = percent(s.percentOf(0)) + " / " + percent(s.percentOf(1));
        row.push_back(std::move(cell));
      }
    }
    t.addRow(std::move(row));
  }
  return t;
}

Table successTable(const Analysis& a) {
  Table t;
  t.title = "Overall success rate";
  t.note =
      "Successful grasps (stable or slipped) among all grasps of the group's scenes, pooled over "
      "the grasps.";
  t.intervals = a.intervals;
  addGroupColumns(t);
  t.columns.push_back(integerColumn("scenes", "scenes"));
  t.columns.push_back(integerColumn("grasps", "grasps"));
  t.columns.push_back(integerColumn("successes", "successes"));
  t.columns.push_back(numberColumn("success_rate", "success rate", CellKind::kEstimate, 3));
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const GroupResult& r = a.results[g][c];
      std::vector<TableCell> row = groupCells(a, g, c);
      row.insert(row.end(), {integerCell(r.distribution.scenes), integerCell(r.success.grasps),
                             integerCell(r.success.successes),
                             estimateCell(r.success.rate, r.success.rateCi)});
      t.addRow(std::move(row));
    }
  }
  return t;
}

Table comparisonsTable(const Analysis& a) {
  Table t;
  t.title = "Every group";
  t.note =
      "A and B on the scenes both were run on: success rate (pooled over the grasps) and p "
      "(share of scenes with a success), each with A - B, its paired bootstrap interval and the "
      "paired permutation test's p-value.";
  t.intervals = a.intervals;
  t.columns = {textColumn("group", "", kCsvFormat),
               textColumn("", "group", kDisplayFormats),
               textColumn("method_a", "A"),
               textColumn("method_b", "B"),
               integerColumn("scenes", "scenes"),
               numberColumn("rate_a", "rate A", CellKind::kNumber, 3),
               numberColumn("rate_b", "rate B", CellKind::kNumber, 3),
               numberColumn("difference", "rate A - B", CellKind::kEstimate, 3),
               numberColumn("p_value", "p-value", CellKind::kNumber, 4),
               numberColumn("p_a", "p A", CellKind::kNumber, 3),
               numberColumn("p_b", "p B", CellKind::kNumber, 3),
               numberColumn("p_difference", "p A - B", CellKind::kEstimate, 3),
               numberColumn("p_difference_p_value", "p-value", CellKind::kNumber, 4),
               textColumn("run_differences", "runs differ in")};
  for (const Comparison& c : a.comparisons) {
    t.addRow({textCell(a.groups[c.group].key), textCell(a.groups[c.group].name),
              textCell(a.columns[c.columnA].label), textCell(a.columns[c.columnB].label),
              integerCell(c.scenes), numberCell(c.rate.a), numberCell(c.rate.b),
              estimateCell(c.rate.difference, c.rate.differenceCi), numberCell(c.rate.pValue),
              numberCell(c.p.a), numberCell(c.p.b), estimateCell(c.p.difference, c.p.differenceCi),
              numberCell(c.p.pValue), textCell(joined(c.runDifferences, ", "))});
  }
  return t;
}

Table winnersTable(const Analysis& a) {
  Table t;
  t.title = "Method against method";
  t.note =
      "All scenes (overall): each pair of methods on the scenes both were run on, the one "
      "that succeeds more often first; differences in percentage points with their " +
      levelText(a.options.ciLevel) +
      " % paired bootstrap intervals, p from the paired permutation test; \"yes\" where the "
      "interval excludes 0 and the permutation test agrees (p below 1 - the level): with few "
      "shared scenes a bootstrap interval can exclude 0 where the test cannot.";
  t.intervals = a.intervals;
  t.columns = {
      textColumn("", "better", kDisplayFormats),
      textColumn("", "worse", kDisplayFormats),
      integerColumn("", "scenes", kDisplayFormats),
      numberColumn("", "success rate, points", CellKind::kEstimate, 1, kDisplayFormats),
      numberColumn("", "p-value", CellKind::kNumber, 4, kDisplayFormats),
      textColumn("", "excludes 0", kDisplayFormats),
      numberColumn("", "scenes with a success, points", CellKind::kEstimate, 1, kDisplayFormats),
      numberColumn("", "p-value", CellKind::kNumber, 4, kDisplayFormats),
      textColumn("", "excludes 0", kDisplayFormats),
      textColumn("", "runs differ in", kDisplayFormats)};
  // Both tools must agree: a bootstrap over a handful of scenes is degenerate (every resample the
  // same) or too narrow where the exact permutation test is not.
  const double alpha = 1.0 - a.options.ciLevel;
  const auto excludesZero = [alpha](const results::Interval& i, double pValue) {
    return i.defined() && (i.low > 0.0 || i.high < 0.0) && pValue < alpha ? "yes" : "no";
  };
  for (const Oriented& o : overallComparisons(a)) {
    const Comparison& c = *o.comparison;
    const double f = 100.0 * o.sign;
    t.addRow({textCell(a.columns[o.better].label), textCell(a.columns[o.worse].label),
              integerCell(c.scenes),
              estimateCell(f * c.rate.difference + 0.0, scaled(c.rate.differenceCi, f)),
              numberCell(c.rate.pValue), textCell(excludesZero(c.rate.differenceCi, c.rate.pValue)),
              estimateCell(f * c.p.difference + 0.0, scaled(c.p.differenceCi, f)),
              numberCell(c.p.pValue), textCell(excludesZero(c.p.differenceCi, c.p.pValue)),
              textCell(joined(c.runDifferences, ", "))});
  }
  return t;
}

std::vector<std::string> comparisonSentences(const Analysis& a) {
  std::vector<std::string> out;
  const std::string level = levelText(a.options.ciLevel) + " % CI ";
  for (const Oriented& o : overallComparisons(a)) {
    const Comparison& c = *o.comparison;
    const double f = 100.0 * o.sign;
    const results::Interval ci = scaled(c.rate.differenceCi, f);
    const std::string better = a.columns[o.better].label;
    const std::string worse = a.columns[o.worse].label;
    const std::string interval = "(" + level + fixed(ci.low, 1) + " to " + fixed(ci.high, 1) + ")";
    const double points = f * c.rate.difference;
    std::string sentence =
        std::abs(points) < 0.05  // "0.0" points
            ? better + " and " + worse + " succeed equally often " + interval + "."
            : better + " succeeds " + fixed(points, 1) + " points more often than " + worse + " " +
                  interval + ".";
    if (!c.runDifferences.empty()) {
      sentence += " Their runs differ in " + joined(c.runDifferences, " and ") + ".";
    }
    out.push_back(std::move(sentence));
  }
  return out;
}

Table robustTable(const Analysis& a) {
  Table t;
  t.title = "Robust success over repeats";
  t.note =
      "Each grasp's P(success) = held trials / trials over its repeats (the unperturbed one "
      "included); the robust rate is the mean of P over the grasps, borderline grasps have "
      "0 < P < 1.";
  t.intervals = a.intervals;
  addGroupColumns(t);
  t.columns.push_back(integerColumn("grasps", "grasps"));
  t.columns.push_back(integerColumn("trials", "trials"));
  t.columns.push_back(numberColumn("robust_rate", "robust success rate", CellKind::kEstimate, 3));
  t.columns.push_back(numberColumn("borderline_share", "borderline share", CellKind::kEstimate, 3));
  for (const RobustRate& r : a.robust) {
    std::vector<TableCell> row = groupCells(a, r.group, r.column);
    row.insert(row.end(),
               {integerCell(r.grasps), integerCell(r.trials), estimateCell(r.rate, r.rateCi),
                estimateCell(r.borderlineShare, r.borderlineShareCi)});
    t.addRow(std::move(row));
  }
  return t;
}

}  // namespace visgrab::analysis::detail
