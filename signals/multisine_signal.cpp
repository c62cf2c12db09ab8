#include "signals/multisine_signal.h"

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
  const std::size_t count = frequencies_.size();
  if (count > 2) {
    const double spacing =
        (frequencies_.back() - frequencies_.front()) / static_cast<double>(count - 1);
    equally_spaced_ = spacing > 0.0;
    for (std::size_t i = 0; i < count && equally_spaced_; ++i) {
      const double expected = frequencies_.front() + spacing * static_cast<double>(i);
      equally_spaced_ = std::abs(frequencies_[i] - expected) <= 1e-12 * frequencies_.back();
    }
  }
  for (double phase : phases_) {
    cos_phase_.push_back(std::cos(phase));
    sin_phase_.push_back(std::sin(phase));
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
  if (equally_spaced_) {
    // sin(a + k b + phi_k) = Im(e^{i(a + k b)}) cos(phi_k) + Re(e^{i(a + k b)}) sin(phi_k),
    // with e^{i(a + k b)} advanced by one rotation per component.
    const double spacing =
        (frequencies_.back() - frequencies_.front()) / static_cast<double>(frequencies_.size() - 1);
    const double a = 2.0 * std::numbers::pi * frequencies_.front() * time;
    const double b = 2.0 * std::numbers::pi * spacing * time;
    double re = std::cos(a), im = std::sin(a);
    const double step_re = std::cos(b), step_im = std::sin(b);
    double sum = offset_;
    for (std::size_t i = 0; i < amplitudes_.size(); ++i) {
      sum += amplitudes_[i] * (im * cos_phase_[i] + re * sin_phase_[i]);
      const double next_re = re * step_re - im * step_im;
      im = re * step_im + im * step_re;
      re = next_re;
    }
    return sum;
  }
  double sum = offset_;
  for (std::size_t i = 0; i < amplitudes_.size(); ++i) {
    sum += amplitudes_[i] * std::sin(2.0 * std::numbers::pi * frequencies_[i] * time + phases_[i]);
  }
  return sum;
}

double MultisineSignal::slope(double time) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < amplitudes_.size(); ++i) {
    const double omega = 2.0 * std::numbers::pi * frequencies_[i];
    sum += amplitudes_[i] * omega * std::cos(omega * time + phases_[i]);
  }
  return sum;
}

std::pair<double, double> MultisineSignal::range(double begin, double end) const {
  // Every interior extremum is a zero of the slope. Sampling the slope 16 times per period of
  // the fastest component brackets its sign changes; bisection then pins each extremum down
  // to rounding. (Two extrema closer than 1/16 period would be a flat wiggle, whose value
  // differs negligibly from its neighbours'.)
  double low = std::min(value(begin), value(end));
  double high = std::max(value(begin), value(end));
  const double fastest = *std::max_element(frequencies_.begin(), frequencies_.end());
  const auto intervals = static_cast<long>(std::ceil((end - begin) * fastest * 16.0)) + 1;
  const double step = (end - begin) / static_cast<double>(intervals);
  double left = begin, left_slope = slope(begin);
  for (long k = 1; k <= intervals; ++k) {
    const double right = k == intervals ? end : begin + static_cast<double>(k) * step;
    const double right_slope = slope(right);
    if ((left_slope > 0.0) != (right_slope > 0.0)) {
      double a = left, b = right, slope_a = left_slope;
      for (int iteration = 0; iteration < 60 && b - a > 1e-12 * std::max(1.0, std::abs(b));
           ++iteration) {
        const double middle = 0.5 * (a + b);
        const double slope_middle = slope(middle);
        if ((slope_middle > 0.0) == (slope_a > 0.0)) {
          a = middle, slope_a = slope_middle;
        } else {
          b = middle;
        }
      }
      const double extremum = value(0.5 * (a + b));
      low = std::min(low, extremum);
      high = std::max(high, extremum);
    }
    left = right, left_slope = right_slope;
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
  // Peak from the exact range; rms on a grid of 64 samples per fastest period.
  const auto [low, high] = range(0.0, duration);
  const double peak = std::max(high - offset_, offset_ - low);
  const double fastest = *std::max_element(frequencies_.begin(), frequencies_.end());
  const auto samples = static_cast<long>(std::ceil(duration * fastest * 64.0)) + 1;
  double sum_of_squares = 0.0;
  for (long k = 0; k < samples; ++k) {
    const double deviation =
        value(duration * static_cast<double>(k) / static_cast<double>(samples)) - offset_;
    sum_of_squares += deviation * deviation;
  }
  return peak / std::sqrt(sum_of_squares / static_cast<double>(samples));
}

SignalDescription MultisineSignal::describe() const {
  return {"multisine",
          {{"offset", offset_}},
          {{"amplitudes", amplitudes_}, {"frequencies", frequencies_}, {"phases", phases_}},
          {}};
}

}  // namespace tcpmsim
