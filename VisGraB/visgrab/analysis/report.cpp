#include "visgrab/analysis/report.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "rw/common/strings.hpp"
#include "visgrab/analysis/detail/format.hpp"
#include "visgrab/analysis/paper_tables.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/results/csv.hpp"

namespace visgrab::analysis {

namespace {

using rwsim::trial::GraspOutcome;
using rwsim::trial::kOutcomeTable;

/// One per outcome, in kOutcomeTable order.
struct OutcomeStyle {
  std::string_view colour;
  std::string_view legend;
};
constexpr std::array<OutcomeStyle, kOutcomeCount> kStyles = {{
    {"#1a9641", "stable grasp"},
    {"#a6d96a", "object slipped"},
    {"#fdae61", "object dropped"},
    {"#2c7bb6", "object missed"},
    {"#d7191c", "in collision"},
    {"#7b3294", "invalid grasp contacts"},
    {"#404040", "simulation failure"},
    {"#8c510a", "time-out"},
}};

std::string csvNumber(double value) {
  return std::isnan(value) ? std::string() : results::formatDouble(value);
}

/// One record of a CSV table (RFC 4180: pandas.read_csv reads the tables with no options).
std::string line(const std::vector<std::string>& fields) { return results::csvRecord(fields); }

std::string subjectName(bool single, std::size_t index) {
  if (single) return std::string(database::objectName(static_cast<int>(index) + 1));
  const database::ObjectPair& p = database::kObjectPairs[index];
  return std::string(database::objectName(p.first)) + "+" +
         std::string(database::objectName(p.second));
}

std::string mdRow(const std::vector<std::string>& cells) {
  std::string text = "|";
  for (const std::string& c : cells) {
    std::string escaped;
    for (const char ch : c) escaped += ch == '|' ? std::string("\\|") : std::string(1, ch);
    text += " " + escaped + " |";
  }
  return text + "\n";
}

std::string mdRule(std::size_t columns) {
  std::string text = "|";
  for (std::size_t i = 0; i < columns; ++i) text += i == 0 ? " --- |" : " ---: |";
  return text + "\n";
}

/// The paper's two values for a group and column: numbers as printed in the paper (2 decimals),
/// or two empty strings where it has none.
std::array<std::string, 2> paperCells(PaperTable table, const std::string& group,
                                      const MethodColumn& column) {
  const auto values = paperValues(table, group, column.method);
  if (!values) return {};
  return {detail::fixed((*values)[0], 2), detail::fixed((*values)[1], 2)};
}

/// The paper's two values as CSV fields (empty where it has none).
std::array<std::string, 2> paperCsvFields(PaperTable table, const std::string& group,
                                          const MethodColumn& column) {
  const auto values = paperValues(table, group, column.method);
  if (!values) return {};
  return {results::formatDouble((*values)[0]), results::formatDouble((*values)[1])};
}

/// Tables 1 and 2 of the Markdown report, with the paper's values beside the methods named like
/// its grasp types, and the note on comparing with the paper.
std::string markdownTables12(const Analysis& a) {
  using detail::fixed;
  const bool paper = std::any_of(a.columns.begin(), a.columns.end(),
                                 [](const MethodColumn& c) { return isPaperMethod(c.method); });
  std::string md = "\n## Grasp quality of the successful grasps (Table 1)\n\n";
  std::vector<std::string> head = {"group", "method", "successes", "Q_lift", "Q_GWS"};
  if (paper) head.insert(head.end(), {"paper Q_lift", "paper Q_GWS"});
  head.emplace_back("Q_GWS,unit");
  md += mdRow(head) + mdRule(head.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const QualityMeans& q = a.results[g][c].quality;
      std::vector<std::string> row = {a.groups[g].name, a.columns[c].label,
                                      std::to_string(q.successes), fixed(q.meanQLift, 2),
                                      fixed(q.meanQGws, 2)};
      if (paper) {
        const auto cells = paperCells(PaperTable::kQuality, a.groups[g].key, a.columns[c]);
        row.insert(row.end(), cells.begin(), cells.end());
      }
      row.push_back(fixed(q.meanQGwsUnit, 2));
      md += mdRow(row);
    }
  }
  md += "\n" + std::string(kQualityColumnsNote) + "\n";
  if (paper) md += "\n" + paperColumnsNote(PaperTable::kQuality) + "\n";
  md +=
      "\n## Scenes with a success and attempts to the first success (Table 2)\n\n"
      "ga: expected attempts under random order, (n+1)/(k+1), averaged over the scenes with "
      "a success.\n\n";
  head = {"group", "method", "p", "ga"};
  if (paper) head.insert(head.end(), {"paper p", "paper ga"});
  head.insert(head.end(), {"ga (randomized)", "ga (given order)"});
  md += mdRow(head) + mdRule(head.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const FirstSuccess& f = a.results[g][c].firstSuccess;
      std::vector<std::string> row = {a.groups[g].name, a.columns[c].label, fixed(f.p, 2),
                                      fixed(f.ga, 2)};
      if (paper) {
        const auto cells = paperCells(PaperTable::kFirstSuccess, a.groups[g].key, a.columns[c]);
        row.insert(row.end(), cells.begin(), cells.end());
      }
      row.insert(row.end(), {fixed(f.gaRandomized, 2), fixed(f.gaGivenOrder, 2)});
      md += mdRow(row);
    }
  }
  if (paper) {
    const PaperComparisonNote& note = paperComparisonNote();
    md += "\n" + paperColumnsNote(PaperTable::kFirstSuccess) + "\n\n### " + note.heading + "\n";
    for (const std::string& paragraph : note.paragraphs) md += "\n" + paragraph + "\n";
  }
  return md;
}

