#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rw/common/diagnostic_sink.hpp"

namespace rw::common {

/// One attribute of an element, as written.
struct XmlAttribute {
  /// Attribute name.
  std::string name;
  /// Value after XML attribute normalisation.
  std::string value;
};

/// A light XML element that remembers where it was written (file, line and column of its '<').
struct XmlElement {
  /// Element name.
  std::string name;
  /// Attributes in document order.
  std::vector<XmlAttribute> attributes;
  /// All character data directly inside the element, concatenated.
  std::string text;
  /// Child elements in document order.
  std::vector<XmlElement> children;
  /// Where the start tag begins.
  SourceLocation location;

  /// The attribute's value, or nullptr if absent.
  const std::string* attribute(std::string_view attributeName) const;
  /// True if the attribute is present.
  bool has(std::string_view attributeName) const { return attribute(attributeName) != nullptr; }
  /// The attribute's value, or `fallback` if absent.
  std::string attributeOr(std::string_view attributeName, std::string_view fallback) const;
  /// How messages name the element: `<Frame name="Base">` (the first of the attributes name,
  /// id, file, refjoint that is present), or just `<RPY>`.
  std::string describe() const;
  /// Number of elements in this subtree (itself included).
  std::size_t subtreeSize() const;
};

/// Removes leading and trailing XML whitespace.
std::string_view trimXmlSpace(std::string_view text);

}  // namespace rw::common
