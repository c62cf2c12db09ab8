#include "sim/output_grid.h"

#include <algorithm>
#include <cmath>

namespace tcpmsim {

double output_sample_count(double start, double end, double interval) {
  const double last_on_grid = std::floor((end - start) / interval * (1.0 + 1e-12));
  const double last = start + last_on_grid * interval;
  const bool end_on_grid = std::abs(last - end) <= 1e-9 * std::max(1.0, std::abs(end));
  return last_on_grid + (end_on_grid ? 1.0 : 2.0);
}

}  // namespace tcpmsim
