#include <algorithm>
#include <array>
#include <string>

#include "visgrab/analysis/detail/format.hpp"
#include "visgrab/analysis/detail/report_tables.hpp"
#include "visgrab/analysis/paper_tables.hpp"
#include "visgrab/analysis/report.hpp"
#include "visgrab/analysis/table.hpp"

namespace visgrab::analysis {

namespace {

using detail::fixed;
using rwsim::trial::GraspOutcome;
using rwsim::trial::kOutcomeTable;

/// Line colours of the compared methods in Figure 7 (cycled).
constexpr std::array<std::string_view, 8> kMethodColours = {
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string_view methodColour(std::size_t column) {
  return kMethodColours[column % kMethodColours.size()];
}

std::string num(double value) { return fixed(value, 1); }

/// Indices into Analysis::groups of one table's rows: single standing .. all (7 rows).
std::array<std::size_t, 7> tableGroups(std::size_t table) {
  std::array<std::size_t, 7> rows{};
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = table * 7 + i;
  return rows;
}

constexpr std::array<std::string_view, 7> kRowNames = {"standing", "lying", "all",       "apart",
                                                       "close",    "all",   "all scenes"};
constexpr std::array<std::string_view, 7> kRowKinds = {"single", "single", "single", "double",
                                                       "double", "double", ""};

std::string methodsLegend(const Analysis& a) {
  std::string html = "<p class=\"legend\">";
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    html +=
        "<span><b>" + std::to_string(c + 1) + "</b> " + escapeHtml(a.columns[c].label) + "</span> ";
  }
  return html + "</p>\n";
}

/// Figure 6 for one table: stacked bars, one cluster per condition row, one bar per method.
std::string distributionSvg(const Analysis& a, std::size_t table) {
  const std::size_t columns = std::max<std::size_t>(a.columns.size(), 1);
  const double barWidth = 16.0;
  const double clusterWidth = static_cast<double>(columns) * (barWidth + 2.0) + 14.0;
  const double left = 44.0;
  const double top = 10.0;
  const double height = 200.0;
  const double width = left + 7.0 * clusterWidth + 10.0;
  const double totalHeight = top + height + 46.0;
  std::string svg = "<svg class=\"plot\" width=\"" + num(width) + "\" height=\"" +
                    num(totalHeight) + "\" viewBox=\"0 0 " + num(width) + " " + num(totalHeight) +
                    "\" role=\"img\">\n";
  svg += "<title>Outcome distribution, " + std::string(table == 0 ? "textured" : "plain") +
         " table</title>\n";
  for (int tick = 0; tick <= 4; ++tick) {
    const double y = top + height - height * tick / 4.0;
    svg += "<line x1=\"" + num(left - 4) + "\" y1=\"" + num(y) + "\" x2=\"" + num(width - 10) +
           "\" y2=\"" + num(y) + "\" class=\"grid\"/>\n";
    svg += "<text x=\"" + num(left - 6) + "\" y=\"" + num(y + 4) + "\" class=\"ytick\">" +
           fixed(tick / 4.0, 2) + "</text>\n";
  }
  const auto rows = tableGroups(table);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double x0 = left + static_cast<double>(r) * clusterWidth + 7.0;
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const Distribution& d = a.results[rows[r]][c].distribution;
      const double x = x0 + static_cast<double>(c) * (barWidth + 2.0);
      double y = top + height;
      auto segment = [&](double share, std::string_view colour, std::string_view name) {
        if (share <= 0.0) return;
        const double h = share * height;
        y -= h;
        svg += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(barWidth) +
               "\" height=\"" + num(h) + "\" fill=\"" + std::string(colour) + "\"><title>" +
               escapeHtml(a.columns[c].label) + ", " + std::string(name) + ": " + fixed(share, 3) +
               "</title></rect>\n";
      };
      for (const auto& info : kOutcomeTable) {
        segment(d.share[static_cast<std::size_t>(info.outcome)], outcomeColour(info.outcome),
                outcomeLegend(info.outcome));
      }
      segment(d.noGraspShare, kNoGraspColour, "no grasp suggested");
      svg += "<text x=\"" + num(x + barWidth / 2) + "\" y=\"" + num(top + height + 12) +
             "\" class=\"xtick\">" + std::to_string(c + 1) + "</text>\n";
    }
    const double mid = x0 + static_cast<double>(a.columns.size()) * (barWidth + 2.0) / 2.0;
    svg += "<text x=\"" + num(mid) + "\" y=\"" + num(top + height + 26) + "\" class=\"xlabel\">" +
           std::string(kRowNames[r]) + "</text>\n";
    if (!kRowKinds[r].empty()) {
      svg += "<text x=\"" + num(mid) + "\" y=\"" + num(top + height + 38) + "\" class=\"xlabel\">" +
             std::string(kRowKinds[r]) + "</text>\n";
    }
  }
  return svg + "</svg>\n";
}

