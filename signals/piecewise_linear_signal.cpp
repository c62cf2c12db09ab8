#include "signals/piecewise_linear_signal.h"

#include <algorithm>
#include <stdexcept>

namespace tcpmsim {

PiecewiseLinearSignal::PiecewiseLinearSignal(std::vector<double> times, std::vector<double> values,
                                             std::string type)
    : times_(std::move(times)), values_(std::move(values)), type_(std::move(type)) {
  if (times_.empty() || times_.size() != values_.size()) {
    throw std::invalid_argument("piecewise linear: need equally many times and values");
  }
  if (!std::is_sorted(times_.begin(), times_.end())) {
    throw std::invalid_argument("piecewise linear: times must increase");
  }
}

double PiecewiseLinearSignal::value(double time) const {
  const auto after = std::upper_bound(times_.begin(), times_.end(), time);
  if (after == times_.begin()) return values_.front();
  if (after == times_.end()) return values_.back();
  const auto k = static_cast<std::size_t>(after - times_.begin());
  const double span = times_[k] - times_[k - 1];
  const double fraction = span > 0 ? (time - times_[k - 1]) / span : 1.0;
  return values_[k - 1] + fraction * (values_[k] - values_[k - 1]);
}

double PiecewiseLinearSignal::next_breakpoint_after(double time) const {
  const auto after = std::upper_bound(times_.begin(), times_.end(), time);
  return after == times_.end() ? kNoBreakpoint : *after;
}

SignalDescription PiecewiseLinearSignal::describe() const {
  return {type_, {}, {{"times", times_}, {"values", values_}}, {}};
}

std::pair<double, double> PiecewiseLinearSignal::range(double begin, double end) const {
  double low = std::min(value(begin), value(end));
  double high = std::max(value(begin), value(end));
  for (std::size_t k = 0; k < times_.size(); ++k) {
    if (times_[k] > begin && times_[k] < end) {
      low = std::min(low, values_[k]);
      high = std::max(high, values_[k]);
    }
  }
  return {low, high};
}

}  // namespace tcpmsim
