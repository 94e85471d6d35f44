#include "visgrab/analysis/table.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "visgrab/analysis/detail/format.hpp"
#include "visgrab/analysis/report.hpp"
#include "visgrab/results/csv.hpp"

namespace visgrab::analysis {

namespace {

bool isNumeric(CellKind kind) {
  return kind == CellKind::kNumber || kind == CellKind::kEstimate || kind == CellKind::kPaper;
}

bool showsInterval(const TableColumn& column, bool intervals) {
  return intervals && column.kind == CellKind::kEstimate;
}

std::string csvNumber(double value) {
  return std::isnan(value) ? std::string() : results::formatDouble(value);
}

/// A number as Markdown and HTML show it: rounded, with " %" for percentages.
std::string displayNumber(const TableColumn& column, double value) {
  if (std::isnan(value)) return column.kind == CellKind::kPaper ? std::string() : "–";
  const std::string text = detail::fixed(value, column.decimals);
  return column.percent ? text + " %" : text;
}

std::string markdownEscaped(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    if (c == '|') escaped += '\\';
    escaped += c;
  }
  return escaped;
}

std::string markdownLine(const std::vector<std::string>& cells) {
  std::string line = "|";
  for (const std::string& c : cells) line += " " + markdownEscaped(c) + " |";
  return line + "\n";
}

std::string titleAttribute(const std::string& tooltip) {
  return tooltip.empty() ? std::string() : " title=\"" + escapeHtml(tooltip) + "\"";
}

}  // namespace

TableCell textCell(std::string text) {
  TableCell cell;
  cell.text = std::move(text);
  return cell;
}

TableCell integerCell(long long value) {
  TableCell cell;
  cell.text = std::to_string(value);
  return cell;
}

TableCell numberCell(double value) {
  TableCell cell;
  cell.value = value;
  return cell;
}

TableCell estimateCell(double value, results::Interval interval) {
  TableCell cell;
  cell.value = value;
  cell.interval = interval;
  return cell;
}

void Table::addRow(std::vector<TableCell> cells) {
  if (cells.size() != columns.size()) {
    throw std::logic_error("table '" + title + "': a row of " + std::to_string(cells.size()) +
                           " cells for " + std::to_string(columns.size()) + " columns");
  }
  rows.push_back(std::move(cells));
}

std::string displayText(const TableColumn& column, const TableCell& cell, bool intervals) {
  std::string text = isNumeric(column.kind) ? displayNumber(column, cell.value) : cell.text;
  if (showsInterval(column, intervals) && !std::isnan(cell.value) && cell.interval.defined()) {
    // "[low, high]" in the column's decimals; a percentage's ends without the unit.
    text += " [" + detail::fixed(cell.interval.low, column.decimals) + ", " +
            detail::fixed(cell.interval.high, column.decimals) + "]";
  }
  if (!cell.note.empty()) text += " (" + cell.note + ")";
  return text;
}

std::string csvText(const Table& table) {
  std::vector<std::string> names;
  for (const TableColumn& c : table.columns) {
    if ((c.formats & kCsvFormat) == 0U) continue;
    names.push_back(c.name);
    if (showsInterval(c, table.intervals)) {
      names.push_back(c.name + "_ci_low");
      names.push_back(c.name + "_ci_high");
    }
  }
  std::string csv = results::csvRecord(names);
  for (const std::vector<TableCell>& row : table.rows) {
    std::vector<std::string> fields;
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      const TableColumn& c = table.columns[i];
      if ((c.formats & kCsvFormat) == 0U) continue;
      const TableCell& cell = row[i];
      fields.push_back(isNumeric(c.kind) ? csvNumber(cell.value) : cell.text);
      if (showsInterval(c, table.intervals)) {
        // An interval is shown only with its estimate.
        const bool defined = !std::isnan(cell.value) && cell.interval.defined();
        fields.push_back(defined ? csvNumber(cell.interval.low) : std::string());
        fields.push_back(defined ? csvNumber(cell.interval.high) : std::string());
      }
    }
    csv += results::csvRecord(fields);
  }
  return csv;
}

std::string markdownText(const Table& table) {
  std::vector<std::string> head;
  for (const TableColumn& c : table.columns) {
    if ((c.formats & kMarkdownFormat) != 0U) head.push_back(c.heading);
  }
  std::string md = markdownLine(head) + "|";
  for (std::size_t i = 0; i < head.size(); ++i) md += i == 0 ? " --- |" : " ---: |";
  md += "\n";
  for (const std::vector<TableCell>& row : table.rows) {
    std::vector<std::string> cells;
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      const TableColumn& c = table.columns[i];
      if ((c.formats & kMarkdownFormat) != 0U) {
        cells.push_back(displayText(c, row[i], table.intervals));
      }
    }
    md += markdownLine(cells);
  }
  return md;
}

std::string htmlText(const Table& table) {
  std::string html = "<table>\n<thead><tr>";
  for (const TableColumn& c : table.columns) {
    if ((c.formats & kHtmlFormat) == 0U) continue;
    const std::string cls = c.kind == CellKind::kPaper ? " class=\"paper\"" : "";
    html += "<th" + cls + titleAttribute(c.tooltip) + ">" +
            (c.htmlHeading.empty() ? escapeHtml(c.heading) : c.htmlHeading) + "</th>";
  }
  html += "</tr></thead>\n<tbody>\n";
  for (const std::vector<TableCell>& row : table.rows) {
    html += "<tr>";
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
      const TableColumn& c = table.columns[i];
      if ((c.formats & kHtmlFormat) == 0U) continue;
      const TableCell& cell = row[i];
      std::string cls;
      if (c.kind == CellKind::kPaper) cls = " class=\"paper\"";
      if (c.kind == CellKind::kText) cls = " class=\"text\"";
      TableCell shown = cell;
      shown.note.clear();
      std::string text = escapeHtml(displayText(c, shown, table.intervals));
      if (!cell.note.empty()) text += " <small>(" + escapeHtml(cell.note) + ")</small>";
      html += "<td" + cls + titleAttribute(cell.tooltip) + ">" + text + "</td>";
    }
    html += "</tr>\n";
  }
  return html + "</tbody>\n</table>\n";
}

}  // namespace visgrab::analysis
