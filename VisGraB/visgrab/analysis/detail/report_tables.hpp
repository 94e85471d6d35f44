#pragma once

#include <string>
#include <vector>

#include "visgrab/analysis/analysis.hpp"
#include "visgrab/analysis/table.hpp"

/// The report's tables, built once from an Analysis and written by the CSV, Markdown and HTML
/// writers (report.cpp, html_report.cpp).
namespace visgrab::analysis::detail {

/// The runs and their methods: rejected grasps, closings at the cap (display only; HTML numbers
/// the columns as the figures do).
Table runsTable(const Analysis& a);

/// Figure 6 (distribution.csv): counts and scene-weighted shares per group and column.
Table distributionTable(const Analysis& a);

/// Table 1 (quality.csv): mean qualities of the successful grasps, the paper's values beside
/// them (always in CSV; in Markdown and HTML only when a column is named like its grasp types).
Table qualityTable(const Analysis& a);

/// Table 2 (first_success.csv): p, ga and their variants, the paper's values as in Table 1.
Table firstSuccessTable(const Analysis& a);

/// Figure 7 as CSV (attempts.csv): one row per group, column and number of attempts.
Table attemptsTable(const Analysis& a);

/// Figure 7 as Markdown and HTML: one row per group and column, one column per number of
/// attempts (exact expectation, its interval, the randomized estimate as a note).
Table attemptsDisplayTable(const Analysis& a);

/// Tables 3-4 as CSV (objects.csv): one row per table, column, object or pair, arrangement.
Table objectsTable(const Analysis& a);

/// Table 3 (`table` 0) or 4 (1) as Markdown and HTML: objects (single = true) or pairs as rows,
/// two columns (the arrangements) per compared column.
Table objectDisplayTable(const Analysis& a, std::size_t table, bool single);

/// The overall success rates (success.csv): successes among all grasps per group and column.
Table successTable(const Analysis& a);

/// Method against method (comparisons.csv): every compared pair in every group.
Table comparisonsTable(const Analysis& a);

/// The "who beats whom" table of the overall group (display only): each pair ordered so that the
/// first succeeds more often, differences in percentage points.
Table winnersTable(const Analysis& a);

/// One sentence per compared pair of the overall group, e.g. "s3EGA1 succeeds 6.8 points more
/// often than s2EGA1 (95 % CI 5.1 to 8.6).", followed by what differs between their runs.
std::vector<std::string> comparisonSentences(const Analysis& a);

/// The robust rates (robust.csv) of the columns with repeats.
Table robustTable(const Analysis& a);

/// The confidence level in percent as the reports write it: "95", "99.5".
std::string levelText(double level);

/// The sentence on the intervals in the reports' introduction.
std::string intervalsSentence(const Analysis& a);

/// The warning that opens a report of runs that had not finished (empty when all had).
std::string unfinishedSentence(const Analysis& a);

}  // namespace visgrab::analysis::detail
