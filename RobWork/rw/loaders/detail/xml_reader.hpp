#pragma once

// Moved to rw/loaders/xml/xml_reader.hpp (public: the dynamic workcell loader shares it). The names
// stay available in rw::loaders::detail for the workcell loader's sources.
#include "rw/loaders/xml/xml_reader.hpp"

namespace rw::loaders::detail {

using xml::kFragmentElement;
using xml::kMaxElementDepth;
using xml::XmlReader;
using xml::XmlReaderOptions;

}  // namespace rw::loaders::detail
