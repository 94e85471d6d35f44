#pragma once

#include <string>

#include "support/test_support.hpp"

#ifndef VISGRAB_BINARY
#error "define VISGRAB_BINARY as $<TARGET_FILE:visgrab> for the test target"
#endif

/// Running the visgrab program from a command-line test: the test target defines VISGRAB_BINARY
/// as $<TARGET_FILE:visgrab> and adds a dependency on visgrab.
namespace visgrab::test {

/// Runs the visgrab program with `args` (already shell-quoted) and captures its output.
inline RunResult runVisgrab(const std::string& args) { return runProgram(VISGRAB_BINARY, args); }

}  // namespace visgrab::test
