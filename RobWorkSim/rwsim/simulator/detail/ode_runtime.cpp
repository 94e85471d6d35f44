#include "rwsim/simulator/detail/ode_runtime.hpp"

#include <ode/ode.h>

#include <cstdarg>
#include <cstdio>
#include <mutex>

namespace rwsim::simulator::detail {

namespace {

thread_local std::string tMessages;
thread_local bool tThreadReady = false;
bool gDoublePrecision = false;

std::string format(const char* kind, int num, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof text, msg, ap);
  return std::string(kind) + " " + std::to_string(num) + ": " + text;
}

[[noreturn]] void onError(int num, const char* msg, va_list ap) {
  throw OdeFatalError(format("ODE error", num, msg, ap));
}

[[noreturn]] void onDebug(int num, const char* msg, va_list ap) {
  throw OdeFatalError(format("ODE internal error", num, msg, ap));
}

void onMessage(int num, const char* msg, va_list ap) {
  if (tMessages.size() > 4096) return;  // keep the first few; a diverging step repeats itself
  if (!tMessages.empty()) tMessages += "; ";
  tMessages += format("ODE message", num, msg, ap);
}

void initProcess() {
  dInitODE2(0);
  dSetErrorHandler(onError);
  dSetDebugHandler(onDebug);
  dSetMessageHandler(onMessage);
  gDoublePrecision = dCheckConfiguration("ODE_double_precision") != 0;
}

}  // namespace

void prepareOdeForThisThread() {
  static std::once_flag once;
  std::call_once(once, initProcess);
  if (!gDoublePrecision) {
    throw std::runtime_error("the ODE library is not built in double precision");
  }
  if (!tThreadReady) {
    dAllocateODEDataForThread(dAllocateMaskAll);
    tThreadReady = true;
  }
}

std::string takeOdeMessages() {
  std::string out;
  out.swap(tMessages);
  return out;
}

}  // namespace rwsim::simulator::detail
