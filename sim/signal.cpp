#include "sim/signal.h"

#include <algorithm>
#include <cmath>

namespace tcpmsim {

double Signal::slope(double time) const {
  // One-sided, so that a breakpoint at `time` is not straddled; second order.
  const double h = 1e-6 * std::max(1.0, std::abs(time));
  return (-3.0 * value(time) + 4.0 * value(time + h) - value(time + 2.0 * h)) / (2.0 * h);
}

double Signal::next_breakpoint_after(double) const {
  return kNoBreakpoint;
}

}  // namespace tcpmsim
