#pragma once

namespace tcpmsim {

// SIGINT and SIGTERM while a run integrates. The first one asks the run to stop: the run ends
// after its current step and keeps its record as <out>.interrupted.h5. The handler is
// installed for one delivery (SA_RESETHAND), so a second signal ends the program at once.
// Installed for the guard's lifetime; the previous handlers come back with its end.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // The signal received since the last guard was made (SIGINT or SIGTERM), or 0; it stays
  // readable after the guard's end.
  static int received();
  // Throws StopRequest ("interrupted by SIGTERM") when a signal was received.
  static void stop_if_received();
};

}  // namespace tcpmsim
