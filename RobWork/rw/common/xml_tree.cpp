#include "rw/common/xml_tree.hpp"

namespace rw::common {

const std::string* XmlElement::attribute(std::string_view attributeName) const {
  for (const XmlAttribute& a : attributes) {
    if (a.name == attributeName) return &a.value;
  }
  return nullptr;
}

std::string XmlElement::attributeOr(std::string_view attributeName,
                                    std::string_view fallback) const {
  const std::string* value = attribute(attributeName);
  return value != nullptr ? *value : std::string(fallback);
}

std::string XmlElement::describe() const {
  for (const char* key : {"name", "id", "file", "refjoint"}) {
    if (const std::string* label = attribute(key)) {
      return "<" + name + " " + key + "=\"" + *label + "\">";
    }
  }
  return "<" + name + ">";
}

std::size_t XmlElement::subtreeSize() const {
  std::size_t n = 1;
  for (const XmlElement& c : children) n += c.subtreeSize();
  return n;
}

std::string_view trimXmlSpace(std::string_view text) {
  constexpr std::string_view kSpace = " \t\r\n";
  const auto first = text.find_first_not_of(kSpace);
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(kSpace);
  return text.substr(first, last - first + 1);
}

}  // namespace rw::common
