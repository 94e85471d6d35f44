#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/database/scene_set.hpp"

/// The VisGraB paper's baseline results (its Tables 1 and 2), shown beside ours in the report.
/// Data: docs/paper-tables.csv, compiled in; the caveats: docs/paper-comparison.md.
namespace visgrab::analysis {

/// Which of the paper's tables a value comes from.
enum class PaperTable {
  /// Table 1: mean Q_l and Q_GWS of the successful trials.
  kQuality = 1,
  /// Table 2: proportion p of scenes with a successful grasp, mean attempts ga until it.
  kFirstSuccess = 2,
};

/// One cell pair of the paper's tables: a row (condition group) and a grasp type.
struct PaperEntry {
  /// The table.
  PaperTable table = PaperTable::kQuality;
  /// The table's background (textured / plain = the paper's "non-textured").
  database::Texture texture = database::Texture::kTextured;
  /// The row as a conditionGroups() key, e.g. "textured-single-standing".
  std::string group;
  /// The paper's grasp type: "s2EGA1", "s2EGA3" or "s3EGA1".
  std::string method;
  /// Table 1: {Q_l, Q_GWS}; Table 2: {p, ga}.
  std::array<double, 2> values{};
};

/// Parses text in the format of docs/paper-tables.csv: '#' comment lines, the header
/// "table,texture,group,method,q_lift,q_gws,p,ga", then one entry per line (Table 1 entries fill
/// q_lift and q_gws, Table 2 entries p and ga; the other two fields empty). Checks that the group
/// is one of the paper's rows of that texture (single/double, not "all" of a table or
/// "overall"), that values are in range (p, Q in [0, 1], ga >= 1) and that no entry repeats.
/// @throws std::invalid_argument naming `source`:LINE and what is wrong.
std::vector<PaperEntry> parsePaperTables(std::string_view text,
                                         std::string_view source = "paper-tables.csv");

/// The paper's Tables 1 and 2 (docs/paper-tables.csv as compiled in; 72 entries), parsed once.
/// @throws std::logic_error if the compiled-in table is malformed (a build of a bad edit; the
/// analysis tests catch it).
const std::vector<PaperEntry>& paperTables();

/// True if the paper reports a method of this name (s2EGA1, s2EGA3, s3EGA1; case-sensitive).
bool isPaperMethod(std::string_view method);

/// The paper's value pair (PaperEntry::values) for a table, group key and method; nullopt where
/// the paper has none (another method name, a table's "all" row, "overall").
std::optional<std::array<double, 2>> paperValues(PaperTable table, std::string_view group,
                                                 std::string_view method);

/// The sentence under a table with paper columns that says what they are.
std::string paperColumnsNote(PaperTable table);

/// The note under Table 1 on its two Q_GWS columns (docs/report.md gives the definitions). It
/// does not mention the paper: paperColumnsNote() says which column the paper's compares with.
inline constexpr std::string_view kQualityColumnsNote =
    "Q_GWS: friction cones centred on the measured contact forces and scaled by them, a grasp "
    "with fewer than 4 contacts getting a jittered copy of each (as VisGraB's original simulator "
    "computed its tables). Q_GWS,unit: unit normal forces on the contact normals (RobWork's "
    "GraspTaskSimulator; this project's Q_GWS before). Both: 10 cone edges, torques over the "
    "object's largest radius. '–' where a successful trial lacks the value (trials written "
    "before Q_GWS,unit existed have no Q_GWS).";

/// The "Comparing with the paper" note (docs/paper-comparison.md as compiled in).
struct PaperComparisonNote {
  /// The heading (the file's "# " line, without the "# ").
  std::string heading;
  /// The paragraphs, each on one line (the file's lines joined by spaces).
  std::vector<std::string> paragraphs;
};

/// Parses docs/paper-comparison.md: a first line "# <heading>", then plain-text paragraphs
/// separated by blank lines. @throws std::invalid_argument if the heading or any paragraph is
/// missing.
PaperComparisonNote parsePaperComparisonNote(std::string_view text);

/// The compiled-in note, parsed once. @throws std::logic_error if it is malformed.
const PaperComparisonNote& paperComparisonNote();

}  // namespace visgrab::analysis
