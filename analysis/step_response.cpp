#include "analysis/step_response.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "analysis/series_checks.h"
#include "analysis/statistics.h"
#include "sim/not_a_number.h"

namespace tcpmsim {

namespace {

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

// A step of the reference: its first sample, the end of its segment (the next step's first
// sample, or the end of the data), its time and how long it holds.
struct StepSegment {
  std::size_t index = 0;
  std::size_t last = 0;
  double time = 0.0;
  double hold = 0.0;
};

// Checks the series as `what` needs them and cuts them where the reference changes by more than
// `threshold`.
std::vector<StepSegment> step_segments(std::span<const double> time,
                                       std::span<const double> reference,
                                       std::span<const double> response, double threshold,
                                       const char* what) {
  require_same_length(time.size(), reference.size(), what);
  require_same_length(time.size(), response.size(), what);
  if (time.size() < 2)
    throw std::invalid_argument(std::string(what) + ": need two samples at least");
  require_time(time, what);
  require_finite(reference, what, "reference");
  require_finite(response, what, "response");
  std::vector<std::size_t> steps;
  for (std::size_t i = 1; i < time.size(); ++i)
    if (std::abs(reference[i] - reference[i - 1]) > threshold) steps.push_back(i);
  const std::size_t n = time.size();
  // Each sample stands for the interval up to the next: evenly sampled data covering a 20 s
  // hold gives a 20 s hold for the last step too.
  const double end_of_data = time[n - 1] + (time[n - 1] - time[n - 2]);
  std::vector<StepSegment> segments;
  for (std::size_t j = 0; j < steps.size(); ++j) {
    const std::size_t last = j + 1 < steps.size() ? steps[j + 1] : n;
    segments.push_back(
        {steps[j], last, time[steps[j]], (last < n ? time[last] : end_of_data) - time[steps[j]]});
  }
  return segments;
}
}  // namespace

std::vector<StepRise> step_rise_times(std::span<const double> time,
                                      std::span<const double> reference,
                                      std::span<const double> response,
                                      const RiseTimeDefinition& definition, double threshold) {
  if (!(definition.lower >= 0.0 && definition.lower < definition.upper && definition.upper <= 1.0))
    throw std::invalid_argument("step_rise_times: need 0 <= lower < upper <= 1");
  std::vector<StepRise> rises;
  for (const StepSegment& segment :
       step_segments(time, reference, response, threshold, "step_rise_times")) {
    StepRise rise;
    rise.index = segment.index;
    const std::size_t last = segment.last;
    rise.step_time = segment.time;
    rise.hold = segment.hold;
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

double overshoot_fraction(std::span<const double> values, double start, double final_value) {
  if (final_value == start || values.empty()) return kNaN;
  const double beyond = final_value > start
                            ? *std::max_element(values.begin(), values.end()) - final_value
                            : final_value - *std::min_element(values.begin(), values.end());
  return std::max(0.0, beyond) / std::abs(final_value - start);
}

namespace {

// The time from `step_time` until the response enters the band |y - y_f| <= band for good
// within samples [first, last): the crossing into the band after the last sample outside it,
// interpolated linearly; NaN if the last sample is outside.
double settling_time(std::span<const double> time, std::span<const double> response,
                     std::size_t first, std::size_t last, double final_value, double band) {
  std::size_t outside = last;  // none
  for (std::size_t i = last; i-- > first;) {
    if (std::abs(response[i] - final_value) > band) {
      outside = i;
      break;
    }
  }
  if (outside == last) return 0.0;
  if (outside + 1 == last) return kNaN;
  const double d0 = std::abs(response[outside] - final_value);
  const double d1 = std::abs(response[outside + 1] - final_value);
  const double fraction = (d0 - band) / (d0 - d1);
  return time[outside] + fraction * (time[outside + 1] - time[outside]) - time[first];
}

}  // namespace

std::vector<StepMetrics> step_metrics(std::span<const double> time,
                                      std::span<const double> reference,
                                      std::span<const double> response, bool same_units,
                                      const StepMetricsOptions& options) {
  const RiseTimeDefinition& rise = options.rise;
  if (!(rise.lower >= 0.0 && rise.lower < rise.upper && rise.upper <= 1.0))
    throw std::invalid_argument("step_metrics: need 0 <= lower < upper <= 1");
  if (!(options.final_fraction > 0.0 && options.final_fraction <= 1.0))
    throw std::invalid_argument("step_metrics: the final fraction must be in (0, 1]");
  if (!(options.settling_band > 0.0))
    throw std::invalid_argument("step_metrics: the settling band must be positive");
  const auto segments = step_segments(time, reference, response, options.threshold, "step_metrics");
  if (segments.size() > time.size() / 4)
    throw std::invalid_argument(
        "step_metrics: the reference changes at " + std::to_string(segments.size()) + " of " +
        std::to_string(time.size()) +
        " samples, which is no step reference (raise the threshold, or analyse its frequency "
        "response)");
  std::vector<StepMetrics> metrics;
  for (const StepSegment& segment : segments) {
    StepMetrics step;
    step.index = segment.index;
    const std::size_t last = segment.last;
    step.step_time = segment.time;
    step.hold = segment.hold;
    step.reference = reference[step.index];
    step.start = response[step.index - 1];  // the response before the step acts
    const std::size_t samples = last - step.index;
    const auto averaged = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::floor(options.final_fraction * double(samples))));
    step.final_value = analysis::mean(response.subspan(last - averaged, averaged));
    const double size = step.final_value - step.start;
    const double direction = size >= 0.0 ? 1.0 : -1.0;
    const double lower =
        first_reaching(time, response, step.index, last, step.start + rise.lower * size, direction);
    const double upper =
        first_reaching(time, response, step.index, last, step.start + rise.upper * size, direction);
    step.rise_time = size == 0.0 ? kNaN : upper - lower;
    const double at_time_constant = first_reaching(
        time, response, step.index, last, step.start + (1.0 - std::exp(-1.0)) * size, direction);
    step.time_constant = size == 0.0 ? kNaN : at_time_constant - time[step.index];
    step.settled = step.hold >= kSettledTimeConstants * step.time_constant;  // NaN: not settled
    step.settling_time = size == 0.0
                             ? kNaN
                             : settling_time(time, response, step.index, last, step.final_value,
                                             options.settling_band * std::abs(size));
    step.overshoot =
        overshoot_fraction(response.subspan(step.index, samples), step.start, step.final_value);
    step.steady_state_error = same_units ? step.reference - step.final_value : kNaN;
    metrics.push_back(step);
  }
  return metrics;
}

}  // namespace tcpmsim
