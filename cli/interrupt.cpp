#include "cli/interrupt.h"

#include <atomic>
#include <csignal>
#include <string>

#include "sim/integrator.h"

namespace tcpmsim {

namespace {

// A signal handler can only reach the program through an object of static storage: the one
// process-wide state of tcpmsim, and only the CLI's. Lock-free, so the handler may store it and
// any run's thread read it.
std::atomic<int> received_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);
struct sigaction previous_interrupt, previous_terminate;

extern "C" void note_signal(int signal) {
  received_signal = signal;
}

}  // namespace

InterruptGuard::InterruptGuard() {
  received_signal = 0;
  struct sigaction action {};
  action.sa_handler = note_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, &previous_interrupt);
  sigaction(SIGTERM, &action, &previous_terminate);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &previous_interrupt, nullptr);
  sigaction(SIGTERM, &previous_terminate, nullptr);
}

int InterruptGuard::received() {
  return received_signal;
}

void InterruptGuard::stop_if_received() {
  const int signal = received_signal;
  if (signal == 0) return;
  throw StopRequest(std::string("interrupted by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM"));
}

}  // namespace tcpmsim
