#include "visgrab/analysis/paper_tables.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "visgrab/analysis/analysis.hpp"
#include "visgrab/analysis/detail/paper_data.hpp"
#include "visgrab/results/csv.hpp"

namespace visgrab::analysis {

namespace {

/// The paper's grasp types (its section 4), as method names.
constexpr std::array<std::string_view, 3> kPaperMethods = {"s2EGA1", "s2EGA3", "s3EGA1"};

constexpr std::string_view kPaperTablesHeader = "table,texture,group,method,q_lift,q_gws,p,ga";

/// The text's lines without their line breaks (a trailing '\r' removed).
std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> out;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view l = text.substr(0, end);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    out.push_back(l);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
  }
  return out;
}

/// Reads one value; `what` names the column.
double parseValue(const std::string& field, std::string_view what) {
  double v = 0.0;
  try {
    v = results::parseDouble(field);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(std::string(what) + " '" + field + "' is not a number");
  }
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(what) + " is not finite");
  return v;
}

PaperEntry parsePaperEntry(const std::vector<std::string>& f) {
  if (f.size() != 8) {
    throw std::invalid_argument("expected 8 fields, found " + std::to_string(f.size()));
  }
  PaperEntry e;
  if (f[0] == "1") {
    e.table = PaperTable::kQuality;
  } else if (f[0] == "2") {
    e.table = PaperTable::kFirstSuccess;
  } else {
    throw std::invalid_argument("table '" + f[0] + "' is neither 1 nor 2");
  }
  const auto texture = database::textureFromString(f[1]);
  if (!texture) throw std::invalid_argument("unknown texture '" + f[1] + "'");
  e.texture = *texture;
  const auto groups = conditionGroups();
  const auto group = std::find_if(groups.begin(), groups.end(),
                                  [&](const ConditionGroup& g) { return g.key == f[2]; });
  if (group == groups.end() || !group->kind || group->texture != e.texture) {
    throw std::invalid_argument("group '" + f[2] + "' is not a row of the paper's " + f[1] +
                                " table");
  }
  e.group = f[2];
  if (!isPaperMethod(f[3])) throw std::invalid_argument("unknown grasp type '" + f[3] + "'");
  e.method = f[3];
  const bool quality = e.table == PaperTable::kQuality;
  const std::size_t used = quality ? 4 : 6;
  const std::size_t unused = quality ? 6 : 4;
  if (!f[unused].empty() || !f[unused + 1].empty()) {
    throw std::invalid_argument(std::string("table ") + f[0] + " has no " +
                                (quality ? "p, ga" : "q_lift, q_gws") + " values");
  }
  e.values = {parseValue(f[used], quality ? "q_lift" : "p"),
              parseValue(f[used + 1], quality ? "q_gws" : "ga")};
  const bool firstOk = e.values[0] >= 0.0 && e.values[0] <= 1.0;
  const bool secondOk = quality ? e.values[1] >= 0.0 && e.values[1] <= 1.0 : e.values[1] >= 1.0;
  if (!firstOk || !secondOk) {
    throw std::invalid_argument(quality ? "q_lift and q_gws must be in [0, 1]"
                                        : "p must be in [0, 1] and ga >= 1");
  }
  return e;
}

}  // namespace

std::vector<PaperEntry> parsePaperTables(std::string_view text, std::string_view source) {
  std::vector<PaperEntry> entries;
  bool header = false;
  const std::vector<std::string_view> all = splitLines(text);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const std::string_view l = all[i];
    const std::string where = std::string(source) + ":" + std::to_string(i + 1) + ": ";
    if (l.empty() || l.front() == '#') continue;
    if (!header) {
      if (l != kPaperTablesHeader) {
        throw std::invalid_argument(where + "expected the header '" +
                                    std::string(kPaperTablesHeader) + "'");
      }
      header = true;
      continue;
    }
    try {
      PaperEntry e = parsePaperEntry(results::splitCsvLine(l));
      const bool repeated = std::any_of(entries.begin(), entries.end(), [&](const PaperEntry& o) {
        return o.table == e.table && o.group == e.group && o.method == e.method;
      });
      if (repeated) throw std::invalid_argument("repeats table, group and method of an entry");
      entries.push_back(std::move(e));
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(where + error.what());
    }
  }
  if (!header) throw std::invalid_argument(std::string(source) + ": no header line");
  return entries;
}

const std::vector<PaperEntry>& paperTables() {
  static const std::vector<PaperEntry> kEntries = [] {
    try {
      return parsePaperTables(detail::paperTablesCsv(), "docs/paper-tables.csv");
    } catch (const std::invalid_argument& error) {
      throw std::logic_error(std::string("compiled-in ") + error.what());
    }
  }();
  return kEntries;
}

bool isPaperMethod(std::string_view method) {
  return std::find(kPaperMethods.begin(), kPaperMethods.end(), method) != kPaperMethods.end();
}

std::optional<std::array<double, 2>> paperValues(PaperTable table, std::string_view group,
                                                 std::string_view method) {
  for (const PaperEntry& e : paperTables()) {
    if (e.table == table && e.group == group && e.method == method) return e.values;
  }
  return std::nullopt;
}

std::string paperColumnsNote(PaperTable table) {
  const bool quality = table == PaperTable::kQuality;
  return std::string(quality ? "paper Q_lift, paper Q_GWS: the paper's Table 1 (its Q_l, Q_GWS; "
                               "compare with Q_GWS, not Q_GWS,unit)"
                             : "paper p, paper ga: the paper's Table 2") +
         " for its grasp type of the same name (docs/paper-tables.csv); empty for other methods "
         "and for rows the paper does not have.";
}

PaperComparisonNote parsePaperComparisonNote(std::string_view text) {
  const std::vector<std::string_view> all = splitLines(text);
  if (all.empty() || all[0].substr(0, 2) != "# " || all[0].size() == 2) {
    throw std::invalid_argument("paper comparison note: the first line must be '# <heading>'");
  }
  PaperComparisonNote note;
  note.heading = std::string(all[0].substr(2));
  std::string paragraph;
  for (std::size_t i = 1; i <= all.size(); ++i) {
    if (i == all.size() || all[i].empty()) {
      if (!paragraph.empty()) note.paragraphs.push_back(std::move(paragraph));
      paragraph.clear();
      continue;
    }
    paragraph += (paragraph.empty() ? "" : " ") + std::string(all[i]);
  }
  if (note.paragraphs.empty()) {
    throw std::invalid_argument("paper comparison note: no paragraph after the heading");
  }
  return note;
}

const PaperComparisonNote& paperComparisonNote() {
  static const PaperComparisonNote kNote = [] {
    try {
      return parsePaperComparisonNote(detail::paperComparisonMarkdown());
    } catch (const std::invalid_argument& error) {
      throw std::logic_error(std::string("compiled-in ") + error.what());
    }
  }();
  return kNote;
}

}  // namespace visgrab::analysis
