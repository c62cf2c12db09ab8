#include "analysis/statistics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tcpmsim::analysis {

double mean(std::span<const double> values) {
  if (values.empty()) throw std::invalid_argument("mean of no values");
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double standard_deviation(std::span<const double> values) {
  if (values.size() < 2) throw std::invalid_argument("standard deviation needs two values");
  const double m = mean(values);
  double sum = 0.0;
  for (double v : values) sum += (v - m) * (v - m);
  return std::sqrt(sum / static_cast<double>(values.size() - 1));
}

double value_range(std::span<const double> values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return *high - *low;
}

double rmse(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size() || a.empty()) throw std::invalid_argument("rmse of unequal series");
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(sum / static_cast<double>(a.size()));
}

double root_mean_square(std::span<const double> values) {
  if (values.empty()) throw std::invalid_argument("root mean square of no values");
  double sum = 0.0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) throw std::invalid_argument("percentile of no values");
  if (!(p >= 0.0 && p <= 100.0)) throw std::invalid_argument("percentile outside [0, 100]");
  std::sort(values.begin(), values.end());
  const double position = (double(values.size()) - 1.0) * p / 100.0;
  const auto below = static_cast<std::size_t>(std::floor(position));
  if (below + 1 >= values.size()) return values.back();
  return values[below] + (position - double(below)) * (values[below + 1] - values[below]);
}

double r_squared(std::span<const double> measured, std::span<const double> predicted) {
  if (measured.size() != predicted.size() || measured.size() < 2) {
    throw std::invalid_argument("R^2 of unequal series");
  }
  const double m = mean(measured);
  double residual = 0.0, total = 0.0;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    residual += (measured[i] - predicted[i]) * (measured[i] - predicted[i]);
    total += (measured[i] - m) * (measured[i] - m);
  }
  return 1.0 - residual / total;  // (2.15)
}

double interpolate_linear(std::span<const double> x, std::span<const double> y, double at) {
  const std::size_t n = x.size();
  if (n < 2 || y.size() != n) throw std::invalid_argument("interpolation needs two points");
  const bool increasing = x[n - 1] > x[0];
  for (std::size_t i = 1; i < n; ++i) {
    if (increasing ? !(x[i] > x[i - 1]) : !(x[i] < x[i - 1])) {
      throw std::invalid_argument("interpolation table is not strictly monotonic");
    }
  }
  // The segment [i, i+1] containing `at`, or the end segment for extrapolation.
  std::size_t i = 0;
  while (i + 2 < n && (increasing ? at > x[i + 1] : at < x[i + 1])) ++i;
  return y[i] + (y[i + 1] - y[i]) * (at - x[i]) / (x[i + 1] - x[i]);
}

LineFit fit_line(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size() || x.size() < 2) throw std::invalid_argument("line fit needs 2 points");
  const double mx = mean(x), my = mean(y);
  LineFit fit;
  double sxy = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    fit.sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (!(fit.sxx > 0.0)) throw std::invalid_argument("line fit needs distinct x");
  fit.slope = sxy / fit.sxx;
  fit.intercept = my - fit.slope * mx;
  fit.r_squared = syy > 0.0 ? sxy * sxy / (fit.sxx * syy) : 1.0;
  return fit;
}

}  // namespace tcpmsim::analysis
