#include "models/inductance/loop_mutual.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "models/inductance/constants.h"

namespace tcpmsim::inductance {

namespace {

// 2 (K - E)/m - K as a power series in m = k^2, free of the cancellation as m -> 0:
// 2D - K = (pi/2) sum_{j>=1} a_j j/(j+1) m^j with a_j = ((1/2)_j / j!)^2. Leading term pi m/16.
double two_d_minus_k_series(double m) {
  double a = 1.0;
  double power = 1.0;
  double sum = 0.0;
  for (int j = 1; j < 200; ++j) {
    const double factor = (j - 0.5) / j;
    a *= factor * factor;
    power *= m;
    const double term = a * j / (j + 1.0) * power;
    sum += term;
    if (term < 1e-17 * sum) break;
  }
  return 0.5 * std::numbers::pi * sum;
}

}  // namespace

double loop_mutual_inductance(double radius, double distance) {
  if (!(radius > 0.0) || !(distance > 0.0)) {
    throw std::domain_error("loop_mutual_inductance: radius and distance must be positive");
  }
  const double d2 = 4.0 * radius * radius;
  const double m = d2 / (d2 + distance * distance);  // (2.12): k^2
  const double k = std::sqrt(m);
  // (2.11): (2/k - k) K - (2/k) E = k (2 (K - E)/k^2 - K)
  if (m < 0.1) return mu0 * radius * k * two_d_minus_k_series(m);
  const double big_k = std::comp_ellint_1(k);
  const double big_e = std::comp_ellint_2(k);
  return mu0 * radius * ((2.0 / k - k) * big_k - (2.0 / k) * big_e);
}

double wire_gmd(double wire_diameter) {
  return 0.5 * wire_diameter * std::exp(-0.25);
}

}  // namespace tcpmsim::inductance
