#include "rw/common/stop_signals.hpp"

#include <signal.h>

#include <cerrno>
#include <cstring>

namespace rw::common {

namespace {

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "a signal handler may only touch lock-free atomics");

// The one place a signal handler can reach: process-wide by nature.
std::atomic<bool> stopFlag{false};
std::atomic<int> stopSignalNumber{0};

extern "C" void onStopSignal(int signal) {
  int none = 0;
  stopSignalNumber.compare_exchange_strong(none, signal);
  stopFlag.store(true);
}

}  // namespace

void catchStopSignals() {
  stopFlag.store(false);
  stopSignalNumber.store(0);
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  for (const int signal : {SIGINT, SIGTERM}) {
    // A signal ignored from the start (a background job's SIGINT, nohup) stays ignored.
    struct sigaction current {};
    if (::sigaction(signal, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    if (::sigaction(signal, &action, nullptr) != 0) {
      throw std::runtime_error("cannot handle " + signalName(signal) + ": " + std::strerror(errno));
    }
  }
}

const std::atomic<bool>& stopSignalFlag() { return stopFlag; }

int stopSignal() { return stopSignalNumber.load(); }

int stopExitCode(int signal) { return 128 + signal; }

std::string signalName(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "signal " + std::to_string(signal);
  }
}

}  // namespace rw::common