std::string outcomeLegendHtml() {
  std::string html = "<p class=\"legend\">";
  for (const auto& info : kOutcomeTable) {
    html += "<span><i style=\"background:" + std::string(outcomeColour(info.outcome)) + "\"></i>" +
            std::string(outcomeLegend(info.outcome)) + "</span> ";
  }
  html += "<span><i style=\"background:" + std::string(kNoGraspColour) +
          "\"></i>no grasp suggested</span></p>\n";
  return html;
}

/// Figure 7 for one group: success rate against attempts, one line per method (exact expectation)
/// with the randomized trials' estimate as dots.
std::string attemptsSvg(const Analysis& a, std::size_t group) {
  const double left = 44.0;
  const double top = 24.0;
  const double plotWidth = 300.0;
  const double height = 180.0;
  const double width = left + plotWidth + 12.0;
  const double totalHeight = top + height + 36.0;
  const int n = std::max(a.maxAttempts, 1);
  auto xOf = [&](int k) {
    return left + (n == 1 ? plotWidth / 2 : plotWidth * (k - 1) / static_cast<double>(n - 1));
  };
  auto yOf = [&](double v) { return top + height - height * v; };
  std::string svg = "<svg class=\"plot\" width=\"" + num(width) + "\" height=\"" +
                    num(totalHeight) + "\" viewBox=\"0 0 " + num(width) + " " + num(totalHeight) +
                    "\" role=\"img\">\n";
  svg += "<title>Success rate against attempts, " + escapeHtml(a.groups[group].name) + "</title>\n";
  svg += "<text x=\"" + num(left) + "\" y=\"14\" class=\"ptitle\">" +
         escapeHtml(a.groups[group].name) + "</text>\n";
  for (int tick = 0; tick <= 4; ++tick) {
    const double y = yOf(tick / 4.0);
    svg += "<line x1=\"" + num(left) + "\" y1=\"" + num(y) + "\" x2=\"" + num(left + plotWidth) +
           "\" y2=\"" + num(y) + "\" class=\"grid\"/>\n";
    svg += "<text x=\"" + num(left - 6) + "\" y=\"" + num(y + 4) + "\" class=\"ytick\">" +
           fixed(tick / 4.0, 2) + "</text>\n";
  }
  const int step = std::max(1, n / 10);
  for (int k = 1; k <= n; k += step) {
    svg += "<text x=\"" + num(xOf(k)) + "\" y=\"" + num(top + height + 14) + "\" class=\"xtick\">" +
           std::to_string(k) + "</text>\n";
  }
  svg += "<text x=\"" + num(left + plotWidth / 2) + "\" y=\"" + num(top + height + 30) +
         "\" class=\"xlabel\">number of attempts</text>\n";
  // The intervals as bands under the lines.
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    const AttemptsCurve& curve = a.results[group][c].attempts;
    std::string upper;
    std::string lower;
    for (std::size_t k = 0; k < curve.exactCi.size(); ++k) {
      const results::Interval& ci = curve.exactCi[k];
      if (!ci.defined()) continue;
      const std::string x = num(xOf(static_cast<int>(k) + 1));
      upper += (upper.empty() ? "" : " ") + x + "," + num(yOf(ci.high));
      lower = x + "," + num(yOf(ci.low)) + (lower.empty() ? "" : " ") + lower;
    }
    if (upper.empty()) continue;
    svg += "<polygon points=\"" + upper + " " + lower + "\" fill=\"" +
           std::string(methodColour(c)) + "\" class=\"band\"><title>" +
           escapeHtml(a.columns[c].label) + " (" + detail::levelText(a.options.ciLevel) +
           " % interval)</title></polygon>\n";
  }
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    const AttemptsCurve& curve = a.results[group][c].attempts;
    std::string points;
    for (std::size_t k = 0; k < curve.exact.size(); ++k) {
      points += (points.empty() ? "" : " ") + num(xOf(static_cast<int>(k) + 1)) + "," +
                num(yOf(curve.exact[k]));
    }
    const std::string colour(methodColour(c));
    svg += "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + colour +
           "\" stroke-width=\"2\"><title>" + escapeHtml(a.columns[c].label) +
           " (exact)</title></polyline>\n";
    for (std::size_t k = 0; k < curve.randomized.size(); ++k) {
      svg += "<circle cx=\"" + num(xOf(static_cast<int>(k) + 1)) + "\" cy=\"" +
             num(yOf(curve.randomized[k])) + "\" r=\"2.5\" fill=\"" + colour + "\"><title>" +
             escapeHtml(a.columns[c].label) + ", " + std::to_string(k + 1) +
             " attempts: " + fixed(curve.exact[k], 3) + " exact, " + fixed(curve.randomized[k], 3) +
             " randomized</title></circle>\n";
    }
  }
  return svg + "</svg>\n";
}

