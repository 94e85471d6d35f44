#pragma once

#include <stdexcept>
#include <string>

// Private to rwsim_simulator: process-wide ODE set-up. ODE's error and debug handlers normally end
// the process (exit / abort after the handler returns); here they throw OdeFatalError instead,
// which Simulator::step turns into a failure status. Non-fatal messages are collected per thread.
namespace rwsim::simulator::detail {

/// Thrown (through ODE) by the installed error and debug handlers.
class OdeFatalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Calls dInitODE2 and installs the handlers once per process, and dAllocateODEDataForThread
/// once per calling thread. @throws std::runtime_error if ODE is not double precision.
void prepareOdeForThisThread();

/// ODE's non-fatal messages on this thread since the last call (joined by "; "), then clears.
std::string takeOdeMessages();

}  // namespace rwsim::simulator::detail
