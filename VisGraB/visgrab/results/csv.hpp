#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

/// CSV text as the project's result files use it: RFC 4180 (what `pandas.read_csv(path)` and
/// Python's csv module read with no options).
namespace visgrab::results {

/// `text` as one RFC 4180 field. Quoted when it contains a comma, a double quote, a carriage
/// return or a line feed, when it begins or ends with a space, or when `alwaysQuote`; inside
/// quotes `"` becomes `""` and everything else (line breaks, backslashes) stays as it is, so a
/// field with a line break makes its record span lines.
std::string csvField(std::string_view text, bool alwaysQuote = false);

/// One record: the fields (each through csvField) joined by commas, ending in "\n".
std::string csvRecord(const std::vector<std::string>& fields);

/// Splits one line of RFC 4180 text (without its line break; a quoted field cannot hold one
/// here) into fields, undoing csvField.
/// @throws std::invalid_argument saying what is wrong (unterminated quote, text after a closing
/// quote, a quote inside an unquoted field) and at which 1-based column.
std::vector<std::string> splitCsvLine(std::string_view line);

/// Splits one line of the older result files (trials.csv versions 1 and 2, run.csv version 1),
/// whose quoted fields escaped `\`, line feed and carriage return as `\\`, `\n`, `\r`.
/// @throws std::invalid_argument as splitCsvLine, also for an unknown escape.
std::vector<std::string> splitLegacyCsvLine(std::string_view line);

/// A syntax error in CSV text, located by the record it is in and by its own position.
class CsvSyntaxError : public std::invalid_argument {
 public:
  /// what() is "column C: what" when the error is on the record's first line, "line L, column
  /// C: what" otherwise. Lines and columns are 1-based; `offset` is the byte of the error.
  CsvSyntaxError(int recordLine, int line, int column, std::size_t offset, const std::string& what);
  /// Line where the record with the error starts.
  int recordLine() const { return recordLine_; }
  /// Line of the error itself.
  int line() const { return line_; }
  /// Column of the error in its line.
  int column() const { return column_; }
  /// Byte offset of the error in the text.
  std::size_t offset() const { return offset_; }

 private:
  int recordLine_;
  int line_;
  int column_;
  std::size_t offset_;
};

/// One record of CSV text.
struct CsvRecord {
  /// Its fields, quoting undone.
  std::vector<std::string> fields;
  /// 1-based line where it starts (a quoted line break makes a record span lines).
  int line = 0;
  /// True for an empty line (one empty, unquoted field).
  bool blank = false;
};

/// The complete records of CSV text and where the complete part ends.
struct CsvText {
  /// Every record that ends in an unquoted line break, in order.
  std::vector<CsvRecord> records;
  /// The text does not end in an unquoted line break (a write cut off by a kill): what follows
  /// the last complete record was dropped, whatever it holds.
  bool torn = false;
  /// 1-based line where the dropped record starts (0 when nothing was dropped).
  int tornLine = 0;
  /// Bytes up to and including the line break of the last complete record.
  std::size_t completeBytes = 0;
};

/// Reads RFC 4180 text: records end at an unquoted line feed or CR LF; quoted fields may hold
/// commas, `""` for a quote, and line breaks (kept as they are, CR LF included). Text after the
/// last unquoted line break is torn (see CsvText): an open quote at the end, a record cut in
/// mid-field, or a syntax error with no line break after it.
/// @throws CsvSyntaxError for a quote inside an unquoted field, text after a closing quote or a
/// carriage return outside quotes that is not before a line feed, in a complete record.
CsvText parseCsv(std::string_view text);

/// Shortest text that reads back as exactly `value` ("nan", "inf", "-inf" for non-finite).
std::string formatDouble(double value);

/// Reads a number written by formatDouble (or any decimal). @throws std::invalid_argument.
double parseDouble(std::string_view text);

/// Reads a decimal integer. @throws std::invalid_argument.
int parseInt(std::string_view text);

}  // namespace visgrab::results
