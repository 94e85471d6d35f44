#pragma once

#include <string_view>

namespace rw::loaders::detail {

/// The text of xml/workcell.xsd, embedded into the library at build time.
std::string_view workcellSchema();

}  // namespace rw::loaders::detail
