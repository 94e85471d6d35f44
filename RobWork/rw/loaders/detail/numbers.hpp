#pragma once

// Moved to rw/loaders/xml/numbers.hpp (public: the dynamic workcell loader shares it). The names
// stay available in rw::loaders::detail for the workcell loader's sources.
#include "rw/loaders/xml/numbers.hpp"

namespace rw::loaders::detail {

using xml::ParsedNumber;
using xml::parseFiniteNumber;
using xml::parseNumberList;

}  // namespace rw::loaders::detail
