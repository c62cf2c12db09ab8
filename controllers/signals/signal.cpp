#include "controllers/signals/signal.h"

namespace tcpmsim {

double Signal::next_breakpoint_after(double) const {
  return kNoBreakpoint;
}

}  // namespace tcpmsim
