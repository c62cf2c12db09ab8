#pragma once

#include <span>
#include <string>
#include <vector>

namespace tcpmsim::analysis {

// Thesis chapter 3: how strongly, and how unambiguously, one impedance component (resistance
// or inductance) follows deflection in a sequence of steps with repeated readings.
struct ImpedanceSensitivity {
  std::vector<double> step_mean;  // mean of the readings at each step
  std::vector<double> step_std;   // their sample standard deviation
  double mean = 0.0;              // over all steps
  double noise = 0.0;             // pooled single-reading standard deviation (rms of step_std)
  // Least-squares line through the step means against deflection:
  double slope = 0.0;        // [unit/m]
  double slope_error = 0.0;  // standard error from the reading noise: noise/sqrt(n)/sqrt(Sxx)
  double slope_t = 0.0;      // slope / slope_error: significance of the trend
  double line_r_squared = 0.0;
  // rms of the step means about the line, in standard errors of a step mean: ~1 when the line
  // explains the data to within the reading noise, >> 1 when the relation is not a clean trend.
  double excess_scatter = 0.0;
  double relative_change = 0.0;   // (last - first) / mean
  double relative_slope = 0.0;    // slope / mean [1/m]
  double deflection_noise = 0.0;  // noise / |slope|: single-reading deflection resolution [m]
  int significant_steps = 0;      // successive steps that move with the trend, beyond 2 sigma
  int significant_reversals = 0;  // ... and against it, beyond 2 sigma
};

// `readings[i]` are the readings at deflection `deflection[i]`.
ImpedanceSensitivity impedance_sensitivity(std::span<const double> deflection,
                                           const std::vector<std::vector<double>>& readings);

}  // namespace tcpmsim::analysis
