#pragma once

#include <string_view>

namespace rwsim::loaders::detail {

/// The text of xml/dynamicworkcell.xsd, embedded into the library at build time.
std::string_view dynamicWorkCellSchema();

}  // namespace rwsim::loaders::detail
