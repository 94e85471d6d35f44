#pragma once

// Moved to rw/loaders/xml/xml_tree.hpp (public: the dynamic workcell loader shares it). The names
// stay available in rw::loaders::detail for the workcell loader's sources.
#include "rw/loaders/xml/xml_tree.hpp"

namespace rw::loaders::detail {

using xml::trimXmlSpace;
using xml::XmlAttribute;
using xml::XmlElement;

}  // namespace rw::loaders::detail
