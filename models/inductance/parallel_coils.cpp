#include "models/inductance/parallel_coils.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "models/inductance/loop_mutual.h"

namespace tcpmsim::inductance {

namespace {

constexpr int kFirstIntervals = 8;  // over [0, pi]
constexpr int kMostIntervals = 1 << 16;
constexpr double kAgreement = 1e-12;

// The integrand of M = int_0^2pi f(phi) dphi: the flux of the first ring's vector potential
// A(rho, z) = M_coax(a, rho, z) / (2 pi rho) along the second ring, whose point at angle phi
// sits at distance rho from the first ring's axis and moves along it at the rate
// b (b + lateral cos phi) / rho:
//   f(phi) = b (b + lateral cos phi) M_coax(a, rho, axial) / (2 pi rho^2),
//   rho^2 = lateral^2 + b^2 + 2 lateral b cos phi.
// Where the second ring crosses the axis (rho = 0, lateral = b, phi = pi) the factor
// b + lateral cos phi vanishes and A stays finite: f = 0.
double flux_rate(double a, double b, double lateral, double axial, double phi) {
  const double cosine = std::cos(phi);
  const double rho2 = lateral * lateral + b * b + 2.0 * lateral * b * cosine;
  if (!(rho2 > 0.0)) return 0.0;
  return b * (b + lateral * cosine) * coaxial_loops_mutual_inductance(a, std::sqrt(rho2), axial) /
         (2.0 * std::numbers::pi * rho2);
}

}  // namespace

double parallel_loops_mutual_inductance(double a, double b, double lateral, double axial) {
  if (!(a > 0.0) || !(b > 0.0) || !(lateral >= 0.0) || !std::isfinite(lateral) ||
      !std::isfinite(axial))
    throw std::domain_error(
        "parallel_loops_mutual_inductance: expected positive radii and "
        "finite, non-negative offsets");
  // Coplanar circles meet where |a - b| <= lateral <= a + b.
  if (axial == 0.0 && lateral >= std::abs(a - b) && lateral <= a + b)
    throw std::domain_error("parallel_loops_mutual_inductance: the rings meet");
  if (lateral == 0.0) return coaxial_loops_mutual_inductance(a, b, axial);
  // f is even and 2 pi periodic: M = 2 int_0^pi f, by the trapezoidal rule, which converges
  // geometrically for a smooth periodic integrand. The intervals are doubled (the new points
  // are the odd ones) until two estimates agree to 1e-12 of the integral of |f| (side by side
  // M is a small difference of large parts).
  const auto f = [&](double phi) { return flux_rate(a, b, lateral, axial, phi); };
  const double end_0 = f(0.0), end_pi = f(std::numbers::pi);
  double ends = 0.5 * (end_0 + end_pi), ends_magnitude = 0.5 * (std::abs(end_0) + std::abs(end_pi));
  double inner = 0.0, inner_magnitude = 0.0;
  double previous = 0.0;
  for (int n = kFirstIntervals, added = 1; n <= kMostIntervals; n *= 2) {
    // The points of n intervals not already in the sums: odd multiples of pi / n (all of them
    // when n is the first count).
    for (int k = 1; k < n; k += added) {
      const double value = f(std::numbers::pi * k / n);
      inner += value;
      inner_magnitude += std::abs(value);
    }
    added = 2;
    const double width = std::numbers::pi / n;
    const double estimate = 2.0 * width * (ends + inner);
    const double magnitude = 2.0 * width * (ends_magnitude + inner_magnitude);
    if (n > kFirstIntervals && std::abs(estimate - previous) <= kAgreement * magnitude)
      return estimate;
    previous = estimate;
  }
  throw std::domain_error(
      "parallel_loops_mutual_inductance: no convergence with 65536 intervals: the rings nearly "
      "meet");
}

double parallel_coils_mutual_inductance(const CoilGeometry& coil, double separation) {
  if (!(coil.turns >= 1.0) || !(coil.length > 0.0))
    throw std::domain_error(
        "parallel_coils_mutual_inductance: expected a coil of at least "
        "one turn and positive length");
  if (!(separation > 2.0 * coil.radius))
    throw std::domain_error(
        "parallel_coils_mutual_inductance: side by side needs the axes more "
        "than a diameter apart");
  const int rings = static_cast<int>(std::lround(coil.turns));
  const double pitch = coil.pitch();
  double sum = static_cast<double>(rings) *
               parallel_loops_mutual_inductance(coil.radius, coil.radius, separation, 0.0);
  for (int s = 1; s < rings; ++s) {
    // Offsets s p and -s p give the same ring pair value (mirror symmetry).
    sum += 2.0 * static_cast<double>(rings - s) *
           parallel_loops_mutual_inductance(coil.radius, coil.radius, separation, s * pitch);
  }
  return sum;
}

}  // namespace tcpmsim::inductance
