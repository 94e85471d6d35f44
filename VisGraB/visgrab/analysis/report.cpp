#include "visgrab/analysis/report.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "rw/common/strings.hpp"
#include "visgrab/analysis/detail/report_tables.hpp"
#include "visgrab/analysis/paper_tables.hpp"
#include "visgrab/analysis/table.hpp"
#include "visgrab/database/atomic_file.hpp"

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

/// A table with its title as a Markdown section: "\n## title\n\n", the note, the table.
std::string markdownSection(const Table& table, const std::string& level = "##") {
  std::string md = "\n" + level + " " + table.title + "\n\n";
  if (!table.note.empty()) md += table.note + "\n\n";
  return md + markdownText(table);
}

/// Tables 1 and 2 of the Markdown report, with the paper's values beside the methods named like
/// its grasp types, and the note on comparing with the paper.
std::string markdownTables12(const Analysis& a) {
  const bool paper = std::any_of(a.columns.begin(), a.columns.end(),
                                 [](const MethodColumn& c) { return isPaperMethod(c.method); });
  std::string md = markdownSection(detail::qualityTable(a));
  md += "\n" + std::string(kQualityColumnsNote) + "\n";
  if (paper) md += "\n" + paperColumnsNote(PaperTable::kQuality) + "\n";
  md += markdownSection(detail::firstSuccessTable(a));
  if (paper) {
    const PaperComparisonNote& note = paperComparisonNote();
    md += "\n" + paperColumnsNote(PaperTable::kFirstSuccess) + "\n\n### " + note.heading + "\n";
    for (const std::string& paragraph : note.paragraphs) md += "\n" + paragraph + "\n";
  }
  return md;
}

/// The sections that come with the intervals and the repeats: overall success rates, method
/// against method, robust rates (each only when it has rows).
std::string markdownStatistics(const Analysis& a) {
  std::string md;
  if (a.intervals) md += markdownSection(detail::successTable(a));
  if (!a.comparisons.empty()) {
    const Table winners = detail::winnersTable(a);
    if (!winners.rows.empty()) {
      md += markdownSection(winners) + "\n";
      for (const std::string& sentence : detail::comparisonSentences(a)) {
        md += "- " + sentence + "\n";
      }
    } else {
      md += "\n## Method against method\n";
    }
    md += markdownSection(detail::comparisonsTable(a), "###");
  }
  if (!a.robust.empty()) md += markdownSection(detail::robustTable(a));
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
  database::writeFileAtomically(outDir / "distribution.csv", csvText(detail::distributionTable(a)));
  database::writeFileAtomically(outDir / "quality.csv", csvText(detail::qualityTable(a)));
  database::writeFileAtomically(outDir / "attempts.csv", csvText(detail::attemptsTable(a)));
  database::writeFileAtomically(outDir / "first_success.csv",
                                csvText(detail::firstSuccessTable(a)));
  database::writeFileAtomically(outDir / "objects.csv", csvText(detail::objectsTable(a)));
  if (a.intervals) {
    database::writeFileAtomically(outDir / "success.csv", csvText(detail::successTable(a)));
    database::writeFileAtomically(outDir / "comparisons.csv", csvText(detail::comparisonsTable(a)));
  }
  if (!a.robust.empty()) {
    database::writeFileAtomically(outDir / "robust.csv", csvText(detail::robustTable(a)));
  }
}

std::string markdownReport(const Analysis& a, const std::vector<Showcase>& showcases) {
  std::string md = "# VisGraB results\n\n";
  if (const std::string warning = detail::unfinishedSentence(a); !warning.empty()) {
    md += "**" + warning + "**\n\n";
  }
  md +=
      "Definitions: docs/report.md. Success = stable grasp or object slipped. Randomized "
      "trials: " +
      std::to_string(a.options.randomTrials) + ", seed " + std::to_string(a.options.seed) + ".";
  if (a.intervals) md += " " + detail::intervalsSentence(a);
  md += "\n\n" + markdownText(detail::runsTable(a));
  md += markdownStatistics(a);
  md += markdownSection(detail::distributionTable(a));
  md += markdownTables12(a);
  md += markdownSection(detail::attemptsDisplayTable(a));
  for (std::size_t t = 0; t < 2; ++t) {
    md += std::string("\n## Successful grasps per object, ") +
          (t == 0 ? "textured (Table 3)" : "plain (Table 4)") + "\n\n";
    md += markdownText(detail::objectDisplayTable(a, t, true)) + "\n";
    md += markdownText(detail::objectDisplayTable(a, t, false));
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
