#include "runtime/simulation/interrupt.h"

#include <csignal>

namespace ffriga {

namespace {

volatile std::sig_atomic_t g_signal = 0;  // the first signal received, 0 if none

extern "C" void onStopSignal(int signal_number) {
  if (g_signal == 0) g_signal = signal_number;
}

}  // namespace

void installInterruptHandler() {
  struct sigaction action = {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // reads and writes in progress complete
  sigset_t stop;
  sigemptyset(&stop);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) {
    sigaction(s, &action, nullptr);
    sigaddset(&stop, s);
  }
  // A launcher may start us with these blocked (they are inherited across exec): unblocked
  // here, a stop requested before this point is delivered now and honoured.
  sigprocmask(SIG_UNBLOCK, &stop, nullptr);
}

bool interruptRequested() {
  return g_signal != 0;
}

std::string interruptSignalName() {
  switch (g_signal) {
    case 0:
      return "";
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "signal " + std::to_string(static_cast<int>(g_signal));
  }
}

void requestInterrupt(int signal_number) {
  g_signal = signal_number;
}

void clearInterrupt() {
  g_signal = 0;
}

}  // namespace ffriga
