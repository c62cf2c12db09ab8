#include "analysis/control_tasks.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "analysis/statistics.h"

namespace tcpmsim {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// z_0.975 of the standard normal distribution.
constexpr double kZ975 = 1.959963984540054;

void require_finite(std::span<const double> values, const char* what, const char* name) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument(std::string(what) + ": " + name + "[" + std::to_string(i) +
                                  "] is not finite (trim the start-up before the analysis)");
    }
  }
}

void require_same_length(std::size_t a, std::size_t b, const char* what) {
  if (a != b) throw std::invalid_argument(std::string(what) + ": series differ in length");
}

void require_time(std::span<const double> time, const char* what) {
  require_finite(time, what, "time");
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (!(time[i] > time[i - 1]))
      throw std::invalid_argument(std::string(what) + ": time must increase strictly");
  }
}

double wrap_phase(double phase) {
  // To (-pi, pi].
  double wrapped = std::remainder(phase, 2.0 * std::numbers::pi);
  if (wrapped <= -std::numbers::pi) wrapped += 2.0 * std::numbers::pi;
  return wrapped;
}

// The first time in samples [first, last) at which the response reaches `level` going in
// `direction`, interpolated linearly; NaN if it does not.
double first_reaching(std::span<const double> time, std::span<const double> response,
                      std::size_t first, std::size_t last, double level, double direction) {
  for (std::size_t i = first; i < last; ++i) {
    if (direction * (response[i] - level) < 0.0) continue;
    if (i == first) return time[i];
    const double fraction = (level - response[i - 1]) / (response[i] - response[i - 1]);
    return time[i - 1] + fraction * (time[i] - time[i - 1]);
  }
  return kNaN;
}
}  // namespace

std::vector<StepRise> step_rise_times(std::span<const double> time,
                                      std::span<const double> reference,
                                      std::span<const double> response,
                                      const RiseTimeDefinition& definition, double threshold) {
  const char* what = "step_rise_times";
  require_same_length(time.size(), reference.size(), what);
  require_same_length(time.size(), response.size(), what);
  if (time.size() < 2) throw std::invalid_argument("step_rise_times: need two samples at least");
  require_time(time, what);
  require_finite(reference, what, "reference");
  require_finite(response, what, "response");
  if (!(definition.lower >= 0.0 && definition.lower < definition.upper && definition.upper <= 1.0))
    throw std::invalid_argument("step_rise_times: need 0 <= lower < upper <= 1");

  std::vector<std::size_t> steps;
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (std::abs(reference[i] - reference[i - 1]) > threshold) steps.push_back(i);
  }
  const std::size_t n = time.size();
  // Each sample stands for the interval up to the next: evenly sampled data covering a 20 s
  // hold gives a 20 s hold for the last step too.
  const double end_of_data = time[n - 1] + (time[n - 1] - time[n - 2]);

  std::vector<StepRise> rises;
  for (std::size_t j = 0; j < steps.size(); ++j) {
    StepRise rise;
    rise.index = steps[j];
    const std::size_t last = j + 1 < steps.size() ? steps[j + 1] : n;
    rise.step_time = time[rise.index];
    rise.hold = (last < n ? time[last] : end_of_data) - rise.step_time;
    rise.start = response[rise.index];
    rise.target = reference[rise.index];
    const double size = rise.target - rise.start;
    if (size == 0.0) {
      rise.lower_time = rise.upper_time = rise.step_time;
      rise.rise_time = 0.0;
      rise.reached = true;
    } else {
      const double direction = size > 0.0 ? 1.0 : -1.0;
      rise.lower_time = first_reaching(time, response, rise.index, last,
                                       rise.start + definition.lower * size, direction);
      rise.upper_time = first_reaching(time, response, rise.index, last,
                                       rise.start + definition.upper * size, direction);
      rise.reached = std::isfinite(rise.upper_time);
      rise.rise_time = rise.reached ? rise.upper_time - rise.lower_time : rise.hold;
    }
    rises.push_back(rise);
  }
  return rises;
}

