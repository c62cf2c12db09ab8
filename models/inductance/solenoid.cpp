#include "models/inductance/solenoid.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "models/inductance/constants.h"

namespace tcpmsim::inductance {

namespace {

// (K(k) - E(k)) / k^2 for the modulus k, without the cancellation of K - E as k -> 0.
// Gauss' series: K - E = (pi/2) sum_{n>=1} [((1/2)_n)^2 - (-1/2)_n (1/2)_n] / (n!)^2 k^(2n);
// the n-th term is t_n = (pi/2) c_n m^n with c_n = ((1/2)_n / n!)^2 * 2n/(2n-1), m = k^2.
double k_minus_e_over_m(double k) {
  const double m = k * k;
  if (m > 0.1) return (std::comp_ellint_1(k) - std::comp_ellint_2(k)) / m;
  double a = 1.0;  // ((1/2)_n / n!)^2, starting at n = 0
  double power = 1.0;
  double sum = 0.0;
  for (int n = 1; n < 200; ++n) {
    const double factor = (n - 0.5) / n;
    a *= factor * factor;
    const double term = a * (2.0 * n / (2.0 * n - 1.0)) * power;  // m^(n-1) after dividing by m
    sum += term;
    if (term < 1e-17 * sum) break;
    power *= m;
  }
  return 0.5 * std::numbers::pi * sum;
}

}  // namespace

double basic_solenoid_inductance(const CoilGeometry& coil) {
  const double area = std::numbers::pi * coil.radius * coil.radius;
  return mu0 * coil.turns * coil.turns * area / coil.length;  // (2.2)
}

double nagaoka_coefficient(double diameter_over_length) {
  const double u = diameter_over_length;
  if (!(u >= 0.0) || !std::isfinite(u)) {
    throw std::domain_error("nagaoka_coefficient: 2r/l must be finite and non-negative");
  }
  if (u == 0.0) return 1.0;
  const double k2 = u * u / (1.0 + u * u);  // (2.5), corrected
  const double kp2 = 1.0 / (1.0 + u * u);   // (2.6), corrected
  const double k = std::sqrt(k2);
  const double kp = std::sqrt(kp2);
  const double e = std::comp_ellint_2(k);
  // (2.4) with (k'^2/k^2)(K - E) written as k'^2 (K - E)/k^2.
  return 4.0 / (3.0 * std::numbers::pi * kp) * (kp2 * k_minus_e_over_m(k) + e - k);
}

double nagaoka_inductance(const CoilGeometry& coil) {
  return basic_solenoid_inductance(coil) * nagaoka_coefficient(coil.diameter() / coil.length);
}

}  // namespace tcpmsim::inductance
