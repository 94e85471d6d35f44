#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rwsim::loaders::detail {

/// A position in a text: 1-based line and column (columns count UTF-8 characters, as Xerces).
struct TextPosition {
  /// Line.
  int line = 0;
  /// Column.
  int column = 0;
};

/// One closing tag rewritten to the name of the element it closes.
struct TagRepair {
  /// Where the closing tag's '<' is.
  TextPosition where;
  /// The name written in the closing tag.
  std::string written;
  /// The name of the element it closes (what it was rewritten to).
  std::string closes;
};

/// The outcome of repairClosingTags.
struct TagRepairResult {
  /// The text with every mismatched closing tag renamed; lines are unchanged.
  std::string text;
  /// The repairs in document order.
  std::vector<TagRepair> repairs;
  /// An element still open at the end of the text (the innermost one) and where it started.
  std::optional<std::pair<std::string, TextPosition>> unclosed;
};

/// Reproduces RobWork's lenient reading of dynamic workcell files (reference §2.1): any closing
/// tag closes the innermost open element. A small tokenizer (comments, CDATA sections,
/// processing instructions and quoted attribute values, '>' inside them included, are skipped)
/// renames each closing tag whose name differs from the innermost open element's to that name.
/// A closing tag with no open element is left for the XML parser to reject. On markup it does
/// not understand (a DOCTYPE, an unterminated comment, a '<' without a name) it stops repairing
/// and leaves the rest unchanged for the XML parser to report; `unclosed` is then not set.
TagRepairResult repairClosingTags(std::string_view text);

/// A character XML does not allow, found before parsing.
struct CharacterProblem {
  /// Where it is.
  TextPosition where;
  /// What is wrong, e.g. "byte 0x02 is not allowed in XML".
  std::string message;
};

/// Finds the first byte that is not valid UTF-8 or is a control character XML 1.0 forbids
/// (everything below 0x20 except tab, line feed and carriage return), so that binary input is
/// reported at its line and column. Texts that declare another encoding or start with a UTF-16
/// byte order mark are left to the XML parser (nullopt).
std::optional<CharacterProblem> findInvalidCharacter(std::string_view text);

}  // namespace rwsim::loaders::detail
