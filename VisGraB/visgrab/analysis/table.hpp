#pragma once

#include <limits>
#include <string>
#include <vector>

#include "visgrab/results/statistics.hpp"

/// One table model for every table of the report: built once from the analyses, written as CSV
/// (exact numbers, one column per value and interval end), as a Markdown table and as an HTML
/// table (rounded numbers, the interval beside its estimate). A column added here reaches all
/// three formats.
namespace visgrab::analysis {

/// What a column holds, which decides how each format writes its cells.
enum class CellKind {
  /// Text, written as it is (CSV quoted where needed, '|' escaped in Markdown, HTML escaped).
  kText,
  /// An integer (TableCell::text holds its digits).
  kInteger,
  /// A number without an interval: CSV its shortest round-trip text, Markdown and HTML
  /// `decimals` fixed; undefined (NaN) is an empty CSV field and '–' elsewhere.
  kNumber,
  /// An estimate with its confidence interval: like kNumber, and when the table shows intervals
  /// CSV has two more columns right after it, `<name>_ci_low` and `<name>_ci_high`, and Markdown
  /// and HTML write "0.64 [0.61, 0.67]".
  kEstimate,
  /// A value from the paper: like kNumber, but an empty cell where the paper has none, and grey
  /// italic in HTML.
  kPaper,
};

/// The formats a column appears in (bits of TableColumn::formats).
enum TableFormat : unsigned {
  /// The CSV file.
  kCsvFormat = 1U,
  /// report.md.
  kMarkdownFormat = 2U,
  /// report.html.
  kHtmlFormat = 4U,
};

/// Markdown and HTML.
inline constexpr unsigned kDisplayFormats = kMarkdownFormat | kHtmlFormat;
/// Every format.
inline constexpr unsigned kAllFormats = kCsvFormat | kDisplayFormats;

/// One column of a Table.
struct TableColumn {
  /// Name in the CSV column line.
  std::string name;
  /// Heading in Markdown and HTML (plain text).
  std::string heading;
  /// What the cells hold.
  CellKind kind = CellKind::kText;
  /// Decimals of numbers in Markdown and HTML.
  int decimals = 2;
  /// Markdown and HTML write numbers as percentages: "50 %" (the value is already in percent).
  bool percent = false;
  /// The formats it appears in (TableFormat bits).
  unsigned formats = kAllFormats;
  /// The heading as HTML markup (e.g. "Q<sub>lift</sub>"); empty: the heading, escaped.
  std::string htmlHeading;
  /// The HTML heading's tooltip (title attribute); may be empty.
  std::string tooltip;
};

/// A NaN, the undefined value of a number cell.
inline constexpr double kUndefinedValue = std::numeric_limits<double>::quiet_NaN();

/// An interval with both ends undefined.
inline constexpr results::Interval kUndefinedInterval{kUndefinedValue, kUndefinedValue};

/// One cell; which fields count depends on its column's kind.
struct TableCell {
  /// kText: the text; kInteger: the digits.
  std::string text;
  /// kNumber, kEstimate, kPaper: the value (NaN: undefined).
  double value = kUndefinedValue;
  /// kEstimate: the interval (undefined ends: none shown).
  results::Interval interval = kUndefinedInterval;
  /// Markdown and HTML: a remark after the value, in parentheses (e.g. the randomized estimate).
  std::string note;
  /// HTML: the cell's tooltip (title attribute); may be empty.
  std::string tooltip;
};

/// A text cell.
TableCell textCell(std::string text);
/// An integer cell.
TableCell integerCell(long long value);
/// A number cell (kNumber or kPaper columns).
TableCell numberCell(double value);
/// An estimate cell with its interval.
TableCell estimateCell(double value, results::Interval interval);

/// A table: columns and rows of cells (one per column, in column order).
struct Table {
  /// The table's heading in the reports (the report writes it).
  std::string title;
  /// The paragraph under the heading; may be empty.
  std::string note;
  /// The columns.
  std::vector<TableColumn> columns;
  /// The rows.
  std::vector<std::vector<TableCell>> rows;
  /// Estimates show their intervals (kEstimate): off when no interval was computed, and then no
  /// interval column appears anywhere.
  bool intervals = false;
  /// Appends a row. @throws std::logic_error unless it has one cell per column.
  void addRow(std::vector<TableCell> cells);
};

/// The table as a CSV file: the column line, then one record per row (RFC 4180 as
/// results::csvRecord writes it), its kCsvFormat columns only.
std::string csvText(const Table& table);

/// The table as Markdown: the heading line, the rule (first column left-aligned, the others
/// right-aligned), one line per row; its kMarkdownFormat columns only. No title or note.
std::string markdownText(const Table& table);

/// The table as an HTML <table> element (one line per row); its kHtmlFormat columns only. No
/// title or note.
std::string htmlText(const Table& table);

/// What Markdown and HTML show for one cell of `column` (plain text, before any escaping): the
/// rounded value, its interval when the table shows intervals, the note in parentheses.
std::string displayText(const TableColumn& column, const TableCell& cell, bool intervals);

}  // namespace visgrab::analysis
