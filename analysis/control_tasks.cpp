#include "analysis/control_tasks.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "analysis/series_checks.h"
#include "analysis/statistics.h"

namespace tcpmsim {

namespace {
// z_0.975 of the standard normal distribution.
constexpr double kZ975 = 1.959963984540054;
}  // namespace

namespace {
// estimate - truth, both finite and of equal length.
std::vector<double> estimation_errors(std::span<const double> truth,
                                      std::span<const double> estimate, const char* what) {
  require_same_length(truth.size(), estimate.size(), what);
  require_finite(truth, what, "truth");
  require_finite(estimate, what, "estimate");
  std::vector<double> errors(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) errors[i] = estimate[i] - truth[i];
  return errors;
}
}  // namespace

ErrorStatistics error_statistics(std::span<const double> errors) {
  if (errors.size() < 2) throw std::invalid_argument("error_statistics: need two samples");
  require_finite(errors, "error_statistics", "errors");
  ErrorStatistics statistics;
  statistics.count = errors.size();
  statistics.mean = analysis::mean(errors);
  statistics.standard_deviation = analysis::standard_deviation(errors);
  statistics.half_width_95 = kZ975 * statistics.standard_deviation;
  statistics.rmse = analysis::root_mean_square(errors);
  const std::vector<double> values(errors.begin(), errors.end());
  statistics.percentile_2_5 = analysis::percentile(values, 2.5);
  statistics.percentile_97_5 = analysis::percentile(values, 97.5);
  return statistics;
}

ErrorStatistics estimation_error_statistics(std::span<const double> truth,
                                            std::span<const double> estimate) {
  return error_statistics(estimation_errors(truth, estimate, "estimation_error_statistics"));
}

double calibration_offset(std::span<const double> truth, std::span<const double> estimate) {
  if (truth.empty()) throw std::invalid_argument("calibration_offset: no samples");
  return -analysis::mean(estimation_errors(truth, estimate, "calibration_offset"));
}

}  // namespace tcpmsim
