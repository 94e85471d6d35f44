#pragma once

// Moved to rw/loaders/xml/diagnostic_sink.hpp (public: the dynamic workcell loader shares it). The
// names stay available in rw::loaders::detail for the workcell loader's sources.
#include "rw/loaders/xml/diagnostic_sink.hpp"

namespace rw::loaders::detail {

using xml::DiagnosticSink;
using xml::sanitizeText;
using xml::SourceFile;
using xml::SourceLocation;

}  // namespace rw::loaders::detail
