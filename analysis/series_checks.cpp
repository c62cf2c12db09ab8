#include "analysis/series_checks.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tcpmsim {

void require_finite(std::span<const double> values, const char* what, const char* name) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument(std::string(what) + ": " + name + "[" + std::to_string(i) +
                                  "] is not finite (trim the start-up before the analysis)");
    }
  }
}

void require_same_length(std::size_t a, std::size_t b, const char* what) {
  if (a != b) throw std::invalid_argument(std::string(what) + ": series differ in length");
}

void require_time(std::span<const double> time, const char* what) {
  require_finite(time, what, "time");
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (!(time[i] > time[i - 1]))
      throw std::invalid_argument(std::string(what) + ": time must increase strictly");
  }
}

double wrap_phase(double phase) {
  double wrapped = std::remainder(phase, 2.0 * std::numbers::pi);
  if (wrapped <= -std::numbers::pi) wrapped += 2.0 * std::numbers::pi;
  return wrapped;
}

}  // namespace tcpmsim
