#include "models/inductance/maxwell_evaluator.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "models/inductance/loop_mutual.h"

namespace tcpmsim::inductance {

namespace {

constexpr int kPoints = MaxwellEvaluator::kDegree + 1;
constexpr int kShift = 52 - MaxwellEvaluator::kSubdivisionBits;
constexpr std::size_t kMaxSegments = 1 << 16;

double edge_of(std::uint64_t key) {
  return std::bit_cast<double>(key << kShift);
}

// Chebyshev interpolant of f on [-1, 1] at the kPoints first-kind nodes, converted to monomial
// coefficients (well conditioned at this degree: the coefficients decay geometrically).
template <typename F>
std::array<double, kPoints> interpolate(F&& f) {
  std::array<double, kPoints> values{};
  for (int k = 0; k < kPoints; ++k) {
    values[k] = f(std::cos(std::numbers::pi * (k + 0.5) / kPoints));
  }
  std::array<double, kPoints> chebyshev{};
  for (int j = 0; j < kPoints; ++j) {
    double sum = 0.0;
    for (int k = 0; k < kPoints; ++k) {
      sum += values[k] * std::cos(std::numbers::pi * j * (k + 0.5) / kPoints);
    }
    chebyshev[j] = (j == 0 ? 1.0 : 2.0) * sum / kPoints;
  }
  // T_j as monomials: T_0 = 1, T_1 = t, T_{j+1} = 2 t T_j - T_{j-1}.
  std::array<double, kPoints> monomial{};
  std::array<double, kPoints> previous{}, current{}, next{};
  previous[0] = 1.0;
  current[1] = 1.0;
  for (int i = 0; i < kPoints; ++i) monomial[i] += chebyshev[0] * previous[i];
  for (int i = 0; i < kPoints; ++i) monomial[i] += chebyshev[1] * current[i];
  for (int j = 2; j < kPoints; ++j) {
    next.fill(0.0);
    for (int i = 0; i + 1 < kPoints; ++i) next[i + 1] += 2.0 * current[i];
    for (int i = 0; i < kPoints; ++i) next[i] -= previous[i];
    for (int i = 0; i < kPoints; ++i) monomial[i] += chebyshev[j] * next[i];
    previous = current;
    current = next;
  }
  return monomial;
}

double horner(const std::array<double, kPoints>& coefficients, double t) {
  double sum = coefficients[kPoints - 1];
  for (int i = kPoints - 2; i >= 0; --i) sum = sum * t + coefficients[i];
  return sum;
}

}  // namespace

std::uint64_t MaxwellEvaluator::key_of(double distance) noexcept {
  // For positive finite doubles the bit pattern is monotonic in the value: its top bits are
  // the octave (exponent) and, after it, the sub-segment within the octave.
  return std::bit_cast<std::uint64_t>(distance) >> kShift;
}

MaxwellEvaluator::MaxwellEvaluator(double radius, double self_distance, double min_distance,
                                   double max_distance)
    : radius_(radius), self_term_(loop_mutual_inductance(radius, self_distance)) {
  if (!(min_distance > 0.0) || !(max_distance > min_distance) || !std::isfinite(max_distance)) {
    throw std::invalid_argument("MaxwellEvaluator: needs 0 < min_distance < max_distance");
  }
  first_key_ = key_of(min_distance);
  const std::uint64_t last_key = key_of(max_distance);
  if (last_key - first_key_ + 1 > kMaxSegments) {
    throw std::invalid_argument("MaxwellEvaluator: distance range too wide to tabulate");
  }
  table_min_ = edge_of(first_key_);
  table_max_ = edge_of(last_key + 1);
  segments_.resize(last_key - first_key_ + 1);
  for (std::uint64_t key = first_key_; key <= last_key; ++key) {
    const double lower = edge_of(key);
    const double upper = edge_of(key + 1);
    Segment& segment = segments_[key - first_key_];
    segment.centre = 0.5 * (lower + upper);
    const double half_width = 0.5 * (upper - lower);
    segment.inverse_half_width = 1.0 / half_width;
    segment.coefficients = interpolate(
        [&](double t) { return loop_mutual_inductance(radius_, segment.centre + half_width * t); });
    // Check between the nodes (where an interpolant's error peaks) and at the edges.
    for (int k = 0; k <= kPoints; ++k) {
      const double t = k == kPoints ? 1.0 : std::cos(std::numbers::pi * k / kPoints);
      const double h = std::clamp(segment.centre + half_width * t, lower, upper);
      const double exact = loop_mutual_inductance(radius_, h);
      const double error = std::abs(horner(segment.coefficients, t) - exact) / exact;
      table_error_ = std::max(table_error_, error);
    }
  }
}

double MaxwellEvaluator::direct(double distance) const noexcept {
  if (!(distance > 0.0)) return std::numeric_limits<double>::infinity();  // coincident rings
  return loop_mutual_inductance(radius_, distance);
}

double MaxwellEvaluator::mutual(double distance) const noexcept {
  const std::uint64_t index = key_of(distance) - first_key_;  // wraps below the table
  if (index >= segments_.size() || !(distance > 0.0)) return direct(distance);
  const Segment& segment = segments_[index];
  return horner(segment.coefficients, (distance - segment.centre) * segment.inverse_half_width);
}

double MaxwellEvaluator::inductance(std::span<const double> positions) const noexcept {
  const std::size_t n = positions.size();
  double mutual_sum = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double xi = positions[i];
    for (std::size_t j = i + 1; j < n; ++j) mutual_sum += mutual(std::abs(positions[j] - xi));
  }
  return static_cast<double>(n) * self_term_ + 2.0 * mutual_sum;  // (4.11), M_ij = M_ji
}

double MaxwellEvaluator::inductance_uniform(int rings, double pitch) const noexcept {
  double mutual_sum = 0.0;
  for (int i = 1; i < rings; ++i) mutual_sum += (rings - i) * mutual(i * pitch);
  return rings * self_term_ + 2.0 * mutual_sum;  // (2.13)
}

}  // namespace tcpmsim::inductance
