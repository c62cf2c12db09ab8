#include "models/inductance/parallel_coils.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "models/inductance/constants.h"

namespace tcpmsim::inductance {

namespace {

constexpr int kFirstPoints = 32;
constexpr int kMostPoints = 1 << 12;
constexpr double kAgreement = 1e-12;

struct TrapezoidSum {
  double value = 0.0;      // of cos(t1 - t2) / R
  double magnitude = 0.0;  // of |cos(t1 - t2)| / R: the scale rounding and agreement refer to
};

// The trapezoidal sums over n x n points (without the weights).
TrapezoidSum trapezoid_sum(double a, double b, double lateral, double axial, int n) {
  std::vector<double> cosines(static_cast<std::size_t>(n)), sines(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / n;
    cosines[static_cast<std::size_t>(k)] = std::cos(angle);
    sines[static_cast<std::size_t>(k)] = std::sin(angle);
  }
  const double axial2 = axial * axial;
  TrapezoidSum sum;
  for (int i = 0; i < n; ++i) {
    const double x1 = a * cosines[static_cast<std::size_t>(i)] - lateral;
    const double y1 = a * sines[static_cast<std::size_t>(i)];
    double row = 0.0, row_magnitude = 0.0;
    for (int j = 0; j < n; ++j) {
      const double c2 = cosines[static_cast<std::size_t>(j)];
      const double s2 = sines[static_cast<std::size_t>(j)];
      const double dx = x1 - b * c2;
      const double dy = y1 - b * s2;
      const double alignment =
          cosines[static_cast<std::size_t>(i)] * c2 + sines[static_cast<std::size_t>(i)] * s2;
      const double inverse_distance = 1.0 / std::sqrt(dx * dx + dy * dy + axial2);
      row += alignment * inverse_distance;
      row_magnitude += std::abs(alignment) * inverse_distance;
    }
    sum.value += row;
    sum.magnitude += row_magnitude;
  }
  return sum;
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
  const double weight = mu0 * a * b / (4.0 * std::numbers::pi);
  double previous = 0.0;
  for (int n = kFirstPoints; n <= kMostPoints; n *= 2) {
    const double scale = weight * std::pow(2.0 * std::numbers::pi / n, 2);
    const TrapezoidSum sum = trapezoid_sum(a, b, lateral, axial, n);
    const double estimate = scale * sum.value;
    // Side by side the integral is a small difference of large parts: agreement is judged
    // against the parts' size, below which rounding leaves nothing to gain.
    if (n > kFirstPoints && std::abs(estimate - previous) <= kAgreement * scale * sum.magnitude)
      return estimate;
    previous = estimate;
  }
  throw std::domain_error(
      "parallel_loops_mutual_inductance: no convergence with 4096 points per angle: the rings "
      "nearly meet");
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
