#include "controllers/discrete_filters.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tcpmsim {

namespace {
std::size_t window_size(int length, const char* what) {
  if (length < 1) throw std::invalid_argument(std::string(what) + ": length must be at least 1");
  return static_cast<std::size_t>(length);
}
}  // namespace

MovingAverage::MovingAverage(int length) : window_(window_size(length, "moving average")) {}

double MovingAverage::push(double value) {
  window_[static_cast<std::size_t>(next_)] = value;
  next_ = (next_ + 1) % length();
  count_ = std::min(count_ + 1, length());
  // Summed afresh each sample (the window is short) and relative to one member, so a constant
  // input comes out bit-exact and no running sum drifts over a long run.
  const double anchor = window_[0];
  double deviation = 0.0;
  for (int i = 0; i < count_; ++i) deviation += window_[static_cast<std::size_t>(i)] - anchor;
  return anchor + deviation / count_;
}

void MovingAverage::reset() {
  next_ = 0;
  count_ = 0;
}

RunningMedian::RunningMedian(int length)
    : window_(window_size(length, "median")), sorted_(window_.size()) {}

double RunningMedian::push(double value) {
  if (std::isnan(value)) throw std::invalid_argument("median: NaN sample");
  const auto begin = sorted_.begin();
  auto end = begin + count_;
  if (count_ == length()) {
    // Drop the oldest sample from the ordered copy: any element equal to it will do.
    const double oldest = window_[static_cast<std::size_t>(next_)];
    const auto position = std::lower_bound(begin, end, oldest);
    std::copy(position + 1, end, position);
    --end;
  } else {
    ++count_;
  }
  window_[static_cast<std::size_t>(next_)] = value;
  next_ = (next_ + 1) % length();
  const auto position = std::upper_bound(begin, end, value);
  std::copy_backward(position, end, end + 1);
  *position = value;
  const auto middle = static_cast<std::size_t>(count_ / 2);
  if (count_ % 2 == 1) return sorted_[middle];
  return 0.5 * (sorted_[middle - 1] + sorted_[middle]);
}

void RunningMedian::reset() {
  next_ = 0;
  count_ = 0;
}

FirstOrderLowPass::FirstOrderLowPass(double cutoff_frequency, double period)
    : pole_(std::exp(-2.0 * std::numbers::pi * cutoff_frequency * period)), period_(period) {
  if (!(cutoff_frequency > 0.0)) throw std::invalid_argument("low-pass: cut-off must be positive");
  if (!(period > 0.0)) throw std::invalid_argument("low-pass: period must be positive");
}

double FirstOrderLowPass::push(double value) {
  if (!started_ || pole_ == 0.0) {
    output_ = value;
    started_ = true;
    return output_;
  }
  // y += (1 - a)(u - y) is y = a y + (1 - a) u, written so that u == y leaves y bit-exact.
  output_ += (1.0 - pole_) * (value - output_);
  return output_;
}

double FirstOrderLowPass::gain(double frequency) const {
  const double theta = 2.0 * std::numbers::pi * frequency * period_;
  return (1.0 - pole_) / std::sqrt(1.0 - 2.0 * pole_ * std::cos(theta) + pole_ * pole_);
}

}  // namespace tcpmsim