/// The pictures section of the Markdown report (only showcases with a picture).
std::string showcasesMarkdown(const Analysis& a, const std::vector<Showcase>& showcases) {
  std::string md;
  std::size_t column = showcases.size();
  std::string group;
  for (const Showcase& s : showcases) {
    if (s.image.empty()) continue;
    if (md.empty()) {
      md = "\n## Pictures: best, typical and failed grasps\n\nEach trial simulated again and "
           "drawn at its three moments: placed, fingers closed, after lifting (contact forces "
           "as orange arrows).\n";
    }
    if (s.column != column) {
      column = s.column;
      group.clear();
      md += "\n### " + a.columns[column].label + "\n";
    }
    if (s.groupKey != group) {
      group = s.groupKey;
      md += "\n#### " + s.groupName + "\n\n";
    }
    md += "![" + showcaseCaption(s) + "](" + s.image + ")\n\n" + showcaseCaption(s) + "\n\n";
  }
  return md;
}

}  // namespace

std::string_view outcomeColour(GraspOutcome outcome) {
  return kStyles[static_cast<std::size_t>(outcome)].colour;
}

std::string_view outcomeLegend(GraspOutcome outcome) {
  return kStyles[static_cast<std::size_t>(outcome)].legend;
}

std::string escapeHtml(std::string_view text) {
  // XML's four entities, and the apostrophe for attributes quoted with it.
  std::string out;
  for (const char c : rw::common::escapeXml(text)) {
    if (c == '\'') {
      out += "&#39;";
    } else {
      out += c;
    }
  }
  return out;
}

