#include "controllers/signals/multisine_signal.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tcpmsim {

MultisineSignal::MultisineSignal(double offset, std::vector<double> amplitudes,
                                 std::vector<double> frequencies, std::vector<double> phases)
    : offset_(offset),
      amplitudes_(std::move(amplitudes)),
      frequencies_(std::move(frequencies)),
      phases_(std::move(phases)) {
  if (amplitudes_.size() != frequencies_.size() || phases_.size() != frequencies_.size() ||
      frequencies_.empty()) {
    throw std::invalid_argument("multisine: amplitudes, frequencies and phases must match");
  }
}

std::vector<double> MultisineSignal::equally_spaced(int components, double f_low, double f_high) {
  std::vector<double> frequencies(static_cast<std::size_t>(components));
  for (int i = 0; i < components; ++i) {
    frequencies[static_cast<std::size_t>(i)] =
        components == 1 ? f_low : f_low + (f_high - f_low) * i / (components - 1);
  }
  return frequencies;
}

MultisineSignal MultisineSignal::schroeder(int components, double f_low, double f_high,
                                           double phase_offset) {
  std::vector<double> phases(static_cast<std::size_t>(components));
  for (int i = 1; i <= components; ++i) {
    phases[static_cast<std::size_t>(i - 1)] =
        phase_offset - std::numbers::pi * i * i / components;  // (7.12)
  }
  return MultisineSignal(0.0, std::vector<double>(static_cast<std::size_t>(components), 1.0),
                         equally_spaced(components, f_low, f_high), std::move(phases));
}

double MultisineSignal::value(double time) const {
  double sum = offset_;
  for (std::size_t i = 0; i < amplitudes_.size(); ++i) {
    sum += amplitudes_[i] * std::sin(2.0 * std::numbers::pi * frequencies_[i] * time + phases_[i]);
  }
  return sum;
}

namespace {
// Samples fine enough that an extremum is missed by under 1e-5 of the amplitude.
std::vector<double> sample_grid(double begin, double end, double highest_frequency) {
  const double step = 1.0 / (1000.0 * std::max(highest_frequency, 1e-12));
  const auto count = static_cast<std::size_t>(std::ceil((end - begin) / step)) + 1;
  std::vector<double> times(count);
  for (std::size_t k = 0; k < count; ++k) {
    times[k] = std::min(end, begin + static_cast<double>(k) * step);
  }
  return times;
}
}  // namespace

std::pair<double, double> MultisineSignal::range(double begin, double end) const {
  const double highest = *std::max_element(frequencies_.begin(), frequencies_.end());
  double low = value(begin), high = low;
  for (double time : sample_grid(begin, end, highest)) {
    const double v = value(time);
    low = std::min(low, v);
    high = std::max(high, v);
  }
  return {low, high};
}

MultisineSignal MultisineSignal::scaled_to(double low, double high, double duration) const {
  const auto [unscaled_low, unscaled_high] = range(0.0, duration);
  const double gain = (high - low) / (unscaled_high - unscaled_low);
  std::vector<double> amplitudes = amplitudes_;
  for (double& amplitude : amplitudes) amplitude *= gain;
  return MultisineSignal(low + gain * (offset_ - unscaled_low), std::move(amplitudes), frequencies_,
                         phases_);
}

MultisineSignal MultisineSignal::with_equal_amplitudes(double offset, double amplitude) const {
  return MultisineSignal(offset, std::vector<double>(amplitudes_.size(), amplitude), frequencies_,
                         phases_);
}

double MultisineSignal::crest_factor(double duration) const {
  const double highest = *std::max_element(frequencies_.begin(), frequencies_.end());
  double peak = 0.0, sum_of_squares = 0.0;
  const auto times = sample_grid(0.0, duration, highest);
  for (double time : times) {
    const double deviation = value(time) - offset_;
    peak = std::max(peak, std::abs(deviation));
    sum_of_squares += deviation * deviation;
  }
  return peak / std::sqrt(sum_of_squares / static_cast<double>(times.size()));
}

SignalDescription MultisineSignal::describe() const {
  return {"multisine",
          {{"offset", offset_}},
          {{"amplitudes", amplitudes_}, {"frequencies", frequencies_}, {"phases", phases_}},
          {}};
}

}  // namespace tcpmsim
