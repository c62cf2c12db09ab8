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

// (2/k - k) K(k) - (2/k) E(k) from m = k^2 and its complement m' = 1 - m, by the AGM: with
// E = K (1 - sum_{n>=0} 2^(n-1) c_n^2) the bracket is (K/k) sum_{n>=1} 2^n c_n^2, and
// c_{n+1} = (a_n - b_n)/2 = c_n^2 / (4 a_{n+1}) needs no subtraction.
double maxwell_bracket(double m, double complement) {
  const double k = std::sqrt(m);
  double a = 1.0, b = std::sqrt(complement), c = k;  // a_0, b_0 = k', c_0 = k
  double power = 1.0, sum = 0.0;
  for (int n = 0; n < 32; ++n) {
    const double next_a = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = next_a;
    c = c * c / (4.0 * a);  // c_{n+1} = c_n^2 / (4 a_{n+1})
    power *= 2.0;
    sum += power * c * c;
    // a_{n+1} - b_{n+1} = 2 c_{n+2} < c_{n+1}^2 / a: a_{n+1} is the AGM to 1e-18, and the
    // terms left are as small.
    if (c <= 1e-9 * a) break;
  }
  return std::numbers::pi / (2.0 * a) / k * sum;
}

}  // namespace

double coaxial_loops_mutual_inductance(double a, double b, double distance) {
  if (!(a > 0.0) || !(b > 0.0) || !std::isfinite(a) || !std::isfinite(b) ||
      !std::isfinite(distance))
    throw std::domain_error(
        "coaxial_loops_mutual_inductance: expected positive radii and a finite distance");
  const double h2 = distance * distance;
  const double sum = a + b, difference = a - b;
  const double denominator = sum * sum + h2;
  const double complement = (difference * difference + h2) / denominator;  // k'^2
  if (!(complement > 0.0))
    throw std::domain_error("coaxial_loops_mutual_inductance: the rings meet");
  const double m = 4.0 * a * b / denominator;  // k^2
  if (m == 0.0) return 0.0;                    // so far apart that k^2 underflows
  return mu0 * std::sqrt(a * b) * maxwell_bracket(m, complement);
}

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