std::string methodLegendLines(const Analysis& a) {
  std::string html = "<p class=\"legend\">";
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    html += "<span><i style=\"background:" + std::string(methodColour(c)) + "\"></i>" +
            escapeHtml(a.columns[c].label) + "</span> ";
  }
  return html + "(lines: exact expectation" +
         (a.intervals ? "; bands: its " + detail::levelText(a.options.ciLevel) + " % interval"
                      : "") +
         "; dots: randomized trials)</p>\n";
}

bool hasPaperColumns(const Analysis& a) {
  return std::any_of(a.columns.begin(), a.columns.end(),
                     [](const MethodColumn& c) { return isPaperMethod(c.method); });
}

/// The "Comparing with the paper" note (docs/paper-comparison.md) as a heading and paragraphs.
std::string comparisonNoteHtml() {
  const PaperComparisonNote& note = paperComparisonNote();
  std::string html = "<h3>" + escapeHtml(note.heading) + "</h3>\n";
  for (const std::string& paragraph : note.paragraphs) {
    html += "<p class=\"note\">" + escapeHtml(paragraph) + "</p>\n";
  }
  return html;
}

/// A table with its title as an HTML section (`level` heading, note paragraph, table).
std::string htmlSection(const Table& table, const std::string& level = "h2") {
  std::string html = "<" + level + ">" + escapeHtml(table.title) + "</" + level + ">\n";
  if (!table.note.empty()) html += "<p class=\"note\">" + escapeHtml(table.note) + "</p>\n";
  return html + htmlText(table);
}

/// The overall success rates, method against method and the robust rates (each only when it has
/// rows).
std::string statisticsHtml(const Analysis& a) {
  std::string html;
  if (a.intervals) html += htmlSection(detail::successTable(a));
  if (!a.comparisons.empty()) {
    const Table winners = detail::winnersTable(a);
    if (!winners.rows.empty()) {
      html += htmlSection(winners) + "<ul>\n";
      for (const std::string& sentence : detail::comparisonSentences(a)) {
        html += "<li>" + escapeHtml(sentence) + "</li>\n";
      }
      html += "</ul>\n";
    } else {
      html += "<h2>Method against method</h2>\n";
    }
    html += htmlSection(detail::comparisonsTable(a), "h3");
  }
  if (!a.robust.empty()) html += htmlSection(detail::robustTable(a));
  return html;
}

constexpr std::string_view kStyle =
    "body{font-family:sans-serif;margin:1.5em;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0 1.5em}"
    "th,td{border:1px solid #ccc;padding:2px 6px;text-align:right}"
    "thead th{text-align:center}"
    ".legend span{margin-right:1em;white-space:nowrap}"
    ".legend i{display:inline-block;width:0.9em;height:0.9em;margin-right:0.3em;"
    "vertical-align:middle}"
    ".plot{margin:0.3em 1em 0.3em 0}"
    ".grid{stroke:#ddd;stroke-width:1}"
    ".ytick{font-size:10px;text-anchor:end}"
    ".xtick,.xlabel{font-size:10px;text-anchor:middle}"
    ".ptitle{font-size:12px;font-weight:bold}"
    "small{color:#666}"
    ".paper{color:#555;background:#f4f4f4;font-style:italic}"
    "td.text{text-align:left}"
    ".band{opacity:0.18;stroke:none}"
    "summary{cursor:pointer;margin:0.3em 0}"
    ".note{max-width:50em}"
    ".picture{margin:0.5em 0 1.2em}.picture img{max-width:100%;border:1px solid #ccc}"
    ".picture figcaption{font-size:13px;color:#444}";

