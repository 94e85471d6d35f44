#pragma once

#include <atomic>
#include <stdexcept>
#include <string>

/// SIGINT and SIGTERM as a request to stop long work cleanly (a benchmark run, the generator):
/// the handler only sets a flag; the work reads it between items (TaskPool's stop flag), lets
/// the running items finish, keeps what it wrote and throws StopRequested. A second signal of
/// either kind ends the process at once (the default action).
namespace rw::common {

/// Thrown by work that ended early because its stop flag was set.
class StopRequested : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Installs handlers for SIGINT and SIGTERM that set stopSignalFlag() and record the signal;
/// each handler resets itself to the default on its first use. A signal the process ignores
/// (a background job's SIGINT, nohup) stays ignored. Clears the flag.
/// @throws std::runtime_error if the handlers cannot be installed.
void catchStopSignals();

/// The flag the handlers set (true once SIGINT or SIGTERM arrived after catchStopSignals()).
const std::atomic<bool>& stopSignalFlag();

/// The signal that set the flag (SIGINT or SIGTERM), 0 if none arrived.
int stopSignal();

/// The exit code of a process stopped by `signal`: 128 + the signal's number (130 for SIGINT,
/// 143 for SIGTERM), as a shell reports a process the signal killed.
int stopExitCode(int signal);

/// The signal's name ("SIGINT", "SIGTERM"; "signal N" for others).
std::string signalName(int signal);

}  // namespace rw::common
