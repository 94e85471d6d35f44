#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

/// A reader for the part of YAML that OpenCV's cv::FileStorage writes for matrices and numbers,
/// so that a calibration file never reaches OpenCV's own YAML parser (which loops for ever or
/// throws standard exceptions on some malformed input; found by fuzzing). What it reads:
///  - an optional `%YAML:1.0` (or `%YAML 1.0`) line, then an optional `---` line;
///  - comments from a '#' at the start of a line or after a blank, and blank lines;
///  - a block mapping of `key: value` lines, the keys of one mapping at one indentation (spaces;
///    a tab in the indentation is an error); a key is a letter or '_' followed by letters,
///    digits, '_', '-' or '.';
///  - values: a scalar (the rest of the line; "..." quotes allowed), a flow sequence of scalars
///    `[ a, b, ... ]` that may go on over several lines, or a nested block mapping on the lines
///    below, more indented, optionally after a tag such as `!!opencv-matrix`.
/// Everything else (block sequences `- x`, flow mappings `{ }`, nested flow sequences, anchors,
/// several documents) is an error that names the line and what was expected.
namespace visgrab::database::detail {

/// One parsed value.
struct YamlNode {
  enum class Kind { kScalar, kSequence, kMap };
  Kind kind = Kind::kScalar;
  /// 1-based line where the value (or, for a mapping value, its key) starts.
  int line = 0;
  /// The tag without "!!" (e.g. "opencv-matrix"), empty if none.
  std::string tag;
  /// kScalar: the text (quotes removed).
  std::string scalar;
  /// The key of a mapping entry (empty for a sequence item or the top-level mapping).
  std::string key;
  /// kSequence: the items (scalars); kMap: the entries in file order, each with its key.
  std::vector<YamlNode> items;

  /// The entry called `name` of a mapping, or null.
  const YamlNode* find(std::string_view name) const;
  /// The scalar as a number: integers, decimals, exponents, and .nan/.inf/-.inf in any case
  /// (OpenCV writes ".Nan" and ".Inf"); nullopt if it is not one.
  std::optional<double> number() const;
  /// The scalar as an int, nullopt if it is not a decimal integer that fits.
  std::optional<int> integer() const;
};

/// A syntax error: the 1-based line and what was expected.
class YamlError : public std::runtime_error {
 public:
  YamlError(int line, const std::string& what) : std::runtime_error(what), line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

/// Parses `text` into its top-level mapping (an empty mapping for a file of only comments).
/// @throws YamlError.
YamlNode parseOpencvYaml(std::string_view text);

}  // namespace visgrab::database::detail
