#include "sim/time_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tcpmsim {

double time_margin(double t) {
  return 64.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t));
}

bool same_instant(double t, double instant) {
  return std::abs(t - instant) <= time_margin(t);
}

std::optional<long> grid_index_at(double t, double period) {
  const double k = std::round(t / period);
  if (!same_instant(t, k * period)) return std::nullopt;
  return static_cast<long>(k);
}

double next_grid_instant(double t, double period) {
  double k = std::floor(t / period) + 1.0;
  while (k * period <= t) k += 1.0;
  return k * period;
}

}  // namespace tcpmsim
