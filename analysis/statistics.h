#pragma once

#include <span>
#include <vector>

namespace tcpmsim::analysis {

double mean(std::span<const double> values);
// Sample standard deviation (n - 1), as MATLAB's std.
double standard_deviation(std::span<const double> values);
// max - min
double value_range(std::span<const double> values);
// Root mean square of a - b.
double rmse(std::span<const double> a, std::span<const double> b);
double root_mean_square(std::span<const double> values);
// The p-th percentile (0 <= p <= 100) by linear interpolation between order statistics (NumPy's
// default).
double percentile(std::vector<double> values, double p);
// (2.15), (7.15) R^2 = 1 - sum (y - f)^2 / sum (y - mean y)^2 (negative when f is worse than the
// mean).
double r_squared(std::span<const double> measured, std::span<const double> predicted);

// Piecewise-linear interpolation in the table (x_i, y_i), x strictly monotonic (increasing or
// decreasing), extrapolating linearly beyond either end (MATLAB interp1 'linear', 'extrap').
double interpolate_linear(std::span<const double> x, std::span<const double> y, double at);

// Least-squares straight line y = intercept + slope x.
struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;
  double r_squared = 0.0;
  double sxx = 0.0;  // sum (x - mean x)^2, for the slope's standard error
};
LineFit fit_line(std::span<const double> x, std::span<const double> y);

}  // namespace tcpmsim::analysis
