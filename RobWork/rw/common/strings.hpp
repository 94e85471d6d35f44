#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rw::common {

/// `text` with &, <, > and " escaped for XML element text and attribute values.
std::string escapeXml(std::string_view text);

/// Levenshtein distance between two strings (for "did you mean" suggestions in messages).
std::size_t editDistance(std::string_view a, std::string_view b);

/// The candidate closest to `wanted` by editDistance if it is close enough to be a misspelling
/// (at most max(2, |wanted| / 4) edits; the first of equally close ones), or an empty view.
std::string_view closestMatch(std::string_view wanted, const std::vector<std::string>& candidates);

/// 64-bit FNV-1a offset basis: the state of fnv1a before any byte.
inline constexpr std::uint64_t kFnv1aBasis = 0xcbf29ce484222325ULL;

/// 64-bit FNV-1a of `bytes`, continuing from `state` (kFnv1aBasis for a fresh hash): a stable
/// hash for seeds and file fingerprints (the same on every platform and run).
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t state = kFnv1aBasis);

/// `value` as 16 lower-case hex digits (how file fingerprints are written).
std::string hex64(std::uint64_t value);

/// The parts of `text` between the `separator`s (n separators give n + 1 parts, empty ones too).
std::vector<std::string_view> split(std::string_view text, char separator);

}  // namespace rw::common
