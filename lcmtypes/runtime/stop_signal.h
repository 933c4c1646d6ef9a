// SIGINT/SIGTERM set a flag that a daemon's loop checks; nothing else runs in
// the signal handler.
#pragma once

#include <csignal>

namespace mrsim {

// Installs handlers for SIGINT and SIGTERM (and ignores SIGPIPE).
void InstallStopHandlers();
// True once SIGINT or SIGTERM arrived.
bool StopRequested();
// The signal that asked us to stop, or 0.
int StopSignal();

}  // namespace mrsim
