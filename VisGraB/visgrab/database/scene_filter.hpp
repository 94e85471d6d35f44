#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/database/scene_set.hpp"

namespace visgrab::database {

/// A malformed scene filter; what() names the filter and the offending word.
class FilterError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Selects scenes by their conditions or ids (the CLI's `--scenes FILTER`).
///
/// Syntax: `,` means AND, `;` (or a repeated `--scenes`) means OR, `!` before a term negates it.
/// Terms: `plain` `textured` (`non-textured` = plain), `single` `double`, `standing` `lying`
/// (`laying`), `apart` (`far`) `close` (`touching`), an object name (`cocacola`), `all` or `*`;
/// `object=5|cocacola`, `pair=e`, `pose=3` (1..8), `texture=...`, `kind=...`,
/// `arrangement=...`, `id=GLOB`; a bare term containing `/`, `*` or `?` is an id glob
/// (`*` = any text, `?` = one character). An empty filter selects everything.
/// Example: `textured,single,standing;pair=e,close`.
class SceneFilter {
 public:
  /// The filter that selects every scene.
  SceneFilter() = default;

  /// Parses one filter text. @throws FilterError with a message naming the bad word.
  static SceneFilter parse(std::string_view text);
  /// Parses several filter texts (repeated options) combined with OR; no texts = everything.
  /// @throws FilterError.
  static SceneFilter parse(const std::vector<std::string>& texts);
  /// The same for a database of `catalog`'s objects: object names, ids and pair letters are
  /// that catalog's. @throws FilterError.
  static SceneFilter parse(std::string_view text, const ObjectCatalog& catalog);
  /// The same for several texts. @throws FilterError.
  static SceneFilter parse(const std::vector<std::string>& texts, const ObjectCatalog& catalog);

  /// True if the scene with `id` and `conditions` (null when unknown, e.g. an original
  /// manifest scene whose conditions could not be derived) is selected. Condition terms never
  /// match a scene without conditions; id globs do.
  bool matches(std::string_view id, const SceneConditions* conditions) const;
  /// True if the filter selects everything.
  bool selectsAll() const { return alternatives_.empty(); }
  /// The filter in canonical spelling (aliases resolved), "all" for everything.
  std::string toString() const;

 private:
  struct Term {
    enum class Type { kAll, kTexture, kKind, kArrangement, kObject, kPair, kPose, kIdGlob };
    Type type = Type::kAll;
    bool negated = false;
    int value = 0;
    /// kPair: the pair's object ids, first and second.
    int first = 0;
    int second = 0;
    std::string glob;
  };
  using Conjunction = std::vector<Term>;

  static Term parseTerm(std::string_view term, std::string_view whole,
                        const ObjectCatalog& catalog);
  static bool matchesTerm(const Term& term, std::string_view id, const SceneConditions* c);
  static std::string termToString(const Term& term);

  std::vector<Conjunction> alternatives_;
};

/// True if `text` matches the glob `pattern` (`*` any run of characters, `?` one character).
bool globMatch(std::string_view pattern, std::string_view text);

}  // namespace visgrab::database