void writeCsvTables(const Analysis& a, const std::filesystem::path& outDir) {
  std::vector<std::string> header = {"group", "method", "scenes", "scenes_without_grasps",
                                     "grasps"};
  for (const auto& info : kOutcomeTable) header.push_back("count_" + std::string(info.name));
  for (const auto& info : kOutcomeTable) header.push_back("share_" + std::string(info.name));
  header.push_back("share_no_grasp");
  std::string distribution = line(header);
  std::string quality = line({"group", "method", "successes", "mean_q_lift", "mean_q_gws",
                              "paper_q_lift", "paper_q_gws", "mean_q_gws_unit"});
  std::string attempts = line({"group", "method", "attempts", "exact", "randomized"});
  std::string first = line({"group", "method", "scenes", "scenes_with_success", "p", "ga",
                            "ga_randomized", "ga_given_order", "paper_p", "paper_ga"});
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const GroupResult& r = a.results[g][c];
      const std::string& key = a.groups[g].key;
      const std::string& label = a.columns[c].label;
      const Distribution& d = r.distribution;
      std::vector<std::string> row = {key, label, std::to_string(d.scenes),
                                      std::to_string(d.scenesWithoutGrasps),
                                      std::to_string(d.grasps)};
      for (const int n : d.counts) row.push_back(std::to_string(n));
      for (const double s : d.share) row.push_back(csvNumber(s));
      row.push_back(csvNumber(d.noGraspShare));
      distribution += line(row);
      const auto paperQuality = paperCsvFields(PaperTable::kQuality, key, a.columns[c]);
      quality += line({key, label, std::to_string(r.quality.successes),
                       csvNumber(r.quality.meanQLift), csvNumber(r.quality.meanQGws),
                       paperQuality[0], paperQuality[1], csvNumber(r.quality.meanQGwsUnit)});
      for (std::size_t n = 0; n < r.attempts.exact.size(); ++n) {
        attempts += line({key, label, std::to_string(n + 1), csvNumber(r.attempts.exact[n]),
                          csvNumber(r.attempts.randomized[n])});
      }
      const FirstSuccess& f = r.firstSuccess;
      const auto paperFirst = paperCsvFields(PaperTable::kFirstSuccess, key, a.columns[c]);
      first += line({key, label, std::to_string(f.scenes), std::to_string(f.scenesWithSuccess),
                     csvNumber(f.p), csvNumber(f.ga), csvNumber(f.gaRandomized),
                     csvNumber(f.gaGivenOrder), paperFirst[0], paperFirst[1]});
    }
  }
  std::string objects = line({"table", "method", "kind", "subject", "name", "arrangement", "grasps",
                              "successes", "percent", "successes_first", "successes_second"});
  for (std::size_t t = 0; t < 2; ++t) {
    const std::string table = t == 0 ? "textured" : "plain";
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const ObjectTable& o = a.objectTables[t][c];
      for (std::size_t i = 0; i < o.single.size(); ++i) {
        for (std::size_t k = 0; k < 2; ++k) {
          const SuccessCount& s = o.single[i][k];
          objects +=
              line({table, a.columns[c].label, "single", std::to_string(i + 1),
                    subjectName(true, i), k == 0 ? "standing" : "lying", std::to_string(s.grasps),
                    std::to_string(s.successes), csvNumber(s.percent()), "", ""});
        }
      }
      for (std::size_t i = 0; i < o.pairs.size(); ++i) {
        for (std::size_t k = 0; k < 2; ++k) {
          const SuccessCount& s = o.pairs[i][k];
          objects += line({table, a.columns[c].label, "double",
                           std::string(1, database::kObjectPairs[i].letter), subjectName(false, i),
                           k == 0 ? "apart" : "close", std::to_string(s.grasps),
                           std::to_string(s.successes), csvNumber(s.percent()),
                           std::to_string(s.byObject[0]), std::to_string(s.byObject[1])});
        }
      }
    }
  }
  database::writeFileAtomically(outDir / "distribution.csv", distribution);
  database::writeFileAtomically(outDir / "quality.csv", quality);
  database::writeFileAtomically(outDir / "attempts.csv", attempts);
  database::writeFileAtomically(outDir / "first_success.csv", first);
  database::writeFileAtomically(outDir / "objects.csv", objects);
}

