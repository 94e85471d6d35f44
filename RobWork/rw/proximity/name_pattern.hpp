#pragma once

#include <memory>
#include <string>

namespace rw::proximity {

/// A frame-name pattern of a proximity rule (reference §1.8): `*` matches any sequence, `?` one
/// character, everything else itself; a pattern starting with "REGEX" is an ECMAScript regular
/// expression (the rest of the text). The whole name must match. Immutable; thread-safe.
class NamePattern {
 public:
  /// Compiles `pattern`. @throws std::invalid_argument if a REGEX pattern does not compile.
  explicit NamePattern(const std::string& pattern);
  /// True when `name` matches.
  bool matches(const std::string& name) const;
  /// The pattern as given.
  const std::string& text() const { return text_; }

 private:
  struct Compiled;
  std::string text_;
  std::shared_ptr<const Compiled> compiled_;
};

}  // namespace rw::proximity
