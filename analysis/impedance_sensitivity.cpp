#include "analysis/impedance_sensitivity.h"

#include <cmath>

#include "analysis/statistics.h"

namespace tcpmsim::analysis {

ImpedanceSensitivity impedance_sensitivity(std::span<const double> deflection,
                                           const std::vector<std::vector<double>>& readings) {
  ImpedanceSensitivity s;
  const std::size_t steps = readings.size();
  double variance_sum = 0.0;
  double readings_per_step = 0.0;
  for (const auto& step : readings) {
    s.step_mean.push_back(analysis::mean(step));
    s.step_std.push_back(standard_deviation(step));
    variance_sum += s.step_std.back() * s.step_std.back();
    readings_per_step += static_cast<double>(step.size()) / static_cast<double>(steps);
  }
  s.mean = analysis::mean(s.step_mean);
  s.noise = std::sqrt(variance_sum / static_cast<double>(steps));
  const double mean_error = s.noise / std::sqrt(readings_per_step);  // of one step mean

  const LineFit line = fit_line(deflection, s.step_mean);
  s.slope = line.slope;
  s.slope_error = mean_error / std::sqrt(line.sxx);
  s.slope_t = s.slope / s.slope_error;
  s.line_r_squared = line.r_squared;
  double residual_sum = 0.0;
  for (std::size_t i = 0; i < steps; ++i) {
    const double residual = s.step_mean[i] - (line.intercept + line.slope * deflection[i]);
    residual_sum += residual * residual;
  }
  s.excess_scatter = std::sqrt(residual_sum / static_cast<double>(steps)) / mean_error;
  s.relative_change = (s.step_mean.back() - s.step_mean.front()) / s.mean;
  s.relative_slope = s.slope / s.mean;
  s.deflection_noise = s.noise / std::abs(s.slope);

  // A difference of two step means has standard error sqrt(2) * mean_error.
  const double threshold = 2.0 * std::sqrt(2.0) * mean_error;
  for (std::size_t i = 1; i < steps; ++i) {
    const double change = s.step_mean[i] - s.step_mean[i - 1];
    if (std::abs(change) <= threshold) continue;
    if ((change > 0.0) == (s.slope > 0.0)) {
      ++s.significant_steps;
    } else {
      ++s.significant_reversals;
    }
  }
  return s;
}

}  // namespace tcpmsim::analysis