SineFit fit_sine(std::span<const double> time, std::span<const double> values, double frequency,
                 double origin, double begin, double end) {
  const char* what = "fit_sine";
  require_same_length(time.size(), values.size(), what);
  if (!(frequency > 0.0)) throw std::invalid_argument("fit_sine: frequency must be positive");
  const auto first = std::lower_bound(time.begin(), time.end(), begin) - time.begin();
  const auto last = std::lower_bound(time.begin(), time.end(), end) - time.begin();
  const auto count = last - first;
  if (count < 3) throw std::invalid_argument("fit_sine: fewer than three samples in the window");
  const auto window_time =
      time.subspan(static_cast<std::size_t>(first), static_cast<std::size_t>(count));
  const auto window_values =
      values.subspan(static_cast<std::size_t>(first), static_cast<std::size_t>(count));
  require_finite(window_time, what, "time");
  require_finite(window_values, what, "values");

  const double omega = 2.0 * std::numbers::pi * frequency;
  Eigen::MatrixXd design(count, 3);
  Eigen::VectorXd observed(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double angle = omega * (window_time[static_cast<std::size_t>(i)] - origin);
    design(i, 0) = std::sin(angle);
    design(i, 1) = std::cos(angle);
    design(i, 2) = 1.0;
    observed(i) = window_values[static_cast<std::size_t>(i)];
  }
  const Eigen::Vector3d solution = design.colPivHouseholderQr().solve(observed);
  SineFit fit;
  fit.frequency = frequency;
  // a sin + b cos = A sin(angle + phase) with A cos(phase) = a, A sin(phase) = b.
  fit.amplitude = std::hypot(solution(0), solution(1));
  fit.phase = wrap_phase(std::atan2(solution(1), solution(0)));
  fit.offset = solution(2);
  fit.rms_residual = std::sqrt((design * solution - observed).squaredNorm() / double(count));
  fit.samples = static_cast<std::size_t>(count);
  return fit;
}

std::vector<FrequencyResponsePoint> sweep_frequency_response(std::span<const double> time,
                                                             std::span<const double> reference,
                                                             std::span<const double> response,
                                                             const SweepSchedule& schedule,
                                                             double fit_periods) {
  const char* what = "sweep_frequency_response";
  require_same_length(time.size(), reference.size(), what);
  require_same_length(time.size(), response.size(), what);
  require_time(time, what);
  if (!(fit_periods > 0.0 && fit_periods <= schedule.periods))
    throw std::invalid_argument("sweep_frequency_response: need 0 < fit periods <= periods");
  std::vector<FrequencyResponsePoint> points;
  for (std::size_t i = 0; i < schedule.frequencies.size(); ++i) {
    const double f = schedule.frequencies[i];
    const double end = schedule.end_time(i);
    const double begin = end - fit_periods / f;
    FrequencyResponsePoint point;
    point.frequency = f;
    point.reference = fit_sine(time, reference, f, schedule.start_times[i], begin, end);
    point.response = fit_sine(time, response, f, schedule.start_times[i], begin, end);
    if (!(point.reference.amplitude > 0.0))
      throw std::invalid_argument("sweep_frequency_response: the reference does not oscillate");
    point.magnitude = point.response.amplitude / point.reference.amplitude;
    point.magnitude_db = 20.0 * std::log10(point.magnitude);
    const double phase = wrap_phase(point.response.phase - point.reference.phase);
    if (points.empty()) {
      point.phase = phase;
    } else {
      // The representative of `phase` modulo 2 pi nearest to the previous point's phase.
      const double previous = points.back().phase;
      point.phase = previous + wrap_phase(phase - previous);
    }
    points.push_back(point);
  }
  return points;
}

std::optional<double> bandwidth_3db(std::span<const FrequencyResponsePoint> points) {
  const double level = 20.0 * std::log10(1.0 / std::numbers::sqrt2);  // -3.0103 dB
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (!(points[i].frequency > points[i - 1].frequency))
      throw std::invalid_argument("bandwidth_3db: frequencies must increase");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].magnitude_db > level) continue;
    if (i == 0) return std::nullopt;  // below -3 dB from the first frequency on
    const double x0 = std::log10(points[i - 1].frequency), x1 = std::log10(points[i].frequency);
    const double d0 = points[i - 1].magnitude_db, d1 = points[i].magnitude_db;
    return std::pow(10.0, x0 + (level - d0) / (d1 - d0) * (x1 - x0));
  }
  return std::nullopt;
}

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
