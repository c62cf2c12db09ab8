#include "signals/piecewise_constant_signal.h"

#include <algorithm>
#include <stdexcept>

namespace tcpmsim {

PiecewiseConstantSignal::PiecewiseConstantSignal(double initial, std::vector<double> times,
                                                 std::vector<double> values,
                                                 SignalDescription description)
    : initial_(initial),
      times_(std::move(times)),
      values_(std::move(values)),
      description_(std::move(description)) {
  if (times_.size() != values_.size())
    throw std::invalid_argument("steps: times and values differ in length");
  if (!std::is_sorted(times_.begin(), times_.end()))
    throw std::invalid_argument("steps: times must increase");
  if (description_.type.empty()) description_.type = "steps";
  description_.parameters.emplace_back("initial", initial_);
  description_.arrays.emplace_back("times", times_);
  description_.arrays.emplace_back("values", values_);
}

double PiecewiseConstantSignal::value(double time) const {
  const auto after = std::upper_bound(times_.begin(), times_.end(), time);
  if (after == times_.begin()) return initial_;
  return values_[static_cast<std::size_t>(after - times_.begin() - 1)];
}

double PiecewiseConstantSignal::next_breakpoint_after(double time) const {
  const auto after = std::upper_bound(times_.begin(), times_.end(), time);
  return after == times_.end() ? kNoBreakpoint : *after;
}

SignalDescription PiecewiseConstantSignal::describe() const {
  return description_;
}

std::pair<double, double> PiecewiseConstantSignal::range(double begin, double end) const {
  double low = value(begin), high = low;
  for (std::size_t k = 0; k < times_.size(); ++k) {
    if (times_[k] > begin && times_[k] <= end) {
      low = std::min(low, values_[k]);
      high = std::max(high, values_[k]);
    }
  }
  return {low, high};
}

}  // namespace tcpmsim
