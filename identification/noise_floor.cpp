#include "identification/noise_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/not_a_number.h"

namespace tcpmsim::fit {

namespace {

double third_difference(const std::vector<double>& values, std::size_t i) {
  return values[i + 3] - 3.0 * values[i + 2] + 3.0 * values[i + 1] - values[i];
}

}  // namespace

double input_jump_threshold(const std::vector<double>& input) {
  if (input.empty()) return 0.0;
  const auto [low, high] = std::minmax_element(input.begin(), input.end());
  return 0.02 * (*high - *low);
}

std::vector<char> steps_in_inputs(const std::vector<const std::vector<double>*>& inputs,
                                  std::size_t samples) {
  std::vector<char> steps(samples, 0);
  for (const auto* input : inputs) {
    if (input->size() != samples || samples < 4) continue;
    const double least = input_jump_threshold(*input);
    for (std::size_t i = 0; i + 3 < samples; ++i) {
      if (std::abs(third_difference(*input, i)) > least) {
        for (std::size_t j = i; j <= i + 3; ++j) steps[j] = 1;
      }
    }
  }
  return steps;
}

double difference_noise_floor(const std::vector<double>& values, const std::vector<char>& steps) {
  if (values.size() < 8) return kNaN;
  std::vector<double> third;
  third.reserve(values.size() - 3);
  for (std::size_t i = 0; i + 3 < values.size(); ++i) {
    const bool stepped =
        !steps.empty() && (steps[i] || steps[i + 1] || steps[i + 2] || steps[i + 3]);
    if (!stepped) third.push_back(std::abs(third_difference(values, i)));
  }
  if (third.size() < 8) return kNaN;
  const auto middle = third.begin() + static_cast<long>(third.size() / 2);
  std::nth_element(third.begin(), middle, third.end());
  // The median of |d| is 0.6745 of its standard deviation for Gaussian d; sd(d) = sqrt(20) sigma.
  // It sets a cut at 4.5 of those deviations, past which a difference is a jump, not noise; the
  // RMS of the rest is the estimate (the median alone would sit on a grid the data are read on,
  // and move in its steps). A Gaussian cut at 4.5 sd keeps 0.9999 of its variance.
  const double rough = *middle / 0.674489750196082;
  double sum = 0.0;
  std::size_t kept = 0;
  for (const double d : third) {
    if (d <= 4.5 * rough) {
      sum += d * d;
      ++kept;
    }
  }
  const double scale = kept > 0 && rough > 0.0 ? std::sqrt(sum / static_cast<double>(kept) / 20.0)
                                               : rough / std::sqrt(20.0);
  // Data on a grid (a load cell's resolution q) carry at least its rounding error, q / sqrt(12),
  // which the median misses when the noise is finer than q (most differences are then 0).
  double step = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < values.size(); ++i) {
    const double difference = std::abs(values[i + 1] - values[i]);
    if (difference > 0.0) step = std::min(step, difference);
  }
  return std::isfinite(step) ? std::max(scale, step / std::sqrt(12.0)) : scale;
}

}  // namespace tcpmsim::fit