std::string markdownReport(const Analysis& a, const std::vector<Showcase>& showcases) {
  using detail::fixed;
  using detail::percent;
  std::string md = "# VisGraB results\n\n";
  md +=
      "Definitions: docs/report.md. Success = stable grasp or object slipped. Randomized "
      "trials: " +
      std::to_string(a.options.randomTrials) + ", seed " + std::to_string(a.options.seed) + ".\n\n";
  md += mdRow({"run", "method", "rejected grasps", "closings at the cap"}) + mdRule(4);
  for (const MethodColumn& c : a.columns) {
    md += mdRow(
        {a.runLabels[c.run], c.label, std::to_string(c.rejected), std::to_string(c.closingCapped)});
  }
  // Figure 6.
  md +=
      "\n## Outcome distribution (Figure 6)\n\nScene-weighted shares; \"no grasp\" is the "
      "share of scenes without a suggested grasp.\n\n";
  std::vector<std::string> head = {"group", "method", "scenes", "grasps"};
  for (const auto& info : kOutcomeTable) head.emplace_back(outcomeLegend(info.outcome));
  head.emplace_back("no grasp");
  md += mdRow(head) + mdRule(head.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const Distribution& d = a.results[g][c].distribution;
      std::vector<std::string> row = {a.groups[g].name, a.columns[c].label,
                                      std::to_string(d.scenes), std::to_string(d.grasps)};
      for (const double s : d.share) row.push_back(fixed(s, 3));
      row.push_back(fixed(d.noGraspShare, 3));
      md += mdRow(row);
    }
  }
  md += markdownTables12(a);
  // Figure 7.
  md +=
      "\n## Success rate against attempts (Figure 7)\n\nExact expectation (randomized "
      "estimate in brackets).\n\n";
  head = {"group", "method"};
  for (int n = 1; n <= a.maxAttempts; ++n) head.push_back("n=" + std::to_string(n));
  md += mdRow(head) + mdRule(head.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    for (std::size_t c = 0; c < a.columns.size(); ++c) {
      const AttemptsCurve& curve = a.results[g][c].attempts;
      std::vector<std::string> row = {a.groups[g].name, a.columns[c].label};
      for (std::size_t n = 0; n < curve.exact.size(); ++n) {
        row.push_back(fixed(curve.exact[n], 2) + " (" + fixed(curve.randomized[n], 2) + ")");
      }
      md += mdRow(row);
    }
  }
  // Tables 3 and 4.
  for (std::size_t t = 0; t < 2; ++t) {
    md += std::string("\n## Successful grasps per object, ") +
          (t == 0 ? "textured (Table 3)" : "plain (Table 4)") + "\n\n";
    head = {"object"};
    for (const MethodColumn& c : a.columns) {
      head.push_back(c.label + " s");
      head.push_back(c.label + " l");
    }
    md += mdRow(head) + mdRule(head.size());
    for (std::size_t i = 0; i < database::kObjectCount; ++i) {
      std::vector<std::string> row = {std::to_string(i + 1) + " " + subjectName(true, i)};
      for (std::size_t c = 0; c < a.columns.size(); ++c) {
        for (std::size_t k = 0; k < 2; ++k) {
          row.push_back(percent(a.objectTables[t][c].single[i][k].percent()));
        }
      }
      md += mdRow(row);
    }
    md += "\n";
    head = {"pair"};
    for (const MethodColumn& c : a.columns) {
      head.push_back(c.label + " f");
      head.push_back(c.label + " c");
    }
    md += mdRow(head) + mdRule(head.size());
    for (std::size_t i = 0; i < database::kPairCount; ++i) {
      const database::ObjectPair& p = database::kObjectPairs[i];
      std::vector<std::string> row = {std::string(1, p.letter) + ": " + std::to_string(p.first) +
                                      "-" + std::to_string(p.second)};
      for (std::size_t c = 0; c < a.columns.size(); ++c) {
        for (std::size_t k = 0; k < 2; ++k) {
          const SuccessCount& s = a.objectTables[t][c].pairs[i][k];
          row.push_back(percent(s.percent()) + " (" + percent(s.percentOf(0)) + " / " +
                        percent(s.percentOf(1)) + ")");
        }
      }
      md += mdRow(row);
    }
    md += "\nPairs: total (first object / second object held).\n";
  }
  md += showcasesMarkdown(a, showcases);
  return md;
}

void writeReport(const std::vector<results::RunResults>& runs, const std::filesystem::path& outDir,
                 const AnalysisOptions& options, const ShowcaseDrawer& drawer) {
  const Analysis analysis = analyze(runs, options);
  writeCsvTables(analysis, outDir);
  std::vector<Showcase> showcases;
  if (drawer) {
    showcases = chooseShowcases(analysis, runs);
    drawer(showcases, runs, outDir);
  }
  database::writeFileAtomically(outDir / "report.md", markdownReport(analysis, showcases));
  database::writeFileAtomically(outDir / "report.html", htmlReport(analysis, showcases));
}

}  // namespace visgrab::analysis
