// Stop requests from the outside: Ctrl-C (SIGINT), a batch scheduler's SIGTERM (Slurm at
// its time limit, before SIGKILL) and SIGHUP (the terminal went away) all ask the run to
// stop cleanly: the handler only records the signal; the time loop checks between steps,
// writes the status ("interrupted by SIGTERM at t = ... s") and closes the result file, and
// ffrsim exits with code 1. A second signal of the same kind while stopping is ignored.
#pragma once

#include <string>

namespace ffriga {

// Installs the handler for SIGINT, SIGTERM and SIGHUP (at program start, before loading).
void installInterruptHandler();
bool interruptRequested();
// "SIGTERM", ..., or "" when no stop was requested.
std::string interruptSignalName();
void requestInterrupt(int signal_number = 2);  // for tests; 2 = SIGINT
void clearInterrupt();

}  // namespace ffriga