/// The pictures section (only showcases with a picture).
std::string showcasesHtml(const Analysis& a, const std::vector<Showcase>& showcases) {
  std::string html;
  std::size_t column = showcases.size();
  std::string group;
  for (const Showcase& s : showcases) {
    if (s.image.empty()) continue;
    if (html.empty()) {
      html =
          "<h2>Pictures: best, typical and failed grasps</h2>\n<p>Each trial simulated again and "
          "drawn at its three moments: placed, fingers closed, after lifting (contact forces as "
          "orange arrows). <code>visgrab render --results</code> draws any other.</p>\n";
    }
    if (s.column != column) {
      column = s.column;
      group.clear();
      html += "<h3>" + escapeHtml(a.columns[column].label) + "</h3>\n";
    }
    if (s.groupKey != group) {
      group = s.groupKey;
      html += "<h4>" + escapeHtml(s.groupName) + "</h4>\n";
    }
    html += "<figure class=\"picture\"><img src=\"" + escapeHtml(s.image) + "\" alt=\"" +
            escapeHtml(showcaseCaption(s)) + "\"/><figcaption>" + escapeHtml(showcaseCaption(s)) +
            (s.note.empty() ? "" : " (" + escapeHtml(s.note) + ")") + "</figcaption></figure>\n";
  }
  return html;
}

}  // namespace

std::string htmlReport(const Analysis& a, const std::vector<Showcase>& showcases) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
      "<title>VisGraB results</title>\n<style>" +
      std::string(kStyle) + "</style>\n</head>\n<body>\n<h1>VisGraB results</h1>\n";
  if (const std::string warning = detail::unfinishedSentence(a); !warning.empty()) {
    html += "<p><strong>" + escapeHtml(warning) + "</strong></p>\n";
  }
  html += "<p>Success: stable grasp or object slipped. Randomized trials: " +
          std::to_string(a.options.randomTrials) + ", seed " + std::to_string(a.options.seed) +
          ". " + (a.intervals ? escapeHtml(detail::intervalsSentence(a)) + " " : std::string()) +
          "Definitions: docs/report.md.</p>\n";
  html += htmlText(detail::runsTable(a));
  html += statisticsHtml(a);

  html +=
      "<h2>Figure 6: grasp results</h2>\n<p>Distribution of all grasps over all scenes (each "
      "scene weighted equally); grey: proportion of scenes without a suggested grasp.</p>\n";
  html += outcomeLegendHtml() + methodsLegend(a);
  for (std::size_t t = 0; t < 2; ++t) {
    html += "<figure><figcaption>" + std::string(t == 0 ? "Textured" : "Non-textured (plain)") +
            " background</figcaption>\n" + distributionSvg(a, t) + "</figure>\n";
  }
  html += "<details><summary>The shares as a table</summary>\n" +
          htmlText(detail::distributionTable(a)) + "</details>\n";

  html += "<h2>Table 1: grasp quality of the successful grasps</h2>\n" +
          htmlText(detail::qualityTable(a));
  html += "<p>" + escapeHtml(std::string(kQualityColumnsNote)) + "</p>\n";
  if (hasPaperColumns(a)) {
    html += "<p>" + escapeHtml(paperColumnsNote(PaperTable::kQuality)) + "</p>\n";
  }

  html += "<h2>Figure 7: success rate against the number of attempts</h2>\n" +
          methodLegendLines(a) + "<div>\n";
  for (const std::size_t g :
       {std::size_t{2}, std::size_t{5}, std::size_t{9}, std::size_t{12}, a.groups.size() - 1}) {
    html += attemptsSvg(a, g);
  }
  html += "</div>\n<details><summary>Every group as a table</summary>\n" +
          htmlText(detail::attemptsDisplayTable(a)) + "</details>\n";

  html +=
      "<h2>Table 2: scenes with a successful grasp (p) and attempts until the first success "
      "(ga)</h2>\n<p>ga: expected attempts when the scene's grasps are tried in random order, "
      "(n+1)/(k+1), averaged over the scenes with a success.</p>\n" +
      htmlText(detail::firstSuccessTable(a));
  if (hasPaperColumns(a)) {
    html += "<p>" + escapeHtml(paperColumnsNote(PaperTable::kFirstSuccess)) + "</p>\n" +
            comparisonNoteHtml();
  }

  for (std::size_t t = 0; t < 2; ++t) {
    html += std::string("<h2>Table ") + (t == 0 ? "3" : "4") + ": successful grasps per object, " +
            (t == 0 ? "textured" : "non-textured") +
            " scenes</h2>\n<p>s standing, l lying; f far (apart), c close; pairs: total (first "
            "object / second object held).</p>\n<h3>Single-object scenes</h3>\n" +
            htmlText(detail::objectDisplayTable(a, t, true)) + "<h3>Double-object scenes</h3>\n" +
            htmlText(detail::objectDisplayTable(a, t, false));
  }
  return html + showcasesHtml(a, showcases) + "</body>\n</html>\n";
}

}  // namespace visgrab::analysis
